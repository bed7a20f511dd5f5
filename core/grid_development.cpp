#include "core/grid_development.h"

#include <algorithm>

#include "core/cell_frame.h"
#include "core/growth_meter.h"
#include "core/pool_view.h"
#include "core/rate_integrator.h"
#include "core/rate_stencil.h"
#include "core/rule_evaluator.h"
#include "core/step_rule_pass.h"

namespace ontogen {

namespace {

// What one chunk of cells produced: the cells that stay at (or take) their own site, in
// site order, and successors waiting for a free neighbouring site.
struct ChunkResult {
  struct Extra {
    uint32_t parentSite;
    uint64_t parentId;
    CellRecord cell;  ///< state offset into `extraState`
    uint32_t count;
  };
  CellArray cells;
  StateArray state;
  std::vector<uint32_t> sites;
  std::vector<Extra> extras;
  StateArray extraState;
  std::vector<LineageRecord> lineage;  ///< births that took their parent's site
  uint64_t firings = 0;
  uint64_t born = 0;
  GrowthMeter::Reported metered;
};

}  // namespace

uint64_t gridBytesPerSite(const Program& program, const SystemDefinition& system) {
  uint64_t values = 0;
  for (const MasterCell& master : program.masters) values = std::max<uint64_t>(values, master.stateCount());
  const uint64_t cell = sizeof(CellRecord) + sizeof(uint32_t) + values * sizeof(double);
  uint64_t rates = 0;
  if (system.rates) {
    const uint64_t sites = std::max<uint64_t>(system.grid.siteCount(), 1);
    rates = 8 * values * sizeof(double) + (RateStencil::edgeTableBytes(system.grid) + sites - 1) / sites;
  }
  return sizeof(uint32_t) + sizeof(int64_t) + 3 * cell + rates;
}

GridDevelopment::GridDevelopment(const Program& program, const SystemDefinition& system)
    : program_(&program), system_(&system), grid_(system.grid) {}

// A copy develops on its own: its view looks at its own pool.
GridDevelopment::GridDevelopment(const GridDevelopment& other)
    : Development(other), program_(other.program_), system_(other.system_), grid_(other.grid_) {}

std::array<double, 3> GridDevelopment::positionOf(size_t i) const {
  const GridCoordinates c = grid_.coordinates(grid_.siteOf(i));
  return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
}

// The axiom fills sites 0, 1, 2 ... in site order; then `fill` and `at` placements in
// text order, a later one replacing an earlier one at the same site.
void GridDevelopment::seed(StepContext& context) {
  const SystemDefinition& system = *system_;
  const uint32_t sites = grid_.siteCount();
  checkGridMemory(sites, gridBytesPerSite(*program_, system), context.limits, context.elsewhere.bytes);
  // Which source decides each site: 0 .. axiom-1 are axiom cells, then placements.
  const int64_t axiomCount = static_cast<int64_t>(system.axiom.size());
  // In the pools' large blocks: at a million sites its memory goes on to serve the first
  // step's arrays (the rates' stages) instead of going back to the system.
  LargeVector<int64_t> source(sites, -1);
  for (int64_t a = 0; a < axiomCount && a < static_cast<int64_t>(sites); ++a) source[a] = a;
  int64_t lastFill = -1;
  for (size_t p = 0; p < system.placements.size(); ++p) {
    const GridPlacement& placement = system.placements[p];
    const int64_t ordinal = axiomCount + static_cast<int64_t>(p);
    if (placement.fill)
      lastFill = ordinal;
    else
      source[grid_.siteAt(placement.at)] = ordinal;
  }
  CellArray cells;
  StateArray state;
  std::vector<uint32_t> siteOf;
  FunctionTable functions = program_->functionTable();
  double frame[FrameSlot::kCount] = {};
  for (uint32_t site = 0; site < sites; ++site) {
    const int64_t from = std::max(source[site], lastFill);
    if (from < 0) continue;
    CellRecord cell;
    cell.id = mixKey(context.idSalt, site);
    cell.state = static_cast<uint32_t>(state.size());
    if (from < axiomCount) {
      const AxiomCell& axiom = system.axiom[from];
      cell.master = axiom.master;
      cell.birth = context.time - axiom.age;
      const std::vector<double> values = axiomValues(*program_, axiom, context.seed, context.ancestors);
      state.insert(state.end(), values.begin(), values.end());
    } else {
      const GridPlacement& placement = system.placements[from - axiomCount];
      cell.master = placement.master;
      cell.birth = context.time;
      const GridCoordinates c = grid_.coordinates(site);
      loadInternalState(frame, cell, program_->masters[cell.master].lifetime, context.time,
                        {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])});
      RandomStream random(mixKey(mixKey(context.seed ^ kPlacementSalt, cell.id), 0));
      EvalContext evaluation{frame, EvalEnvironment{&random, context.seed}, &functions};
      evaluation.ancestors = context.ancestors;
      for (const CompiledExpression& value : placement.values) state.push_back(value.evaluate(evaluation));
    }
    cells.push_back(cell);
    siteOf.push_back(site);
  }
  checkSeedCellLimit(cells.size(), context.limits);
  context.stats.cellsBorn += cells.size();
  grid_.assign(cells, state, siteOf);
}

void GridDevelopment::step(StepContext& context, double t1, bool stepRules) {
  if (system_->sampledRules && stepRules) applyStepRules(context);
  if (system_->rates) integrateRates(rates_, *program_, context, grid_, view_, context.time, t1);
}

void GridDevelopment::applyStepRules(StepContext& context) {
  const Program& program = *program_;
  const double t = context.time;
  const auto cells = grid_.cells();
  std::vector<ChunkResult> results;
  GrowthMeter meter(context, WorldHeld{grid_.size(), grid_.bytes()});
  runStepRules(program, context, view_, results,
               [&](ChunkResult& out, size_t i, const CellView& cell, double* frame, const CompiledRule* action,
                   const EvalContext& evaluation, SuccessorWriter& successors) {
                 const uint32_t n = program.masters[cell.master].stateCount();
                 const uint32_t site = grid_.siteOf(i);
                 if (!action) {
                   out.cells.push_back(
                       CellRecord{cell.master, static_cast<uint32_t>(out.state.size()), cell.birth, cell.id});
                   out.state.insert(out.state.end(), frame, frame + n);
                   out.sites.push_back(site);
                   return;
                 }
                 // Successors: the first takes this site, the rest wait for free neighbouring sites.
                 bool first = true;
                 const size_t logged = out.lineage.size();
                 out.born += successors.write(
                     *action, moduleOf(cell), frame, t, BirthCause::StepRule, evaluation,
                     [&](const ModuleValue& module, const double* values, uint32_t count) {
                       CellRecord born = recordOf(module);
                       if (first) {
                         born.state = static_cast<uint32_t>(out.state.size());
                         out.state.insert(out.state.end(), values, values + count);
                         out.cells.push_back(born);
                         out.sites.push_back(site);
                       } else {
                         born.state = static_cast<uint32_t>(out.extraState.size());
                         out.extraState.insert(out.extraState.end(), values, values + count);
                         out.extras.push_back({site, cell.id, born, count});
                       }
                       first = false;
                     });
                 // Successors waiting for a site are not cells yet (most may find none), but
                 // their bytes are held.
                 meter.update(out.metered, out.cells.size(),
                              (out.cells.size() + out.extras.size()) * sizeof(CellRecord) +
                                  (out.state.size() + out.extraState.size()) * sizeof(double));
                 // Only the first successor is sure of a site: the others are logged when they find one.
                 if (context.lineage) {
                   const uint64_t firstId = out.cells.back().id;
                   auto tail = std::remove_if(
                       out.lineage.begin() + static_cast<std::ptrdiff_t>(logged), out.lineage.end(),
                       [&](const LineageRecord& record) { return record.child != firstId; });
                   out.lineage.erase(tail, out.lineage.end());
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
    context.stats.ruleFirings += result.firings;
    context.stats.cellsBorn += result.born;
    if (context.lineage) context.lineage->insert(context.lineage->end(), result.lineage.begin(), result.lineage.end());
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
          ++context.stats.crowded;
          continue;
        }
        taken[free] = 1;
        CellRecord cell = extra.cell;
        cell.state = static_cast<uint32_t>(nextState.size());
        nextState.insert(nextState.end(), result.extraState.begin() + extra.cell.state,
                         result.extraState.begin() + extra.cell.state + extra.count);
        next.push_back(cell);
        nextSites.push_back(free);
        if (context.lineage) context.lineage->push_back(LineageRecord{cell.id, extra.parentId, t});
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
  checkCellLimit(next.size(), context.limits);
  grid_.assign(next, nextState, nextSites);
}

}  // namespace ontogen
