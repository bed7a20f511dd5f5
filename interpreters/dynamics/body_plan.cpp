#include "interpreters/dynamics/body_plan.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace ontogen {

namespace {
// Rotation by radians about a unit axis (Rodrigues), as a matrix.
glm::dmat3 rotation(const glm::dvec3& axis, double radians) {
  const double c = std::cos(radians), s = std::sin(radians), t = 1 - c;
  const double x = axis.x, y = axis.y, z = axis.z;
  // glm is column-major: each line below is a column.
  return glm::dmat3(glm::dvec3(t * x * x + c, t * x * y + s * z, t * x * z - s * y),
                    glm::dvec3(t * x * y - s * z, t * y * y + c, t * y * z + s * x),
                    glm::dvec3(t * x * z + s * y, t * y * z - s * x, t * z * z + c));
}
}  // namespace

int hingeCount(JointKind kind) {
  switch (kind) {
    case JointKind::Bend: return 2;
    case JointKind::Hinge:
    case JointKind::Knee: return 1;
    case JointKind::Hip: return 3;
    case JointKind::Free:
    case JointKind::Weld: return 0;
  }
  return 0;
}

glm::dvec3 hingeAxis(JointKind kind, int index) {
  switch (kind) {
    case JointKind::Bend: return index == 0 ? glm::dvec3(0, 0, 1) : glm::dvec3(0, -1, 0);
    case JointKind::Hinge: return {0, -1, 0};
    case JointKind::Knee: return {0, 1, 0};
    case JointKind::Hip:
      return index == 0 ? glm::dvec3(0, 0, 1) : index == 1 ? glm::dvec3(0, -1, 0) : glm::dvec3(1, 0, 0);
    case JointKind::Free:
    case JointKind::Weld: break;
  }
  return {1, 0, 0};
}

std::array<double, 3> hingeAngles(JointKind kind, const glm::dmat3& base, const glm::dmat3& orientation) {
  const glm::dmat3 delta = glm::transpose(base) * orientation;  // the joint's turn in its base frame
  const glm::dvec3 h = delta[0];
  std::array<double, 3> angles{0, 0, 0};
  switch (kind) {
    case JointKind::Hinge: angles[0] = std::atan2(h.z, h.x); break;
    case JointKind::Knee: angles[0] = std::atan2(-h.z, h.x); break;
    case JointKind::Bend:
    case JointKind::Hip: {
      angles[0] = std::atan2(h.y, h.x);
      angles[1] = std::atan2(h.z, std::hypot(h.x, h.y));
      if (kind == JointKind::Hip) {
        // What the swing and lift leave is a roll about H.
        const glm::dmat3 rest = glm::transpose(turned(JointKind::Bend, glm::dmat3(1.0), angles)) * delta;
        angles[2] = std::atan2(rest[1].z, rest[1].y);
      }
      break;
    }
    case JointKind::Free:
    case JointKind::Weld: break;
  }
  return angles;
}

glm::dmat3 turned(JointKind kind, const glm::dmat3& base, const std::array<double, 3>& angles) {
  glm::dmat3 frame = base;
  for (int i = 0; i < hingeCount(kind); ++i) frame = frame * rotation(hingeAxis(kind, i), angles[i]);
  return frame;
}

bool BodyPlan::sameStructure(const BodyPlan& other) const {
  if (bodies.size() != other.bodies.size()) return false;
  for (std::size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].id != other.bodies[i].id || bodies[i].parent != other.bodies[i].parent ||
        bodies[i].kind != other.bodies[i].kind)
      return false;
  return true;
}

}  // namespace ontogen
