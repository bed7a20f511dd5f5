#pragma once
// A gait in closed form: where each foot of a walking creature is at any time, from the
// gait's period, duty factor and stride and the foot's phase. Nothing is integrated
// from frame to frame, so the walk at a time is the same whatever frames were drawn
// before it.
//
// The body travels straight along `forward` at speed stride / (duty * period): exactly
// what a planted foot pushes, since a stance foot moves back by one stride relative to
// the body while it is down. A foot touches down at phase (in cycles) and stays where it
// touched down, half a stride ahead of its neutral point, for duty * period; then it
// lifts off (half a stride behind) and swings along a smooth arc to its next foothold,
// where its velocity and height are 0 again.

#include <glm/vec3.hpp>

namespace ontogen {

/// The gait of one creature; validated by gaitError().
struct GaitDef {
  double period = 1;   ///< seconds per gait cycle, > 0
  double duty = 0.5;   ///< the fraction of its cycle each foot is on the ground, in (0, 1)
  double stride = 1;   ///< how far a stance foot travels back relative to the body, model units, >= 0
  double lift = 0.2;   ///< the highest point of a swing above the ground, model units, >= 0
  double height = 1;   ///< of the creature's root above the ground, model units, >= 0

  /// Of the body, model units a second.
  double speed() const { return stride / (duty * period); }
};

/// Why def is no gait, or null when it is one.
const char* gaitError(const GaitDef& def);

/// Where a foot is in its cycle at a time.
struct FootPhase {
  bool stance = true;   ///< on the ground
  double touchdown = 0; ///< time of the last touchdown (of this stance, or of the one before this swing), seconds
  double swing = 0;     ///< 0..1 through the swing; 0 in stance
};

/// The phase of a foot that touches down at `phase` (cycles: at times (k + phase) * period).
FootPhase footPhase(const GaitDef& gait, double phase, double time);

/// How far along its way from lift-off to touchdown a swinging foot is at swing u in
/// [0, 1]: u - sin(2 pi u) / (2 pi), which starts and ends at rest.
double swingProgress(double u);
/// The height of a swinging foot as a fraction of the lift: (1 - cos(2 pi u)) / 2.
double swingHeight(double u);

/// Where the foot is at `time`: `neutral` is its neutral point then (on the ground, where
/// the resting leg would stand; it moves with the body), `forward` the unit direction of
/// travel and `up` the unit world up; the ground lies where `neutral` is along `up`.
glm::dvec3 footPosition(const GaitDef& gait, double phase, double lift, double time, const glm::dvec3& neutral,
                        const glm::dvec3& forward, const glm::dvec3& up);

}  // namespace ontogen
