#include "core/world.h"

#include "core/grid_development.h"
#include "core/linear_development.h"
#include "core/parallel_for.h"
#include "core/rate_integrator.h"
#include "core/spatial_development.h"

#include <algorithm>
#include <cmath>
#include <limits>

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
      system_(program_->root),
      grid_(program_->rootSystem().grid),
      spatial_(program_->rootSystem().spatialRadius, positionSlots(*program_)) {
  def_.threads = resolveThreadCount(def_.threads);
  if (const int master = rootSystem().master; master >= 0) cellState_ = program_->masters[master].defaults;
  seedPool();
}

World::World(const World& parent, const CellRecord& cell, const double* cellState)
    : program_(parent.program_),
      def_(parent.def_),
      system_(program_->masters[cell.master].system),
      parent_(&parent),
      cellId_(cell.id),
      cellBirth_(cell.birth),
      cellState_(cellState, cellState + program_->masters[cell.master].stateCount()),
      grid_(program_->systems[system_].grid),
      spatial_(program_->systems[system_].spatialRadius, positionSlots(*program_)),
      time_(parent.time_) {
  seedPool();
}

// The pool from its system's axiom (and placements), then the pools of its system cells.
void World::seedPool() {
  updateAncestorValues();
  if (rootSystem().poolKind == PoolKind::Grid)
    seedGrid();
  else
    seedAxiom();
  developChildren(time_, false, /*step=*/false);
}

World::World(const World& other)
    : program_(other.program_),
      def_(other.def_),
      system_(other.system_),
      parent_(other.parent_),
      cellId_(other.cellId_),
      cellBirth_(other.cellBirth_),
      cellState_(other.cellState_),
      ancestorValues_(other.ancestorValues_),
      pool_(other.pool_),
      grid_(other.grid_),
      spatial_(other.spatial_),
      time_(other.time_),
      stats_(other.stats_) {
  for (const auto& [id, child] : other.children_) {
    auto copy = std::make_unique<World>(*child);
    copy->parent_ = this;
    children_.emplace(id, std::move(copy));
  }
}

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
  rates_->setAncestors(ancestorValues_.data());
  return *rates_;
}

const World* World::childOf(const CellRecord& cell) const {
  if (children_.empty()) return nullptr;
  auto it = children_.find(cell.id);
  return it == children_.end() ? nullptr : it->second.get();
}

uint64_t World::totalCells() const {
  uint64_t total = rootPool().size();
  for (const auto& [id, child] : children_) total += child->totalCells();
  return total;
}

uint64_t World::idSalt() const {
  const uint64_t base = mixKey(0x6f6e746f67656eull, static_cast<uint64_t>(system_));
  return parent_ ? mixKey(base, cellId_) : base;
}

double World::systemValue(int level, const std::string& name) const {
  const World* world = this;
  if (level == 0)
    while (world->parent_) world = world->parent_;
  for (int k = 1; k < level && world; ++k) world = world->parent_;
  if (!world) return std::numeric_limits<double>::quiet_NaN();  // the compiler rules this out
  if (name == "age") return time_ - world->cellBirth_;
  const int master = world->rootSystem().master;
  if (master < 0) return std::numeric_limits<double>::quiet_NaN();
  const auto& names = program_->masters[master].stateNames;
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? std::numeric_limits<double>::quiet_NaN() : world->cellState_[it - names.begin()];
}

void World::updateAncestorValues() {
  const auto& refs = program_->ancestorRefs;
  ancestorValues_.resize(refs.size());
  for (size_t i = 0; i < refs.size(); ++i) ancestorValues_[i] = systemValue(refs[i].level, refs[i].name);
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
    cell.id = mixKey(idSalt(), site);
    cell.state = static_cast<uint32_t>(state.size());
    if (from < axiomCount) {
      const AxiomCell& axiom = system.axiom[from];
      cell.master = axiom.master;
      cell.birth = time_ - axiom.age;
      const std::vector<double> values = axiomValues(axiom);
      state.insert(state.end(), values.begin(), values.end());
    } else {
      const GridPlacement& placement = system.placements[from - axiomCount];
      cell.master = placement.master;
      cell.birth = time_;
      const GridCoordinates c = grid_.coordinates(site);
      frame[FrameSlot::kId] = static_cast<double>(cell.id & ((uint64_t{1} << 53) - 1));
      frame[FrameSlot::kX] = static_cast<double>(c[0]);
      frame[FrameSlot::kY] = static_cast<double>(c[1]);
      frame[FrameSlot::kZ] = static_cast<double>(c[2]);
      RandomStream random(mixKey(mixKey(def_.seed ^ kPlacementSalt, cell.id), 0));
      EvalContext context{frame, EvalEnvironment{&random, def_.seed}, &functions};
      context.ancestors = ancestorValues_.data();
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

// An axiom cell's values; those that read the enclosing systems are evaluated now.
std::vector<double> World::axiomValues(const AxiomCell& axiom) const {
  std::vector<double> values = axiom.values;
  if (axiom.fromSystems.empty()) return values;
  FunctionTable functions = program_->functionTable();
  EvalContext context{nullptr, EvalEnvironment{nullptr, def_.seed}, &functions};
  context.ancestors = ancestorValues_.data();
  for (size_t i = 0; i < values.size() && i < axiom.fromSystems.size(); ++i)
    if (!axiom.fromSystems[i].empty()) values[i] = axiom.fromSystems[i].evaluate(context);
  return values;
}

void World::seedAxiom() {
  const SystemDefinition& system = rootSystem();
  uint64_t index = 0;
  for (const AxiomCell& axiom : system.axiom) {
    CellRecord cell;
    cell.master = axiom.master;
    cell.birth = time_ - axiom.age;
    cell.id = mixKey(idSalt(), index++);
    Pool& pool = system.poolKind == PoolKind::Spatial ? static_cast<Pool&>(spatial_) : pool_;
    const std::vector<double> values = axiomValues(axiom);
    pool.append(cell, values.data(), static_cast<uint32_t>(values.size()));
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

// The ancestor values are those of the current time: made when the world is seeded and
// after every step.
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
  updateAncestorValues();  // as of t1, for interpretation and the next step
  developChildren(t1, stepRules, /*step=*/true);
}

// Existing children step over the same interval as this pool (when `step`); a system
// cell that appeared in this step, or is in the axiom, gets a new child, seeded at t1;
// a child whose cell is gone goes.
void World::developChildren(double t1, bool stepRules, bool step) {
  if (!program_->hasSystemCells) return;
  const Pool& pool = rootPool();
  const auto cells = pool.cells();
  std::unordered_map<uint64_t, std::unique_ptr<World>> next;
  for (const CellRecord& cell : cells) {
    if (program_->masters[cell.master].system < 0) continue;
    std::unique_ptr<World> child;
    if (auto it = children_.find(cell.id); it != children_.end()) {
      child = std::move(it->second);
      if (step) {
        const WorldStats before = child->stats_;
        child->developStep(t1, stepRules);
        stats_.events += child->stats_.events - before.events;
        stats_.ruleFirings += child->stats_.ruleFirings - before.ruleFirings;
        stats_.cellsBorn += child->stats_.cellsBorn - before.cellsBorn;
        stats_.crowded += child->stats_.crowded - before.crowded;
      }
    } else {
      child = std::make_unique<World>(*this, cell, pool.stateOf(cell));
      stats_.cellsBorn += child->stats_.cellsBorn;
    }
    next.emplace(cell.id, std::move(child));
  }
  children_ = std::move(next);
  if (!parent_ && totalCells() > def_.limits.maxCells)
    throw LimitError("the model grew past " + std::to_string(def_.limits.maxCells) +
                     " cells in all its systems, the cell limit; raise it with --max-cells N");
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
