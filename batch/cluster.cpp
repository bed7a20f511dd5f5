#include "batch/cluster.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#ifdef ONTOGEN_HAVE_MPI
#include <mpi.h>
#endif

namespace ontogen {

namespace {
// The size of the job as its launcher announces it: Open MPI's mpirun, then the PMI
// variable of Slurm's srun (--mpi=pmi2) and MPICH's launchers. 0: no launcher. (Not
// SLURM_NTASKS: a batch script's own shell has it too, outside srun.)
int launchedSize() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    if (const char* value = std::getenv(name); value && *value) return std::atoi(value);
  }
  // PMIx launchers may name only the rank.
  if (std::getenv("PMIX_RANK") || std::getenv("PMI_RANK")) return 1;
  return 0;
}
}  // namespace

bool Cluster::built() {
#ifdef ONTOGEN_HAVE_MPI
  return true;
#else
  return false;
#endif
}

Cluster::Cluster(Join join) {
  const int launched = join == Join::Alone ? 0 : launchedSize();
#ifdef ONTOGEN_HAVE_MPI
  // Without a launcher MPI_Init would start a singleton job (an Open MPI daemon): not
  // worth its second for a run on one machine.
  if (launched == 0) return;
  int provided = 0;
  if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
    throw std::runtime_error("MPI could not start (MPI_Init_thread failed)");
  joined_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
#else
  if (launched > 1)
    throw std::runtime_error("this ontogen was built without MPI (ONTOGEN_MPI=OFF) but started as one of " +
                             std::to_string(launched) +
                             " processes by an MPI launcher; each would run the whole sweep into the same folder. "
                             "Run it without mpirun, or build it with Open MPI (libopenmpi-dev)");
#endif
}

Cluster::~Cluster() {
#ifdef ONTOGEN_HAVE_MPI
  if (joined_) MPI_Finalize();
#endif
}

void Cluster::send([[maybe_unused]] int to, [[maybe_unused]] ClusterTag tag, [[maybe_unused]] const std::string& text) {
#ifdef ONTOGEN_HAVE_MPI
  if (!joined_) return;
  MPI_Send(text.data(), static_cast<int>(text.size()), MPI_CHAR, to, static_cast<int>(tag), MPI_COMM_WORLD);
#endif
}

std::optional<ClusterMessage> Cluster::poll() {
#ifdef ONTOGEN_HAVE_MPI
  if (!joined_) return std::nullopt;
  int flag = 0;
  MPI_Status status;
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
  if (!flag) return std::nullopt;
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  ClusterMessage message;
  message.from = status.MPI_SOURCE;
  message.tag = static_cast<ClusterTag>(status.MPI_TAG);
  message.text.resize(static_cast<size_t>(count));
  MPI_Recv(message.text.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  return message;
#else
  return std::nullopt;
#endif
}

std::string Cluster::broadcast(std::string text) {
#ifdef ONTOGEN_HAVE_MPI
  if (!joined_ || size_ == 1) return text;
  // The length first (as 64 bits: a table may pass 2 GiB only in pieces, see below), then
  // the bytes in pieces an int counts.
  unsigned long long length = text.size();
  MPI_Bcast(&length, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  text.resize(static_cast<size_t>(length));
  constexpr size_t kPiece = size_t{1} << 30;
  for (size_t at = 0; at < text.size(); at += kPiece) {
    const int count = static_cast<int>(std::min(kPiece, text.size() - at));
    MPI_Bcast(text.data() + at, count, MPI_CHAR, 0, MPI_COMM_WORLD);
  }
#endif
  return text;
}

void Cluster::barrier() {
#ifdef ONTOGEN_HAVE_MPI
  if (joined_) MPI_Barrier(MPI_COMM_WORLD);
#endif
}

}  // namespace ontogen
