#include "interpreters/creature/two_bone_ik.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace ontogen {

namespace {
// A unit vector perpendicular to unit axis, as close to `towards` as possible.
glm::dvec3 perpendicular(const glm::dvec3& axis, const glm::dvec3& towards) {
  glm::dvec3 p = towards - glm::dot(towards, axis) * axis;
  if (glm::length(p) < 1e-9) {
    const glm::dvec3 other = std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    p = other - glm::dot(other, axis) * axis;
  }
  return glm::normalize(p);
}
}  // namespace

TwoBoneLeg solveTwoBone(const glm::dvec3& hip, const glm::dvec3& target, double upper, double lower,
                        const glm::dvec3& pole) {
  TwoBoneLeg leg;
  glm::dvec3 toTarget = target - hip;
  double distance = glm::length(toTarget);
  const glm::dvec3 axis = distance > 1e-12 ? toTarget / distance : perpendicular(glm::dvec3(0, -1, 0), -pole);
  // Reach: a hair inside the straight and the folded leg, so the angles stay defined.
  const double longest = (upper + lower) * (1 - 1e-9);
  const double shortest = std::abs(upper - lower) * (1 + 1e-9) + 1e-12;
  if (distance > longest || distance < shortest) leg.reached = false;
  distance = std::clamp(distance, shortest, longest);
  const glm::dvec3 side = perpendicular(axis, pole);
  // Law of cosines: the upper limb's angle from the hip-target line, and the knee's.
  const double cosHip = std::clamp((upper * upper + distance * distance - lower * lower) / (2 * upper * distance), -1.0, 1.0);
  const double hipAngle = std::acos(cosHip);
  const double cosInner = std::clamp((upper * upper + lower * lower - distance * distance) / (2 * upper * lower), -1.0, 1.0);
  leg.kneeAngle = 3.141592653589793 - std::acos(cosInner);
  leg.upperDirection = std::cos(hipAngle) * axis + std::sin(hipAngle) * side;
  const glm::dvec3 knee = hip + upper * leg.upperDirection;
  const glm::dvec3 foot = hip + distance * axis;
  leg.lowerDirection = glm::normalize(foot - knee);
  leg.kneeSide = perpendicular(leg.upperDirection, side);
  return leg;
}

}  // namespace ontogen
