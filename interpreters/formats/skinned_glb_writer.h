#pragma once
// glTF 2.0 binary of an articulated run: one skin over the skeleton the frames share
// (interpreters/scene.h, Skeleton).
//
// - A node per joint, keyed by its id and named after its cell, in the skeleton's
//   hierarchy; its rest transform is the pose of the first frame (the bind pose), and
//   the skin's inverse bind matrices invert that pose.
// - One mesh of the skinned triangles as the first frame drew them, with JOINTS_0 and
//   WEIGHTS_0: each vertex carries the joint its limb moves with, weight 1 (a limb is
//   rigid), the other three slots 0. Geometry outside the skin (other sets' drawing) is
//   written once, as the first frame drew it, unanimated.
// - One animation, "walk": a rotation channel per joint and a translation channel per
//   root (and per joint whose offset from its parent is not rigid), sampled at every
//   frame's time, linear. A run whose drivers are periodic over [from, until] loops
//   without a jump in its joints.
// A joint that is missing from a later frame holds its last pose there; joints that
// appear after the first frame are not in the skin (ignoredJoints() counts them).

#include <cstdint>
#include <ostream>
#include <unordered_map>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "interpreters/scene.h"

namespace ontogen {

class SkinnedGlbWriter {
 public:
  /// Adds a frame; the first one fixes the skeleton and the skin.
  void addFrame(const Scene& scene);
  std::size_t frameCount() const { return times_.size(); }
  /// Joints of later frames the first one did not have.
  uint64_t ignoredJoints() const { return ignored_; }
  void clear();
  /// Writes the file. Stream errors are left in out's state.
  void write(std::ostream& out) const;

 private:
  struct Local {
    glm::dvec3 translation{0.0};
    glm::dquat rotation{1, 0, 0, 0};
  };
  Scene bind_;                        // the first frame
  std::unordered_map<uint64_t, int> index_;  // joint id -> index in bind_'s skeleton
  std::vector<double> times_;
  std::vector<std::vector<Local>> poses_;  // per frame, per joint
  uint64_t ignored_ = 0;
};

}  // namespace ontogen
