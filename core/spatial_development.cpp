#include "core/spatial_development.h"

#include "core/growth_meter.h"
#include "core/pool_view.h"
#include "core/rate_integrator.h"
#include "core/rule_evaluator.h"
#include "core/step_rule_pass.h"

namespace ontogen {

namespace {
struct ChunkResult {
  CellArray cells;
  StateArray state;
  std::vector<LineageRecord> lineage;
  uint64_t firings = 0;
  uint64_t born = 0;
  GrowthMeter::Reported metered;
};

// For each master, the state indices of x, y and z (-1 where it has none).
std::vector<std::array<int, 3>> positionSlots(const Program& program) {
  std::vector<std::array<int, 3>> slots;
  for (const MasterCell& master : program.masters) {
    std::array<int, 3> slot{-1, -1, -1};
    for (size_t i = 0; i < master.stateNames.size(); ++i) {
      const std::string& name = master.stateNames[i];
      if (name == "x") slot[0] = static_cast<int>(i);
      if (name == "y") slot[1] = static_cast<int>(i);
      if (name == "z") slot[2] = static_cast<int>(i);
    }
    slots.push_back(slot);
  }
  return slots;
}
}  // namespace

SpatialDevelopment::SpatialDevelopment(const Program& program, const SystemDefinition& system)
    : program_(&program), system_(&system), pool_(system.spatialRadius, positionSlots(program)) {
  for (const MasterCell& master : program.masters)
    for (const CompiledRule& rule : master.rules) aggregates_ = aggregates_ || !rule.aggregates.empty();
}

// A copy develops on its own: its view looks at its own pool.
SpatialDevelopment::SpatialDevelopment(const SpatialDevelopment& other)
    : Development(other),
      program_(other.program_),
      system_(other.system_),
      pool_(other.pool_),
      aggregates_(other.aggregates_) {}

void SpatialDevelopment::seed(StepContext& context) {
  seedFromAxiom(pool_, context);
  pool_.index();
}

void SpatialDevelopment::step(StepContext& context, double t1, bool stepRules) {
  if (system_->sampledRules && stepRules) applyStepRules(context);
  if (system_->rates) {
    pool_.index();
    integrateRates(rates_, *program_, context, pool_, view_, context.time, t1);
  }
}

void SpatialDevelopment::applyStepRules(StepContext& context) {
  const Program& program = *program_;
  const double t = context.time;
  pool_.index();
  // The neighbours of every cell, found in bucket order rather than cell by cell.
  if (aggregates_) pool_.neighbourTable(neighbourOffsets_, neighbourCells_);
  std::vector<ChunkResult> results;
  GrowthMeter meter(context, WorldHeld{pool_.size(), pool_.bytes() + pool_.indexBytes()});
  runStepRules(program, context, view_, results,
               [&](ChunkResult& out, size_t, const CellView& cell, double* frame, const CompiledRule* action,
                   const EvalContext& evaluation, SuccessorWriter& successors) {
                 // Successors take the cell's place in pool order, as in a linear pool.
                 auto emit = [&](CellRecord record, const double* values, uint32_t count) {
                   record.state = static_cast<uint32_t>(out.state.size());
                   out.state.insert(out.state.end(), values, values + count);
                   out.cells.push_back(record);
                 };
                 if (!action)
                   emit(CellRecord{cell.master, 0, cell.birth, cell.id}, frame, program.masters[cell.master].stateCount());
                 else
                   out.born += successors.write(*action, moduleOf(cell), frame, t, BirthCause::StepRule, evaluation,
                                                [&](const ModuleValue& module, const double* values, uint32_t count) {
                                                  emit(recordOf(module), values, count);
                                                });
                 meter.update(out.metered, out.cells.size(),
                              out.cells.size() * sizeof(CellRecord) + out.state.size() * sizeof(double));
               },
               aggregates_ ? std::pair{static_cast<const uint32_t*>(neighbourOffsets_.data()),
                                       static_cast<const uint32_t*>(neighbourCells_.data())}
                           : std::pair<const uint32_t*, const uint32_t*>{nullptr, nullptr});

  CellArray next;
  StateArray nextState;
  size_t total = 0, values = 0;
  uint64_t resultBytes = 0;
  for (const ChunkResult& result : results) {
    total += result.cells.size();
    values += result.state.size();
    resultBytes += result.cells.capacity() * sizeof(CellRecord) + result.state.capacity() * sizeof(double);
  }
  checkCellLimit(total, context.limits);
  // The merged word is written beside the chunks' results, the old word and its index:
  // counted before it is made, as is the new index below (at a limit of 100 MiB a
  // dividing colony peaked at 226 MB when both were counted after the fact).
  checkGrowth(context, total,
              pool_.bytes() + pool_.indexBytes() + resultBytes + total * sizeof(CellRecord) + values * sizeof(double));
  next.reserve(total);
  nextState.reserve(values);
  for (ChunkResult& result : results) {
    const uint32_t base = static_cast<uint32_t>(nextState.size());
    nextState.insert(nextState.end(), result.state.begin(), result.state.end());
    for (CellRecord cell : result.cells) {
      cell.state += base;
      next.push_back(cell);
    }
    // Each result goes as soon as it is merged.
    result.cells = CellArray();
    result.state = StateArray();
    context.stats.ruleFirings += result.firings;
    context.stats.cellsBorn += result.born;
    if (context.lineage) context.lineage->insert(context.lineage->end(), result.lineage.begin(), result.lineage.end());
  }
  pool_.swapContents(next, nextState);
  // The old word goes before the new index is made.
  next = CellArray();
  nextState = StateArray();
  checkGrowth(context, total, pool_.bytes() + pool_.indexBytes() + total * SpatialPool::kIndexPeakBytesPerCell);
  pool_.index();
}

}  // namespace ontogen
