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
// - A camera (gltf::addCamera; no light) framing the body as bound,
//   carried along by its root over the frames.
// The skeleton is the one of the frame with the most joints (the first such: a body that
// grows is written grown). A joint that a frame lacks has scale 0 there (and so has
// everything it carries), with a STEP scale channel: parts of the body appear as they
// grow. Joints that frame lacks are counted (ignoredJoints()).

#include <cstdint>
#include <ostream>
#include <unordered_map>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "interpreters/scene.h"

namespace ontogen {

class SkinnedGlbWriter {
 public:
  /// Adds a frame with its time.
  void addFrame(const Scene& scene);
  std::size_t frameCount() const { return frames_.size(); }
  /// Joints of frames that the skeleton written does not have.
  uint64_t ignoredJoints() const;
  void clear();
  /// Writes the file. Stream errors are left in out's state.
  void write(std::ostream& out) const;

 private:
  struct Pose {
    glm::dvec3 position{0.0};
    glm::dmat3 rotation{1.0};
  };
  struct Frame {
    double time = 0;
    std::unordered_map<uint64_t, Pose> joints;  // by id
  };
  Scene bind_;  // the frame with the most joints: its skeleton, its limbs
  std::vector<Frame> frames_;
};

}  // namespace ontogen
