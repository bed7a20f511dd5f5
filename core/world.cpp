#include "core/world.h"

#include "core/grid_development.h"
#include "core/linear_development.h"
#include "core/parallel_for.h"
#include "core/rate_integrator.h"
#include "core/spatial_development.h"

#include <cmath>

namespace ontogen {

namespace {
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

World::World(std::shared_ptr<const Program> program, WorldDef def)
    : program_(std::move(program)),
      def_(def),
      grid_(program_->rootSystem().grid),
      spatial_(program_->rootSystem().spatialRadius, positionSlots(*program_)) {
  def_.threads = resolveThreadCount(def_.threads);
  if (rootSystem().poolKind == PoolKind::Grid)
    seedGrid();
  else
    seedAxiom();
}

World::World(const World& other)
    : program_(other.program_),
      def_(other.def_),
      pool_(other.pool_),
      grid_(other.grid_),
      spatial_(other.spatial_),
      time_(other.time_),
      stats_(other.stats_) {}

World::~World() = default;

const Pool& World::rootPool() const {
  switch (rootSystem().poolKind) {
    case PoolKind::Grid: return grid_;
    case PoolKind::Spatial: return spatial_;
    case PoolKind::Linear: break;
  }
  return pool_;
}

std::array<double, 3> World::positionOf(size_t i) const {
  if (rootSystem().poolKind == PoolKind::Spatial) return spatial_.positionOf(i);
  if (rootSystem().poolKind != PoolKind::Grid) return {static_cast<double>(i), 0, 0};
  const GridCoordinates c = grid_.coordinates(grid_.siteOf(i));
  return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
}

RateIntegrator& World::rates() {
  if (!rates_) rates_ = std::make_unique<RateIntegrator>(*program_, def_.seed, def_.threads);
  return *rates_;
}

// The axiom fills sites 0, 1, 2 ... in site order; then `fill` and `at` placements in
// text order, a later one replacing an earlier one at the same site.
void World::seedGrid() {
  const SystemDefinition& system = rootSystem();
  const uint32_t sites = grid_.siteCount();
  const uint64_t bytesPerSite = sizeof(CellRecord) + 2 * sizeof(uint32_t);
  if (uint64_t{sites} * bytesPerSite * 2 > def_.limits.maxMemoryBytes)
    throw LimitError("the grid's " + std::to_string(sites) + " sites need more than the memory limit of " +
                     std::to_string(def_.limits.maxMemoryBytes >> 20) + " MiB; raise it with --max-memory MIB");
  // Which source decides each site: 0 .. axiom-1 are axiom cells, then placements.
  const int64_t axiomCount = static_cast<int64_t>(system.axiom.size());
  std::vector<int64_t> source(sites, -1);
  for (int64_t a = 0; a < axiomCount; ++a) source[a] = a;
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
  constexpr uint64_t kPlacementSalt = 0x504c414345ull;
  for (uint32_t site = 0; site < sites; ++site) {
    const int64_t from = std::max(source[site], lastFill);
    if (from < 0) continue;
    CellRecord cell;
    cell.id = mixKey(mixKey(0x6f6e746f67656eull, static_cast<uint64_t>(program_->root)), site);
    cell.state = static_cast<uint32_t>(state.size());
    if (from < axiomCount) {
      const AxiomCell& axiom = system.axiom[from];
      cell.master = axiom.master;
      cell.birth = -axiom.age;
      state.insert(state.end(), axiom.values.begin(), axiom.values.end());
    } else {
      const GridPlacement& placement = system.placements[from - axiomCount];
      cell.master = placement.master;
      const GridCoordinates c = grid_.coordinates(site);
      frame[FrameSlot::kId] = static_cast<double>(cell.id & ((uint64_t{1} << 53) - 1));
      frame[FrameSlot::kX] = static_cast<double>(c[0]);
      frame[FrameSlot::kY] = static_cast<double>(c[1]);
      frame[FrameSlot::kZ] = static_cast<double>(c[2]);
      RandomStream random(mixKey(mixKey(def_.seed ^ kPlacementSalt, cell.id), 0));
      EvalContext context{frame, EvalEnvironment{&random, def_.seed}, &functions};
      for (const CompiledExpression& value : placement.values) state.push_back(value.evaluate(context));
    }
    cells.push_back(cell);
    siteOf.push_back(site);
  }
  if (cells.size() > def_.limits.maxCells)
    throw LimitError("the grid starts with " + std::to_string(cells.size()) + " cells, past the cell limit of " +
                     std::to_string(def_.limits.maxCells) + "; raise it with --max-cells N");
  stats_.cellsBorn = cells.size();
  grid_.assign(cells, state, siteOf);
}

void World::seedAxiom() {
  const SystemDefinition& system = rootSystem();
  uint64_t index = 0;
  for (const AxiomCell& axiom : system.axiom) {
    CellRecord cell;
    cell.master = axiom.master;
    cell.birth = -axiom.age;
    cell.id = mixKey(mixKey(0x6f6e746f67656eull, static_cast<uint64_t>(program_->root)), index++);
    Pool& pool = system.poolKind == PoolKind::Spatial ? static_cast<Pool&>(spatial_) : pool_;
    pool.append(cell, axiom.values.data(), static_cast<uint32_t>(axiom.values.size()));
  }
  stats_.cellsBorn = rootPool().size();
  if (system.poolKind == PoolKind::Spatial) spatial_.index();
}

void World::advanceTo(double target, double dt) {
  if (!(dt > 0)) throw std::invalid_argument("the step must be greater than 0");
  // Steps follow the grid k * dt, so per-step rules fire at the same instants whichever
  // times the caller stops at (frames, --at); a stop between grid points develops the
  // terminal events up to it and fires no per-step rule there.
  while (time_ < target - timeTolerance(target)) {
    double k = std::floor(time_ / dt + 1e-9);
    bool onGrid = std::abs(time_ - k * dt) <= timeTolerance(time_);
    double next = (k + 1) * dt;
    if (next > target - timeTolerance(target)) next = target;
    developStep(next, onGrid);
  }
}

void World::step(double dt) {
  developStep(time_ + dt, true);
}

void World::developStep(double t1, bool stepRules) {
  if (rootSystem().poolKind == PoolKind::Grid) {
    GridDevelopment development(*this);
    development.step(t1, stepRules);
  } else if (rootSystem().poolKind == PoolKind::Spatial) {
    SpatialDevelopment development(*this);
    development.step(t1, stepRules);
  } else {
    LinearDevelopment development(*this);
    development.step(t1, stepRules);
  }
}

void World::developedValues(const CellRecord& cell, std::vector<double>& out) const {
  const MasterCell& master = program_->masters[cell.master];
  const double* state = rootPool().stateOf(cell);
  out.assign(state, state + master.stateCount());
  if (master.developmentFunction < 0) return;
  const DevelopmentFunction& function = program_->functions[master.developmentFunction];
  double frame[CompiledExpression::kMaxStack];
  double age = ageOf(cell);
  for (size_t i = 0; i < function.sources.size() && i < CompiledExpression::kMaxStack; ++i) {
    int source = function.sources[i];
    frame[i] = source == DevelopmentFunction::kFromAge           ? age
               : source == DevelopmentFunction::kFromTerminalAge ? master.lifetime
                                                                 : state[source];
  }
  FunctionTable table = program_->functionTable();
  constexpr uint64_t kDevelopSalt = 0x444556454c4f50ull;  // apart from the cell's rule draws
  RandomStream random(mixKey(mixKey(def_.seed ^ kDevelopSalt, cell.id), keyOf(time_)));
  EvalContext context{frame, EvalEnvironment{&random, def_.seed}, &table};
  double g = program_->functionBodies[master.developmentFunction].evaluate(context);
  for (double& value : out) value *= g;
}

}  // namespace ontogen
