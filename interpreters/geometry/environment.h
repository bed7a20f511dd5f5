#pragma once
// The environment the turtle grows in (paper 004, section VI), declared by turtle
// commands (ceiling, ground, obstaclesphere, obstaclebox, attractor, repeller, maxlength,
// maxdepth) that a model places before its growth, typically in the axiom.
//
// Before each F:
//  1. attractors and repellers bend the heading (each by strength |H x D| / (1 + (d /
//     falloff)^2) radians, towards or away from the point);
//  2. a segment that would cross the ceiling or the ground is turned into the plane,
//     keeping its length (paper 004: "shifted to a legal position while retaining the
//     same length"); one that meets the plane head-on goes along the turtle's L, or U;
//  3. a segment that would enter an obstacle is turned tangent to it (spheres: across the
//     radius through the start; boxes: the velocity towards the face is removed, axis by
//     axis); if it still enters, it is not drawn and the turtle does not move.
// The world is y-up, as the turtle's $ takes it.

#include <limits>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

namespace ontogen {

/// heading turned towards the unit vector target by radians (negative: away), never past
/// it; the turn happens in the plane of the two. Unit in, unit out.
glm::dvec3 rotateTowards(const glm::dvec3& heading, const glm::dvec3& target, double radians);

/// A point that bends growth; strength > 0 attracts, < 0 repels.
struct PointInfluence {
  glm::dvec3 position{0.0};
  double strength = 0;  ///< radians of bend per unit of |H x D| next to the point
  double falloff = 1;   ///< model units; the bend halves at this distance
};

struct SphereObstacle {
  glm::dvec3 centre{0.0};
  double radius = 0;
};

struct BoxObstacle {
  glm::dvec3 min{0.0};
  glm::dvec3 max{0.0};
};

/// Everything growth must respect; empty by default.
struct Environment {
  std::optional<double> ceiling;  ///< y of the ceiling plane
  std::optional<double> ground;   ///< y of the ground plane
  std::vector<SphereObstacle> spheres;
  std::vector<BoxObstacle> boxes;
  std::vector<PointInfluence> influences;
  double maxLength = std::numeric_limits<double>::infinity();  ///< resource limit, model units
  double maxDepth = std::numeric_limits<double>::infinity();   ///< generation limit, segments

  /// True when nothing is declared (the turtle then skips all checks).
  bool empty() const;

  /// The heading after attractors and repellers at position (unit in, unit out).
  glm::dvec3 bend(const glm::dvec3& position, const glm::dvec3& heading) const;

  /// The heading a segment of length from start along heading must take to respect the
  /// planes and obstacles, or nullopt when none does. side and up are fallbacks for a
  /// head-on hit. Unit in, unit out.
  std::optional<glm::dvec3> redirect(const glm::dvec3& start, const glm::dvec3& heading, double length,
                                     const glm::dvec3& side, const glm::dvec3& up) const;

  /// True when the segment start -> end enters an obstacle or crosses a plane.
  bool blocks(const glm::dvec3& start, const glm::dvec3& end) const;
};

}  // namespace ontogen
