#pragma once
// A MuJoCo model and its data, compiled from MJCF text in memory (MuJoCo's virtual file
// system, so nothing touches the disk), owned together. MuJoCo's warnings are kept in
// its data (mjData::warning) and never printed: the first use installs a handler that
// drops its messages. MuJoCo's errors (it would end the process) are thrown as MujocoError.

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
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
  /// Steps once with the controls as they are, and notes what MuJoCo said of the step. Its
  /// warning counts are cleared first: MuJoCo clears them itself as it resets a data, so
  /// only a count of this step alone tells a reset or a lack of room.
  void step();
  /// The last step() found the state bad (not finite, or past 1e10: MuJoCo's bound on
  /// positions, speeds and accelerations) and MuJoCo reset the data to the model's first
  /// pose at time 0 before integrating it.
  bool lastStepReset() const { return lastStepReset_; }
  /// The last step() found more contacts or constraint rows than the model has room for
  /// (MuJoCo dropped those past it).
  bool lastStepOutOfRoom() const { return lastStepOutOfRoom_; }

 private:
  mjModel* model_ = nullptr;
  mjData* data_ = nullptr;
  mjData* scratch_ = nullptr;
  bool lastStepReset_ = false;
  bool lastStepOutOfRoom_ = false;
};

/// A MuJoCo body's frame in the world (columns H, L, U), from its xmat (row-major).
inline glm::dmat3 frameOf(const mjData* d, int body) {
  const mjtNum* x = d->xmat + 9 * body;
  return glm::dmat3(glm::dvec3(x[0], x[3], x[6]), glm::dvec3(x[1], x[4], x[7]), glm::dvec3(x[2], x[5], x[8]));
}

/// A MuJoCo body's place in the world, from its xpos.
inline glm::dvec3 positionOf(const mjData* d, int body) {
  const mjtNum* x = d->xpos + 3 * body;
  return {x[0], x[1], x[2]};
}

}  // namespace ontogen
