#include "interpreters/dynamics/mujoco_model.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <mutex>

namespace ontogen {

namespace {

// MuJoCo prints its warnings and writes MUJOCO_LOG.TXT unless a handler takes them; the
// library never prints, and the data counts them anyway.
void dropWarning(const char*) {}

// MuJoCo's default error handler exits the process; an exception leaves the choice to
// the caller (the data it was stepping is then to be dropped).
void throwError(const char* message) { throw MujocoError(std::string("MuJoCo failed: ") + message); }

void installHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_warning = dropWarning;
    mju_user_error = throwError;
  });
}

struct VfsDeleter {
  void operator()(mjVFS* vfs) const {
    mj_deleteVFS(vfs);
    delete vfs;
  }
};

}  // namespace

MujocoModel::MujocoModel(std::string_view mjcf) {
  installHandlers();
  // mjVFS holds its file table inline (megabytes): on the heap, not the stack.
  std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  const char* file = "model.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), file, static_cast<int>(mjcf.size())) != 0)
    throw MujocoError("MuJoCo's file system has no room for the model");
  const int index = mj_findFileVFS(vfs.get(), file);
  std::memcpy(vfs->filedata[index], mjcf.data(), mjcf.size());
  char error[1000] = "";
  model_ = mj_loadXML(file, vfs.get(), error, sizeof error);
  if (!model_) throw MujocoError(std::string("MuJoCo did not compile the model: ") + error);
  data_ = mj_makeData(model_);
  if (!data_) {
    mj_deleteModel(model_);
    throw MujocoError("MuJoCo could not allocate the model's data");
  }
}

mjData* MujocoModel::scratch() {
  if (!scratch_) scratch_ = mj_makeData(model_);
  if (!scratch_) throw MujocoError("MuJoCo could not allocate the model's data");
  return scratch_;
}

void MujocoModel::step() {
  constexpr std::array kBad{mjWARN_BADQPOS, mjWARN_BADQVEL, mjWARN_BADQACC};
  constexpr std::array kFull{mjWARN_CONTACTFULL, mjWARN_CNSTRFULL};
  for (const mjtWarning warning : kBad) data_->warning[warning].number = 0;
  for (const mjtWarning warning : kFull) data_->warning[warning].number = 0;
  mj_step(model_, data_);
  lastStepReset_ = std::any_of(kBad.begin(), kBad.end(), [&](mjtWarning w) { return data_->warning[w].number > 0; });
  lastStepOutOfRoom_ =
      std::any_of(kFull.begin(), kFull.end(), [&](mjtWarning w) { return data_->warning[w].number > 0; });
}

MujocoModel::~MujocoModel() {
  if (scratch_) mj_deleteData(scratch_);
  if (data_) mj_deleteData(data_);
  if (model_) mj_deleteModel(model_);
}

}  // namespace ontogen
