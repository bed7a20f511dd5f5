#pragma once
// Two-bone inverse kinematics: a hip, an upper and a lower limb, a foot target. The leg
// lies in the plane through the hip, the target and the pole direction; the knee bends
// towards the pole. A target out of reach is moved along the hip-target line to the
// nearest reachable point (the leg then stretches, or folds, as far as it can).

#include <glm/vec3.hpp>

namespace ontogen {

struct TwoBoneLeg {
  glm::dvec3 upperDirection{1.0, 0.0, 0.0};  ///< unit, from the hip to the knee
  glm::dvec3 lowerDirection{1.0, 0.0, 0.0};  ///< unit, from the knee to the foot
  glm::dvec3 kneeSide{0.0, 0.0, 1.0};  ///< unit, across the upper limb towards the knee's side of the hip-foot line
  double kneeAngle = 0;                ///< radians, 0: straight; the lower limb turns away from kneeSide
  bool reached = true;                 ///< false when the target was moved into reach
};

/// Solves the leg for `target`. pole need not be unit or perpendicular; when it is
/// parallel to the hip-target line any perpendicular is used. upper and lower > 0.
TwoBoneLeg solveTwoBone(const glm::dvec3& hip, const glm::dvec3& target, double upper, double lower,
                        const glm::dvec3& pole);

}  // namespace ontogen
