#include "interpreters/geometry/environment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace ontogen {

namespace {

// Slack for "on the plane": a segment ending this far past a plane has not crossed it.
constexpr double kSlack = 1e-9;

bool segmentHitsSphere(const glm::dvec3& a, const glm::dvec3& b, const SphereObstacle& s) {
  glm::dvec3 d = b - a;
  double len2 = glm::dot(d, d);
  double t = len2 > 0 ? std::clamp(glm::dot(s.centre - a, d) / len2, 0.0, 1.0) : 0.0;
  glm::dvec3 closest = a + d * t;
  return glm::length(closest - s.centre) < s.radius - kSlack;
}

bool segmentHitsBox(const glm::dvec3& a, const glm::dvec3& b, const BoxObstacle& box) {
  // Slab test on the open box (touching a face is allowed).
  double t0 = 0, t1 = 1;
  glm::dvec3 d = b - a;
  for (int i = 0; i < 3; ++i) {
    double lo = box.min[i] + kSlack, hi = box.max[i] - kSlack;
    if (std::abs(d[i]) < 1e-15) {
      if (a[i] <= lo || a[i] >= hi) return false;
      continue;
    }
    double u0 = (lo - a[i]) / d[i], u1 = (hi - a[i]) / d[i];
    if (u0 > u1) std::swap(u0, u1);
    t0 = std::max(t0, u0);
    t1 = std::min(t1, u1);
    if (t0 >= t1) return false;
  }
  return true;
}

bool insideBox(const glm::dvec3& p, const BoxObstacle& box) {
  for (int i = 0; i < 3; ++i) {
    if (p[i] <= box.min[i] || p[i] >= box.max[i]) return false;
  }
  return true;
}

bool nearZero(const glm::dvec3& v) { return glm::dot(v, v) < 1e-18; }

}  // namespace

glm::dvec3 rotateTowards(const glm::dvec3& heading, const glm::dvec3& target, double radians) {
  glm::dvec3 axis = glm::cross(heading, target);
  double size = glm::length(axis);
  if (size < 1e-12 || radians == 0) return heading;
  axis /= size;
  // Never turn past the target (or, for a negative angle, past its opposite).
  double between = std::atan2(size, glm::dot(heading, target));
  radians = std::clamp(radians, -(std::numbers::pi - between), between);
  return glm::normalize(heading * std::cos(radians) + glm::cross(axis, heading) * std::sin(radians));
}

bool Environment::empty() const {
  return !ceiling && !ground && spheres.empty() && boxes.empty() && influences.empty() &&
         std::isinf(maxLength) && std::isinf(maxDepth);
}

glm::dvec3 Environment::bend(const glm::dvec3& position, const glm::dvec3& heading) const {
  glm::dvec3 h = heading;
  for (const PointInfluence& influence : influences) {
    glm::dvec3 towards = influence.position - position;
    double distance = glm::length(towards);
    if (distance < 1e-12) continue;
    towards /= distance;
    double ratio = distance / influence.falloff;
    double weight = influence.strength / (1.0 + ratio * ratio);
    h = rotateTowards(h, towards, weight * glm::length(glm::cross(h, towards)));
  }
  return h;
}

bool Environment::blocks(const glm::dvec3& start, const glm::dvec3& end) const {
  if (ceiling && start.y <= *ceiling + kSlack && end.y > *ceiling + kSlack) return true;
  if (ground && start.y >= *ground - kSlack && end.y < *ground - kSlack) return true;
  for (const SphereObstacle& s : spheres) {
    if (glm::length(start - s.centre) >= s.radius && segmentHitsSphere(start, end, s)) return true;
  }
  for (const BoxObstacle& b : boxes) {
    if (!insideBox(start, b) && segmentHitsBox(start, end, b)) return true;
  }
  return false;
}

std::optional<glm::dvec3> Environment::redirect(const glm::dvec3& start, const glm::dvec3& heading, double length,
                                                const glm::dvec3& side, const glm::dvec3& up) const {
  glm::dvec3 h = heading;
  auto flatten = [&](const glm::dvec3& normal) {
    glm::dvec3 along = h - normal * glm::dot(h, normal);
    if (nearZero(along)) along = side - normal * glm::dot(side, normal);
    if (nearZero(along)) along = up - normal * glm::dot(up, normal);
    h = glm::normalize(along);
  };
  // Planes first: they bound everything else.
  if (ceiling && start.y <= *ceiling + kSlack && start.y + h.y * length > *ceiling + kSlack) flatten({0, 1, 0});
  if (ground && start.y >= *ground - kSlack && start.y + h.y * length < *ground - kSlack) flatten({0, 1, 0});
  for (const SphereObstacle& s : spheres) {
    if (glm::length(start - s.centre) < s.radius) continue;  // started inside: cannot help
    if (segmentHitsSphere(start, start + h * length, s)) flatten(glm::normalize(start - s.centre));
  }
  for (const BoxObstacle& b : boxes) {
    if (insideBox(start, b)) continue;
    for (int axis = 0; axis < 3 && segmentHitsBox(start, start + h * length, b); ++axis) {
      // Remove the motion towards the box along each axis where the start is outside it.
      glm::dvec3 normal(0.0);
      if (start[axis] <= b.min[axis] && h[axis] > 0) normal[axis] = 1;
      if (start[axis] >= b.max[axis] && h[axis] < 0) normal[axis] = 1;
      if (normal[axis] != 0) flatten(normal);
    }
  }
  if (blocks(start, start + h * length)) return std::nullopt;
  return h;
}

}  // namespace ontogen
