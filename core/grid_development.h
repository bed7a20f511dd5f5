#pragma once
// Development of a grid pool over one step: per-step rules at t on the grid as it was
// (parallel development: every cell reads the snapshot), then rate integration over
// (t, t1]. Actions: none keeps the cell at its site with its new state, delete empties
// the site at the end of the step, and successors fill sites: the first takes the
// cell's own site, the others free neighbouring sites (docs/LANGUAGE.md, "Grid pools").

#include <vector>

#include "core/world.h"

namespace ontogen {

class GridDevelopment {
 public:
  explicit GridDevelopment(World& world);
  void step(double t1, bool stepRules);

 private:
  void applyStepRules(double t);

  World& world_;
  const Program& program_;
  GridPool& grid_;
};

}  // namespace ontogen
