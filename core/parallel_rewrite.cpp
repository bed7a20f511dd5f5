#include "core/parallel_rewrite.h"

#include <algorithm>
#include <cstdint>

#include "core/cell_frame.h"
#include "core/parallel_for.h"
#include "core/rule_evaluator.h"
#include "core/salts.h"
#include "lang/random.h"
#include "pools/large_page_allocator.h"

namespace ontogen {

namespace {
// Slices per thread: enough that one slice heavier than the others does not hold up the
// rest, few enough that their bookkeeping costs nothing.
constexpr size_t kSlicesPerThread = 4;

bool rewritesWithoutChoice(const CompiledRule& rule) {
  if (rule.group != 0 || !rule.predicate.empty() || !rule.probability.empty() || rule.hasContext() ||
      !rule.aggregates.empty())
    return false;
  for (const SuccessorTemplate& successor : rule.successors)
    if (!successor.birthAge.empty()) return false;
  return true;
}
}  // namespace

ParallelRewrite::ParallelRewrite(const Program& program, const SystemDefinition& system)
    : program_(program), functions_(program.functionTable()), frameSize_(ruleFrameSize(program)) {
  for (uint8_t symbolClass : system.symbolClass)
    if (symbolClass & kSymbolCut) applies_ = false;
  masters_.resize(program.masters.size());
  for (size_t m = 0; m < program.masters.size(); ++m) {
    const MasterCell& master = program.masters[m];
    PerMaster& info = masters_[m];
    info.values = master.stateCount();
    info.shortestLife = master.lifetime;
    if (master.terminalRules.empty()) continue;
    if (master.terminalRules.size() > 1 || !rewritesWithoutChoice(master.terminalRules[0])) {
      applies_ = false;
      continue;
    }
    info.rule = &master.terminalRules[0];
    if (!info.rule->hasAction) continue;  // renews itself after its calculations
    info.cells = 0;
    info.values = 0;
    info.shortestLife = kForever;
    for (const SuccessorTemplate& successor : info.rule->successors) {
      const MasterCell& target = successor.isMe ? master : program.masters[successor.master];
      ++info.cells;
      info.values += target.stateCount();
      info.born += successor.isMe ? 0 : 1;
      info.shortestLife = std::min(info.shortestLife, target.lifetime);
    }
  }
}

void ParallelRewrite::count(const LinearPool& pool, double horizon, Slice& slice) const {
  const auto cells = pool.cells();
  const auto& masters = program_.masters;
  for (size_t i = slice.begin; i < slice.end; ++i) {
    const CellRecord& cell = cells[i];
    const double death = cell.birth + masters[cell.master].lifetime;
    const PerMaster& info = masters_[cell.master];
    if (death > horizon) {
      ++slice.cells;
      slice.values += masters[cell.master].stateCount();
      continue;
    }
    ++slice.events;
    slice.cells += info.cells;
    slice.values += info.values;
    slice.born += info.born;
    // As the serial pass finds it: a successor born at `death` that expires by the horizon.
    if (death + info.shortestLife <= horizon) slice.chained = true;
  }
}

// What LinearDevelopment::expire does for a rule without a choice, written in place.
void ParallelRewrite::write(const LinearPool& pool, double horizon, const StepContext& context, const double* parents,
                            const Slice& slice, uint64_t firstCell, uint64_t firstValue, Worker& worker,
                            CellArray& cells, StateArray& state) const {
  const auto word = pool.cells();
  const auto& masters = program_.masters;
  CellRecord* outCells = cells.data() + firstCell;
  double* outValues = state.data();
  uint64_t valueAt = firstValue;
  auto put = [&](const CellRecord& record, const double* values, uint32_t count) {
    CellRecord copy = record;
    copy.state = static_cast<uint32_t>(valueAt);
    *outCells++ = copy;
    std::copy(values, values + count, outValues + valueAt);
    valueAt += count;
  };
  worker.frame.resize(frameSize_);
  double* frame = worker.frame.data();
  for (size_t i = slice.begin; i < slice.end; ++i) {
    const CellRecord& cell = word[i];
    const MasterCell& master = masters[cell.master];
    const uint32_t n = master.stateCount();
    const double* values = pool.stateOf(cell);
    const double death = cell.birth + master.lifetime;
    if (death > horizon) {
      put(cell, values, n);
      continue;
    }
    loadCellFrame(frame, master, cell, values, death, {static_cast<double>(i), 0, 0}, parents ? parents[i] : -1);
    RandomStream random(mixKey(mixKey(context.seed, cell.id), keyOf(death)));
    EvalContext evaluation{frame, EvalEnvironment{&random, context.seed}, &functions_, nullptr};
    evaluation.ancestors = context.ancestors;
    const CompiledRule* rule = masters_[cell.master].rule;
    if (rule) {
      rule->clearUnbound(frame);
      for (const StateCalculation& calculation : rule->calculations)
        frame[calculation.slot] = calculation.value.evaluate(evaluation);
    }
    if (!rule || !rule->hasAction) {
      CellRecord renewed = cell;
      renewed.birth = death;
      put(renewed, frame, n);
      continue;
    }
    worker.successors.write(*rule, cell, frame, death, BirthCause::Terminal, evaluation, put);
  }
}

bool ParallelRewrite::rewrite(const LinearPool& pool, double horizon, StepContext& context, const double* parents,
                              uint64_t& events, CellArray& cells, StateArray& state) {
  cells.clear();
  state.clear();
  const unsigned threads = context.threads;
  const size_t size = pool.size();
  if (!applies_ || threads < 2 || size < kMinimumCells || context.lineage) return false;
  const size_t sliceCount = std::min<size_t>(size, size_t{threads} * kSlicesPerThread);
  slices_.assign(sliceCount, Slice{});
  for (size_t s = 0; s < sliceCount; ++s) {
    slices_[s].begin = size * s / sliceCount;
    slices_[s].end = size * (s + 1) / sliceCount;
  }
  parallelFor(
      sliceCount, threads,
      [&](size_t begin, size_t end, unsigned) {
        for (size_t s = begin; s < end; ++s) count(pool, horizon, slices_[s]);
      },
      1);
  uint64_t totalCells = 0, totalValues = 0, totalEvents = 0, totalBorn = 0;
  for (const Slice& slice : slices_) {
    if (slice.chained) return false;
    totalCells += slice.cells;
    totalValues += slice.values;
    totalEvents += slice.events;
    totalBorn += slice.born;
  }
  if (events + totalEvents > context.limits.maxEventsPerStep || totalValues > UINT32_MAX) return false;
  try {
    checkGrowth(context, totalCells,
                pool.bytes() + totalCells * sizeof(CellRecord) + totalValues * sizeof(double));
  } catch (const LimitError&) {
    return false;  // the serial pass stops where it passes the limit, as it always did
  }
  resizeForOverwrite(cells, totalCells);
  resizeForOverwrite(state, totalValues);
  while (workers_.size() < threads) workers_.push_back(std::make_unique<Worker>(program_));
  std::vector<uint64_t> firstCell(sliceCount), firstValue(sliceCount);
  for (size_t s = 0, c = 0, v = 0; s < sliceCount; ++s) {
    firstCell[s] = c;
    firstValue[s] = v;
    c += slices_[s].cells;
    v += slices_[s].values;
  }
  parallelFor(
      sliceCount, threads,
      [&](size_t begin, size_t end, unsigned worker) {
        for (size_t s = begin; s < end; ++s)
          write(pool, horizon, context, parents, slices_[s], firstCell[s], firstValue[s], *workers_[worker], cells,
                state);
      },
      1);
  events += totalEvents;
  context.stats.events += totalEvents;
  context.stats.cellsBorn += totalBorn;
  ++context.stats.parallelRewrites;
  return true;
}

}  // namespace ontogen
