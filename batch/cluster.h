#pragma once
// The processes of one sweep across machines: under `mpirun -n K` (or Slurm's srun) K
// copies of ontogen start, each a rank; rank 0 writes every output and the others send
// it their rows. Without an MPI launcher, or in a build without MPI (ONTOGEN_MPI off),
// there is one rank and nothing is sent. Only the thread that made the Cluster calls it
// (MPI_THREAD_FUNNELED): the workers hand their rows to that thread.

#include <optional>
#include <string>

namespace ontogen {

/// What one rank sends another.
enum class ClusterTag : int {
  Row = 1,   ///< a finished row, as a journal line, to rank 0
  Done = 2,  ///< a rank has sent all its rows
  Stop = 3,  ///< from rank 0: Ctrl-C, start no further variant
};

struct ClusterMessage {
  int from = 0;
  ClusterTag tag = ClusterTag::Row;
  std::string text;
};

class Cluster {
 public:
  /// Whether a Cluster joins the MPI job its launcher started.
  enum class Join {
    FromLauncher,  ///< when an MPI launcher started this process (its environment says so)
    Alone,         ///< never: one rank (a host program that runs a sweep on this machine)
  };
  /// Joins the MPI job when `join` says so and an MPI launcher started this process;
  /// else one rank. Throws std::runtime_error when launched as one of several ranks by a
  /// build without MPI, which would have every rank run the whole sweep.
  explicit Cluster(Join join = Join::FromLauncher);
  ~Cluster();
  Cluster(const Cluster&) = delete;
  Cluster& operator=(const Cluster&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool leader() const { return rank_ == 0; }

  /// Sends `text` to rank `to` (blocking until MPI has taken it).
  void send(int to, ClusterTag tag, const std::string& text);
  /// A message sent to this rank, if one has arrived; never waits.
  std::optional<ClusterMessage> poll();
  /// Rank 0's `text` on every rank.
  std::string broadcast(std::string text);
  /// Waits for every rank.
  void barrier();

  /// Whether this build can run across ranks.
  static bool built();

 private:
  int rank_ = 0;
  int size_ = 1;
  bool joined_ = false;  // MPI was initialised here
};

}  // namespace ontogen
