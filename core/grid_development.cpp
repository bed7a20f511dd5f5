#include "core/grid_development.h"

#include <algorithm>

#include "core/parallel_for.h"
#include "core/pool_view.h"
#include "core/rate_integrator.h"
#include "core/rule_evaluator.h"

namespace ontogen {

namespace {

constexpr uint64_t kStepRuleSalt = 0x5354455052554c45ull;  // as in the linear pool

// What one chunk of cells produced: the cells that stay at (or take) their own site, in
// site order, and successors waiting for a free neighbouring site.
struct ChunkResult {
  struct Extra {
    uint32_t parentSite;
    CellRecord cell;  ///< state offset into `extraState`
    uint32_t count;
  };
  CellArray cells;
  StateArray state;
  std::vector<uint32_t> sites;
  std::vector<Extra> extras;
  StateArray extraState;
  uint64_t firings = 0;
  uint64_t born = 0;

  void clear() {
    cells.clear();
    state.clear();
    sites.clear();
    extras.clear();
    extraState.clear();
    firings = born = 0;
  }
};

}  // namespace

GridDevelopment::GridDevelopment(World& world) : world_(world), program_(*world.program_), grid_(world.grid_) {}

void GridDevelopment::step(double t1, bool stepRules) {
  const double t = world_.time_;
  const SystemDefinition& system = world_.rootSystem();
  if (system.sampledRules && stepRules) applyStepRules(t);
  if (system.rates) {
    GridPoolView view(grid_);
    RateIntegrator& rates = world_.rates();
    rates.integrate(grid_, view, t, t1);
    world_.stats_.rateEquations = rates.activeEquations();
  }
  world_.time_ = t1;
  ++world_.stats_.steps;
}

void GridDevelopment::applyStepRules(double t) {
  const auto cells = grid_.cells();
  const double* arena = grid_.stateArena().data();
  const uint64_t seed = world_.def_.seed;
  const unsigned threads = world_.def_.threads;
  GridPoolView view(grid_);
  FunctionTable functions = program_.functionTable();
  std::vector<ChunkResult> results(threads);
  std::vector<double> values(ruleFrameSize(program_));

  parallelFor(cells.size(), threads, [&](size_t begin, size_t end, unsigned worker) {
    ChunkResult& out = results[worker];
    out.clear();
    RuleEvaluator evaluator(program_, view);
    std::vector<double> successorValues(values.size());
    for (size_t i = begin; i < end; ++i) {
      const CellRecord& cell = cells[i];
      const MasterCell& master = program_.masters[cell.master];
      const uint32_t n = master.stateCount();
      const uint32_t site = grid_.siteOf(i);
      double* frame = evaluator.load(i, arena, t);
      RandomStream random(mixKey(mixKey(seed ^ kStepRuleSalt, cell.id), keyOf(t)));
      EvalContext context{frame, EvalEnvironment{&random, seed}, &functions, &evaluator};
      context.ancestors = world_.ancestorValues();
      const CompiledRule* action = evaluator.fireStepRules(master, context, random, out.firings);
      if (!action) {
        out.cells.push_back(CellRecord{cell.master, static_cast<uint32_t>(out.state.size()), cell.birth, cell.id});
        out.state.insert(out.state.end(), frame, frame + n);
        out.sites.push_back(site);
        continue;
      }
      // Successors: the first takes this site, the rest wait for free neighbouring sites.
      const uint64_t lineage = mixKey(cell.id, keyOf(t)) ^ kStepRuleSalt;
      uint64_t k = 0;
      for (const SuccessorTemplate& successor : action->successors) {
        ++k;
        const bool first = k == 1;
        CellRecord born;
        const double* source = frame;
        uint32_t count = n;
        if (successor.isMe) {
          born = cell;
        } else {
          const MasterCell& target = program_.masters[successor.master];
          count = target.stateCount();
          for (uint32_t j = 0; j < count; ++j) successorValues[j] = successor.args[j].evaluate(context);
          source = successorValues.data();
          born = CellRecord{successor.master, 0, t, mixKey(lineage, k)};
          ++out.born;
        }
        if (first) {
          born.state = static_cast<uint32_t>(out.state.size());
          out.state.insert(out.state.end(), source, source + count);
          out.cells.push_back(born);
          out.sites.push_back(site);
        } else {
          born.state = static_cast<uint32_t>(out.extraState.size());
          out.extraState.insert(out.extraState.end(), source, source + count);
          out.extras.push_back({site, born, count});
        }
      }
    }
  });

  // Merge in cell order; successors beyond the first claim free sites in that order, so
  // the outcome does not depend on the number of threads.
  CellArray next;
  StateArray nextState;
  std::vector<uint32_t> nextSites;
  size_t total = 0, extras = 0;
  for (const ChunkResult& result : results) {
    total += result.cells.size();
    extras += result.extras.size();
    world_.stats_.ruleFirings += result.firings;
    world_.stats_.cellsBorn += result.born;
  }
  next.reserve(total + extras);
  nextSites.reserve(total + extras);
  for (const ChunkResult& result : results) {
    const uint32_t base = static_cast<uint32_t>(nextState.size());
    nextState.insert(nextState.end(), result.state.begin(), result.state.end());
    for (size_t c = 0; c < result.cells.size(); ++c) {
      CellRecord cell = result.cells[c];
      cell.state += base;
      next.push_back(cell);
      nextSites.push_back(result.sites[c]);
    }
  }
  if (extras > 0) {
    // A site is free when it was empty at the start of the step and nobody took it yet;
    // a deleted cell's site frees only at the end of the step.
    std::vector<uint8_t> taken(grid_.siteCount(), 0);
    for (size_t i = 0; i < cells.size(); ++i) taken[grid_.siteOf(i)] = 1;
    uint32_t around[GridPool::kMaxNeighbours];
    for (const ChunkResult& result : results) {
      for (const auto& extra : result.extras) {
        const int count = grid_.neighbourSites(extra.parentSite, around);
        uint32_t free = GridPool::kEmpty;
        for (int s = 0; s < count && free == GridPool::kEmpty; ++s)
          if (around[s] != GridPool::kEmpty && !taken[around[s]]) free = around[s];
        if (free == GridPool::kEmpty) {
          ++world_.stats_.crowded;
          continue;
        }
        taken[free] = 1;
        CellRecord cell = extra.cell;
        cell.state = static_cast<uint32_t>(nextState.size());
        nextState.insert(nextState.end(), result.extraState.begin() + extra.cell.state,
                         result.extraState.begin() + extra.cell.state + extra.count);
        next.push_back(cell);
        nextSites.push_back(free);
      }
    }
    // Back into site order.
    std::vector<uint32_t> order(next.size());
    for (uint32_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return nextSites[a] < nextSites[b]; });
    CellArray sorted;
    std::vector<uint32_t> sortedSites;
    sorted.reserve(next.size());
    sortedSites.reserve(next.size());
    for (uint32_t i : order) {
      sorted.push_back(next[i]);
      sortedSites.push_back(nextSites[i]);
    }
    next.swap(sorted);
    nextSites.swap(sortedSites);
  }
  grid_.assign(next, nextState, nextSites);
}

}  // namespace ontogen
