#pragma once
// The developed body as rigid bodies: one per joint of the creature set's skeleton, in
// the skeleton's order (parents first), each with the joint that moves it against its
// parent, the ranges of that joint's degrees of freedom and the limbs it carries. Places
// are world coordinates of the kinematic pose the word was drawn in.
//
// A joint's frame before its own rotation is its `base` (the turtle's frame as the joint
// command started); its degrees of freedom turn the base, one after the other about
// axes of the frame the turns before them left (H, L, U are x, y, z):
//   bend:  yaw about U, then pitch about -L (H towards U)
//   hinge: about -L
//   hip:   swing about U, lift about -L, then roll about H
//   knee:  about L (H away from U)
// which is how the creature set turns them, so a joint's angles are its drivers' values.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace ontogen {

/// How a body moves against its parent.
enum class JointKind {
  Free,   ///< a creature's root (gait): six degrees of freedom in the world
  Bend,   ///< two hinges: yaw, pitch
  Hinge,  ///< one hinge
  Hip,    ///< three hinges: swing, lift, roll
  Knee,   ///< one hinge
  Weld,   ///< none: a foot, fixed to its parent
};

/// Hinges of a kind (0 for Free and Weld).
int hingeCount(JointKind kind);
/// The unit axis of hinge `index` in the frame the hinges before it left.
glm::dvec3 hingeAxis(JointKind kind, int index);
/// The hinges' angles that turn `base` into `orientation` (radians; unused entries 0).
std::array<double, 3> hingeAngles(JointKind kind, const glm::dmat3& base, const glm::dmat3& orientation);
/// The frame the hinges' angles turn `base` into.
glm::dmat3 turned(JointKind kind, const glm::dmat3& base, const std::array<double, 3>& angles);

/// A degree of freedom's range, radians.
struct HingeRange {
  bool set = false;
  double lo = 0, hi = 0;
};

/// A limb a body carries: a capsule from start to end (world, the kinematic pose).
struct PlanLimb {
  glm::dvec3 start{0.0}, end{0.0};
  double radius = 0;  ///< model units, > 0
  double density = 0;      ///< mass per cubic model unit; 0: the model's
  bool cylinder = false;   ///< a flat-ended cylinder (a rod's segment), else a capsule
  bool touches = true;     ///< collides with the ground
};

struct PlanBody {
  uint64_t id = 0;       ///< the joint's stable id
  int parent = -1;       ///< index in BodyPlan::bodies; -1: a root
  JointKind kind = JointKind::Weld;
  glm::dvec3 position{0.0};     ///< of the joint, world
  glm::dmat3 base{1.0};         ///< world frame before the joint's rotation, columns H, L, U
  glm::dmat3 orientation{1.0};  ///< world frame after it
  std::array<HingeRange, 3> ranges{};
  std::vector<PlanLimb> limbs;
  double spring = 0;    ///< each hinge's rotational spring, torque per radian, its rest at angle 0; 0: none
  double damping = -1;  ///< each hinge's damping, torque per radian a second; < 0: the servos' kd
  bool driven = true;   ///< its hinges have position servos
};

struct BodyPlan {
  std::vector<PlanBody> bodies;
  /// True when both have the same bodies (ids, parents and kinds) in the same order.
  bool sameStructure(const BodyPlan& other) const;
};

}  // namespace ontogen
