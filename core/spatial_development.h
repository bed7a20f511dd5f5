#pragma once
// Development of a spatial pool over one step: per-step rules at t read the pool as it
// was (neighbours within the radius, from the positions at t); successors take the
// cell's place in pool order, as in a linear pool, at the positions their state gives.
// Then rates over (t, t1], with the neighbours found from the positions at t+ and kept
// for the step.

#include "core/development.h"
#include "core/pool_view.h"
#include "core/rate_integrator.h"
#include "pools/spatial_pool.h"

namespace ontogen {

class SpatialDevelopment final : public Development {
 public:
  SpatialDevelopment(const Program& program, const SystemDefinition& system);
  SpatialDevelopment(const SpatialDevelopment& other);
  SpatialDevelopment& operator=(const SpatialDevelopment&) = delete;

  std::unique_ptr<Development> clone() const override { return std::make_unique<SpatialDevelopment>(*this); }
  const Pool& pool() const override { return pool_; }
  Pool& pool() override { return pool_; }
  const SpatialPool& spatialPool() const { return pool_; }
  void seed(StepContext& context) override;
  void step(StepContext& context, double t1, bool stepRules) override;
  std::array<double, 3> positionOf(size_t i) const override { return pool_.positionOf(i); }
  /// The pool's cells, its index and the neighbour tables kept for the next step.
  uint64_t heldBytes() const override {
    return pool_.bytes() + pool_.indexBytes() + (neighbourOffsets_.size() + neighbourCells_.size()) * sizeof(uint32_t);
  }

 private:
  void applyStepRules(StepContext& context);

  const Program* program_;
  const SystemDefinition* system_;
  SpatialPool pool_;
  SpatialPoolView view_{pool_};
  bool aggregates_ = false;  // some per-step rule reads its neighbours (count(), sum(x) ...)
  LargeVector<uint32_t> neighbourOffsets_, neighbourCells_;  // found once for a step's rules
  std::unique_ptr<RateIntegrator<SpatialPoolView>> rates_;  // made on the first step that needs it; not copied
};

}  // namespace ontogen
