#pragma once
// Development of a grid pool over one step: per-step rules at t on the grid as it was
// (parallel development: every cell reads the snapshot), then rate integration over
// (t, t1]. Actions: none keeps the cell at its site with its new state, delete empties
// the site at the end of the step, and successors fill sites: the first takes the
// cell's own site, the others free neighbouring sites (docs/LANGUAGE.md, "Grid pools").

#include <vector>

#include "core/development.h"
#include "core/pool_view.h"
#include "core/rate_integrator.h"
#include "pools/grid_pool.h"

namespace ontogen {

/// Bytes a site of `system`'s grid takes at the peak of a step, for the memory limit
/// before the grid is made: its index (4), the seeding's source (8), and three copies of
/// a cell (its record, site and values: the pool's, the step's chunks' and the merged
/// next word), with the integrator's stages when the system integrates rates (eight
/// arrays of values at most, Dormand-Prince's) and the rate stencil's tables of the
/// cells at an edge and their neighbours, shared out over the sites.
uint64_t gridBytesPerSite(const Program& program, const SystemDefinition& system);

class GridDevelopment final : public Development {
 public:
  GridDevelopment(const Program& program, const SystemDefinition& system);
  GridDevelopment(const GridDevelopment& other);
  GridDevelopment& operator=(const GridDevelopment&) = delete;

  std::unique_ptr<Development> clone() const override { return std::make_unique<GridDevelopment>(*this); }
  const Pool& pool() const override { return grid_; }
  Pool& pool() override { return grid_; }
  const GridPool& gridPool() const { return grid_; }
  void seed(StepContext& context) override;
  void step(StepContext& context, double t1, bool stepRules) override;
  std::array<double, 3> positionOf(size_t i) const override;

 private:
  void applyStepRules(StepContext& context);

  const Program* program_;
  const SystemDefinition* system_;
  GridPool grid_;
  GridPoolView view_{grid_};
  std::unique_ptr<RateIntegrator<GridPoolView>> rates_;  // made on the first step that needs it; not copied
};

}  // namespace ontogen
