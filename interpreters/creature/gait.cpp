#include "interpreters/creature/gait.h"

#include <cmath>

#include <glm/geometric.hpp>

namespace ontogen {

namespace {
constexpr double kTwoPi = 6.283185307179586;
}

const char* gaitError(const GaitDef& def) {
  if (!std::isfinite(def.period) || def.period <= 0) return "the gait's period must be > 0";
  if (!std::isfinite(def.duty) || def.duty <= 0 || def.duty >= 1) return "the duty factor must be between 0 and 1";
  if (!std::isfinite(def.stride) || def.stride < 0) return "the stride must be >= 0";
  if (!std::isfinite(def.lift) || def.lift < 0) return "the lift must be >= 0";
  if (!std::isfinite(def.height) || def.height < 0) return "the height must be >= 0";
  return nullptr;
}

FootPhase footPhase(const GaitDef& gait, double phase, double time) {
  const double cycles = time / gait.period - phase;
  const double cycle = std::floor(cycles);
  const double within = cycles - cycle;  // in [0, 1)
  FootPhase foot;
  foot.touchdown = (cycle + phase) * gait.period;
  foot.stance = within < gait.duty;
  foot.swing = foot.stance ? 0 : (within - gait.duty) / (1 - gait.duty);
  return foot;
}

double swingProgress(double u) { return u - std::sin(kTwoPi * u) / kTwoPi; }

double swingHeight(double u) { return (1 - std::cos(kTwoPi * u)) / 2; }

glm::dvec3 footPosition(const GaitDef& gait, double phase, double lift, double time, const glm::dvec3& neutral,
                        const glm::dvec3& forward, const glm::dvec3& up) {
  const FootPhase foot = footPhase(gait, phase, time);
  const double speed = gait.speed();
  // The neutral point at another time s: neutral + speed * (s - time) * forward.
  auto foothold = [&](double touchdown) {
    return neutral + (speed * (touchdown - time) + gait.stride / 2) * forward;
  };
  const glm::dvec3 planted = foothold(foot.touchdown);
  if (foot.stance) return planted;
  const glm::dvec3 next = foothold(foot.touchdown + gait.period);
  return planted + (next - planted) * swingProgress(foot.swing) + std::max(lift, 0.0) * swingHeight(foot.swing) * up;
}

}  // namespace ontogen
