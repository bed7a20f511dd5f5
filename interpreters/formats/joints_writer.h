#pragma once
// The joint tracks of a run as data: DIR/<model>.joints.json (`--format joints`).
//
//   {"up": [0, 1, 0], "ground": H,
//    "joints": [{"id": ID, "name": "Hip.7", "parent": INDEX or -1, "foot": true|false,
//                "side": "left"|"right"|null, "segment": M or null}, ...],
//    "frames": [{"t": T, "positions": [[x, y, z], ...]}, ...]}
//
// Frames a simulation posed (the dynamics set) also give "contacts": [INDEX, ...], the
// joints (indices in "joints", ascending) whose limbs touch the ground.
//
// The joints are those of the frame with the most joints (the first such: a body that
// grows is listed grown), parents first; each frame gives every joint's world position in
// that order, null for a joint the frame lacks (it had not grown yet). Ids are
// the joint cells' stable ids, written as numbers below 2^53 as JSON readers keep them
// exactly (their low 53 bits, as `word --json` writes ids).

#include <ostream>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "interpreters/scene.h"

namespace ontogen {

class JointTrackWriter {
 public:
  explicit JointTrackWriter(double ground = 0) : ground_(ground) {}
  void addFrame(const Scene& scene);
  std::size_t frameCount() const { return frames_.size(); }
  void clear();
  void write(std::ostream& out) const;

 private:
  struct Frame {
    double time = 0;
    std::unordered_map<uint64_t, glm::dvec3> positions;  // by joint id
    bool simulated = false;
    std::vector<uint64_t> contacts;  // joint ids
  };
  double ground_ = 0;
  std::vector<SceneJoint> joints_;  // of the frame with the most
  std::vector<Frame> frames_;
};

}  // namespace ontogen
