#pragma once
// A MuJoCo model and its data, compiled from MJCF text in memory (MuJoCo's virtual file
// system, so nothing touches the disk), owned together. MuJoCo's warnings are kept in
// its data (mjData::warning) and never printed: the first use installs a handler that
// drops its messages. MuJoCo's errors (it would end the process) are thrown as MujocoError.

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include <mujoco/mujoco.h>

namespace ontogen {

/// MuJoCo refused a model: the message is its compiler's.
struct MujocoError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class MujocoModel {
 public:
  /// Compiles the MJCF text; throws MujocoError with MuJoCo's message when it cannot.
  explicit MujocoModel(std::string_view mjcf);
  MujocoModel(const MujocoModel&) = delete;
  MujocoModel& operator=(const MujocoModel&) = delete;
  ~MujocoModel();

  mjModel* model() const { return model_; }
  mjData* data() const { return data_; }
  /// A second data of the model, for states read beside the simulation's own; made on
  /// first use (MuJoCo clears all of a data's memory as it makes one).
  mjData* scratch();
  /// Steps once with the controls as they are.
  void step() { mj_step(model_, data_); }
  /// Times MuJoCo found the simulation unstable and reset it (mjWARN_BADQACC).
  int instabilities() const { return data_->warning[mjWARN_BADQACC].number; }

 private:
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  mjData* scratch_ = nullptr;
};

}  // namespace ontogen
