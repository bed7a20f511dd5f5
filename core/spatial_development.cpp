#include "core/spatial_development.h"

#include "core/parallel_for.h"
#include "core/pool_view.h"
#include "core/rate_integrator.h"
#include "core/rule_evaluator.h"

namespace ontogen {

namespace {
constexpr uint64_t kStepRuleSalt = 0x5354455052554c45ull;  // as in the other pools

struct ChunkResult {
  CellArray cells;
  StateArray state;
  uint64_t firings = 0;
  uint64_t born = 0;
};
}  // namespace

SpatialDevelopment::SpatialDevelopment(World& world)
    : world_(world), program_(*world.program_), pool_(world.spatial_) {}

void SpatialDevelopment::step(double t1, bool stepRules) {
  const double t = world_.time_;
  const SystemDefinition& system = world_.rootSystem();
  if (system.sampledRules && stepRules) applyStepRules(t);
  if (system.rates) {
    pool_.index();
    SpatialPoolView view(pool_);
    RateIntegrator& rates = world_.rates();
    rates.integrate(pool_, view, t, t1);
    world_.stats_.rateEquations = rates.activeEquations();
  }
  world_.time_ = t1;
  ++world_.stats_.steps;
}

void SpatialDevelopment::applyStepRules(double t) {
  pool_.index();
  const auto cells = pool_.cells();
  const double* arena = pool_.stateArena().data();
  const uint64_t seed = world_.def_.seed;
  const unsigned threads = world_.def_.threads;
  SpatialPoolView view(pool_);
  FunctionTable functions = program_.functionTable();
  std::vector<ChunkResult> results(threads);
  const size_t frameSize = ruleFrameSize(program_);

  parallelFor(cells.size(), threads, [&](size_t begin, size_t end, unsigned worker) {
    ChunkResult& out = results[worker];
    RuleEvaluator evaluator(program_, view);
    std::vector<double> successorValues(frameSize);
    for (size_t i = begin; i < end; ++i) {
      const CellRecord& cell = cells[i];
      const MasterCell& master = program_.masters[cell.master];
      const uint32_t n = master.stateCount();
      double* frame = evaluator.load(i, arena, t);
      RandomStream random(mixKey(mixKey(seed ^ kStepRuleSalt, cell.id), keyOf(t)));
      EvalContext context{frame, EvalEnvironment{&random, seed}, &functions, &evaluator};
      context.ancestors = world_.ancestorValues();
      const CompiledRule* action = evaluator.fireStepRules(master, context, random, out.firings);
      auto emit = [&](CellRecord record, const double* values, uint32_t count) {
        record.state = static_cast<uint32_t>(out.state.size());
        out.state.insert(out.state.end(), values, values + count);
        out.cells.push_back(record);
      };
      if (!action) {
        emit(cell, frame, n);
        continue;
      }
      const uint64_t lineage = mixKey(cell.id, keyOf(t)) ^ kStepRuleSalt;
      uint64_t k = 0;
      for (const SuccessorTemplate& successor : action->successors) {
        ++k;
        if (successor.isMe) {
          emit(cell, frame, n);
          continue;
        }
        const MasterCell& target = program_.masters[successor.master];
        for (uint32_t j = 0; j < target.stateCount(); ++j) successorValues[j] = successor.args[j].evaluate(context);
        emit(CellRecord{successor.master, 0, t, mixKey(lineage, k)}, successorValues.data(), target.stateCount());
        ++out.born;
      }
    }
  });

  CellArray next;
  StateArray nextState;
  size_t total = 0;
  for (const ChunkResult& result : results) total += result.cells.size();
  const WorldLimits& limits = world_.def_.limits;
  if (total > limits.maxCells)
    throw LimitError("the model grew past " + std::to_string(limits.maxCells) +
                     " cells, the cell limit; raise it with --max-cells N");
  next.reserve(total);
  for (const ChunkResult& result : results) {
    const uint32_t base = static_cast<uint32_t>(nextState.size());
    nextState.insert(nextState.end(), result.state.begin(), result.state.end());
    for (CellRecord cell : result.cells) {
      cell.state += base;
      next.push_back(cell);
    }
    world_.stats_.ruleFirings += result.firings;
    world_.stats_.cellsBorn += result.born;
  }
  if (next.size() * sizeof(CellRecord) * 2 + nextState.size() * sizeof(double) * 2 > limits.maxMemoryBytes)
    throw LimitError("the model's pools passed " + std::to_string(limits.maxMemoryBytes >> 20) +
                     " MiB, the memory limit; raise it with --max-memory MIB");
  pool_.swapContents(next, nextState);
  pool_.index();
}

}  // namespace ontogen
