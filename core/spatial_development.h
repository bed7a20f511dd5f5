#pragma once
// Development of a spatial pool over one step: per-step rules at t read the pool as it
// was (neighbours within the radius, from the positions at t); successors take the
// cell's place in pool order, as in a linear pool, at the positions their state gives.
// Then rates over (t, t1], with the neighbours found from the positions at t+ and kept
// for the step.

#include "core/world.h"

namespace ontogen {

class SpatialDevelopment {
 public:
  explicit SpatialDevelopment(World& world);
  void step(double t1, bool stepRules);

 private:
  void applyStepRules(double t);

  World& world_;
  const Program& program_;
  SpatialPool& pool_;
};

}  // namespace ontogen
