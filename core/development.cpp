#include "core/development.h"

#include "core/grid_development.h"
#include "core/linear_development.h"
#include "core/spatial_development.h"

namespace ontogen {

std::unique_ptr<Development> makeDevelopment(const Program& program, const SystemDefinition& system) {
  switch (system.poolKind) {
    case PoolKind::Grid: return std::make_unique<GridDevelopment>(program, system);
    case PoolKind::Spatial: return std::make_unique<SpatialDevelopment>(program, system);
    case PoolKind::Linear: break;
  }
  return std::make_unique<LinearDevelopment>(program, system);
}

void checkGrowth(const StepContext& context, uint64_t cells, uint64_t bytes) {
  checkCancelled(context.limits);
  checkCellLimit(cells, context.limits);
  if (context.elsewhere.cells > 0) checkTotalCellLimit(cells + context.elsewhere.cells, context.limits);
  checkMemoryLimit(bytes + context.elsewhere.bytes, context.limits);
}

void seedFromAxiom(Pool& pool, StepContext& context) {
  uint64_t index = 0;
  for (const AxiomCell& axiom : context.system.axiom) {
    CellRecord cell;
    cell.master = axiom.master;
    cell.birth = context.time - axiom.age;
    cell.id = mixKey(context.idSalt, index++);
    const std::vector<double> values = axiomValues(context.program, axiom, context.seed, context.ancestors);
    pool.append(cell, values.data(), static_cast<uint32_t>(values.size()));
  }
  context.stats.cellsBorn += pool.size();
}

std::vector<double> axiomValues(const Program& program, const AxiomCell& axiom, uint64_t seed,
                                const double* ancestors) {
  std::vector<double> values = axiom.values;
  if (axiom.fromSystems.empty()) return values;
  FunctionTable functions = program.functionTable();
  EvalContext context{nullptr, EvalEnvironment{nullptr, seed}, &functions};
  context.ancestors = ancestors;
  for (size_t i = 0; i < values.size() && i < axiom.fromSystems.size(); ++i)
    if (!axiom.fromSystems[i].empty()) values[i] = axiom.fromSystems[i].evaluate(context);
  return values;
}

}  // namespace ontogen
