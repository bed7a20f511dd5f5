#include "core/world.h"

#include "core/finite_state.h"
#include "core/grid_development.h"
#include "core/linear_development.h"
#include "core/parallel_for.h"
#include "core/salts.h"
#include "core/spatial_development.h"
#include "pools/large_block_cache.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ontogen {

World::World(std::shared_ptr<const Program> program, WorldDef def)
    : program_(std::move(program)), def_(def), system_(program_->root), checksFinite_(checksFiniteState(*program_)) {
  def_.threads = resolveThreadCount(def_.threads);
  limitLargeBlockCache(def_.limits.maxMemoryBytes / 8);
  if (const int master = rootSystem().master; master >= 0) cellState_ = program_->masters[master].defaults;
  WorldHeld tree;
  seedPool(tree);
}

World::World(const World& parent, const CellView& cell, WorldHeld* tree)
    : program_(parent.program_),
      def_(parent.def_),
      system_(program_->masters[cell.master].system),
      parent_(&parent),
      cellId_(cell.id),
      cellBirth_(cell.birth),
      cellState_(cell.state, cell.state + program_->masters[cell.master].stateCount()),
      checksFinite_(parent.checksFinite_),
      time_(parent.time_) {
  WorldHeld alone;
  seedPool(tree ? *tree : alone);
}

// The pool from its system's axiom (and placements), then the pools of its system cells.
void World::seedPool(WorldHeld& tree) {
  // Before the grid's arrays are made: a grid far too large stops with the limit named,
  // not for want of the machine's memory.
  if (const SystemDefinition& system = rootSystem(); system.poolKind == PoolKind::Grid)
    checkGridMemory(system.grid.siteCount(), gridBytesPerSite(*program_, system), def_.limits, tree.bytes);
  development_ = makeDevelopment(*program_, rootSystem());
  pool_ = &development_->pool();
  updateAncestorValues();
  StepContext context = stepContext(tree);
  development_->seed(context);
  const WorldHeld own = heldHere();
  tree.cells += own.cells;
  tree.bytes += own.bytes;
  checkTree(tree);
  answerQueries();
  if (def_.recordLineage && parent_)
    for (CellCursor cell = development_->pool().cursor(); !cell.done(); cell.next())
      lineage_.push_back({cell.id(), cellId_, time_});
  developChildren(time_, false, /*step=*/false, tree);
}

StepContext World::stepContext(const WorldHeld& elsewhere) {
  StepContext context{*program_, rootSystem(), def_.seed, def_.threads, def_.limits, time_, ancestorValues_.data(),
                      stats_};
  context.elsewhere = elsewhere;
  context.lineage = def_.recordLineage ? &lineage_ : nullptr;
  context.rewriteBySlices = def_.rewriteBySlices;
  context.wordsWithoutIds = def_.wordsWithoutIds;
  context.forcedRewrite = def_.testRewriteStrategy;
  context.rateStencils = def_.rateStencils;
  context.idSalt = idSalt();
  context.systemCellId = parent_ ? idValue(cellId_) : -1;
  return context;
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
      checksFinite_(other.checksFinite_),
      development_(other.development_->clone()),
      pool_(&development_->pool()),
      time_(other.time_),
      heldOutside_(other.heldOutside_),
      stats_(other.stats_),
      lineage_(other.lineage_) {
  for (const auto& [id, child] : other.children_) {
    auto copy = std::make_unique<World>(*child);
    copy->parent_ = this;
    children_.emplace(id, std::move(copy));
  }
  if (other.onGrid_) onGrid_ = std::make_unique<World>(*other.onGrid_);
}

World::World(World&& other) noexcept
    : program_(std::move(other.program_)),
      def_(other.def_),
      system_(other.system_),
      parent_(other.parent_),
      cellId_(other.cellId_),
      cellBirth_(other.cellBirth_),
      cellState_(std::move(other.cellState_)),
      ancestorValues_(std::move(other.ancestorValues_)),
      checksFinite_(other.checksFinite_),
      children_(std::move(other.children_)),
      development_(std::move(other.development_)),
      pool_(other.pool_),
      time_(other.time_),
      heldOutside_(other.heldOutside_),
      stats_(other.stats_),
      lineage_(std::move(other.lineage_)),
      onGrid_(std::move(other.onGrid_)) {
  for (auto& [id, child] : children_) child->parent_ = this;
}

World& World::operator=(World&& other) noexcept {
  if (this == &other) return *this;
  program_ = std::move(other.program_);
  def_ = other.def_;
  system_ = other.system_;
  parent_ = other.parent_;
  cellId_ = other.cellId_;
  cellBirth_ = other.cellBirth_;
  cellState_ = std::move(other.cellState_);
  ancestorValues_ = std::move(other.ancestorValues_);
  checksFinite_ = other.checksFinite_;
  children_ = std::move(other.children_);
  for (auto& [id, child] : children_) child->parent_ = this;
  development_ = std::move(other.development_);
  pool_ = other.pool_;
  time_ = other.time_;
  heldOutside_ = other.heldOutside_;
  stats_ = other.stats_;
  lineage_ = std::move(other.lineage_);
  onGrid_ = std::move(other.onGrid_);
  return *this;
}

World::~World() = default;

namespace {
[[noreturn]] void wrongPoolKind(const char* kind) {
  throw std::logic_error(std::string("the world's pool is not a ") + kind + " pool");
}
}  // namespace

const LinearPool& World::linearPool() const {
  if (rootSystem().poolKind != PoolKind::Linear) wrongPoolKind("linear");
  return static_cast<const LinearDevelopment&>(*development_).linearPool();
}

const GridPool& World::gridPool() const {
  if (rootSystem().poolKind != PoolKind::Grid) wrongPoolKind("grid");
  return static_cast<const GridDevelopment&>(*development_).gridPool();
}

const SpatialPool& World::spatialPool() const {
  if (rootSystem().poolKind != PoolKind::Spatial) wrongPoolKind("spatial");
  return static_cast<const SpatialDevelopment&>(*development_).spatialPool();
}

std::array<double, 3> World::positionOf(size_t i) const { return development_->positionOf(i); }

const World* World::childOf(uint64_t id) const {
  if (children_.empty()) return nullptr;
  auto it = children_.find(id);
  return it == children_.end() ? nullptr : it->second.get();
}

uint64_t World::totalCells() const {
  uint64_t total = rootPool().size();
  for (const auto& [id, child] : children_) total += child->totalCells();
  return total;
}

WorldHeld World::held() const {
  WorldHeld total = heldHere();
  for (const auto& [id, child] : children_) {
    const WorldHeld nested = child->held();
    total.cells += nested.cells;
    total.bytes += nested.bytes;
  }
  // The copy kept at the last grid instant is memory, not cells of the model.
  if (onGrid_) total.bytes += onGrid_->held().bytes;
  return total;
}

void World::checkTree(const WorldHeld& tree) const {
  if (!program_->hasSystemCells) return;  // one pool, which checks itself as it grows
  checkTotalCellLimit(tree.cells, def_.limits);
  checkMemoryLimit(tree.bytes, def_.limits);
}

uint64_t World::idSalt() const {
  const uint64_t base = mixKey(kWorldIdSalt, static_cast<uint64_t>(system_));
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

bool World::integratesRates() const {
  for (const SystemDefinition& system : program_->systems)
    if (system.rates) return true;
  return false;
}

void World::advanceTo(double target, double dt) {
  if (!(dt > 0)) throw std::invalid_argument("the step must be greater than 0");
  if (target <= time_ + timeTolerance(target)) return;
  returnToGrid();
  // Steps follow the grid k * dt, so per-step rules fire at the same instants whichever
  // times the caller stops at (frames, --at); a stop between grid points develops the
  // terminal events up to it and fires no per-step rule there.
  const bool keepGrid = integratesRates();
  // Before the first step, so that a step far too small stops at once, not after the
  // limit's worth of steps.
  checkStepLimit(stats_.steps, std::ceil((target - time_) / dt), dt, target, def_.limits);
  while (time_ < target - timeTolerance(target)) {
    double k = std::floor(time_ / dt + 1e-9);
    bool onGrid = std::abs(time_ - k * dt) <= timeTolerance(time_);
    double next = (k + 1) * dt;
    checkTimeAdvances(time_, next, dt);
    checkStepLimit(stats_.steps, 1, dt, target, def_.limits);
    checkCancelled(def_.limits);
    if (next > target - timeTolerance(target)) {
      if (keepGrid && next > target + timeTolerance(target)) {
        // Integrating only up to the stop would split this step: keep the world as it is
        // on the grid and show the stop by a step of its own.
        onGrid_ = std::make_unique<World>(*this);
        onGrid_->parent_ = parent_;
      }
      next = target;
    }
    developRootStep(next, onGrid);
  }
}

void World::returnToGrid() {
  if (!onGrid_) return;
  World kept = std::move(*onGrid_);
  onGrid_.reset();
  *this = std::move(kept);
}

void World::step(double dt) {
  if (!(dt > 0)) throw std::invalid_argument("the step must be greater than 0");
  returnToGrid();
  checkTimeAdvances(time_, time_ + dt, dt);
  checkStepLimit(stats_.steps, 1, dt, time_ + dt, def_.limits);
  checkCancelled(def_.limits);
  developRootStep(time_ + dt, true);
}

void World::developRootStep(double t1, bool stepRules) {
  WorldHeld tree = held();
  tree.bytes += heldOutside_;
  developStep(t1, stepRules, tree);
}

// The ancestor values are those of the current time: made when the world is seeded and
// after every step.
void World::developStep(double t1, bool stepRules, WorldHeld& tree) {
  const WorldHeld before = heldHere();
  StepContext context = stepContext({tree.cells - before.cells, tree.bytes - before.bytes});
  development_->step(context, t1, stepRules);
  if (checksFinite_) checkFiniteState(*program_, *pool_, t1);
  const WorldHeld after = heldHere();
  tree = {tree.cells - before.cells + after.cells, tree.bytes - before.bytes + after.bytes};
  time_ = t1;
  ++stats_.steps;
  // The calls a step of a flat world without environment or ancestors needs none of are
  // not made: they were a fifth of the fixed cost of a step (the piston's).
  if (!program_->ancestorRefs.empty()) updateAncestorValues();  // as of t1, for interpretation and the next step
  if (def_.environment && program_->hasQueries) answerQueries();
  if (program_->hasSystemCells) developChildren(t1, stepRules, /*step=*/true, tree);
}

// The environment reads the word as it is now and answers its query modules; rules read
// the answers in the next step (ABOP 1.10: interpretation follows each derivation step).
void World::answerQueries() {
  if (!def_.environment || !program_->hasQueries) return;
  std::vector<QueryAnswer> answers;
  def_.environment->respond(*this, answers);
  Pool& pool = development_->pool();
  for (const QueryAnswer& answer : answers) {
    if (answer.cell >= pool.size()) continue;
    const uint32_t n = std::min<uint32_t>(program_->masters[pool.cellAt(answer.cell).master].stateCount(), 3);
    std::copy(answer.values.begin(), answer.values.begin() + n,
              pool.stateValues().data() + pool.stateOffset(answer.cell));
  }
}

// Existing children step over the same interval as this pool (when `step`); a system
// cell that appeared in this step, or is in the axiom, gets a new child, seeded at t1;
// a child whose cell is gone goes.
void World::developChildren(double t1, bool stepRules, bool step, WorldHeld& tree) {
  if (!program_->hasSystemCells) return;
  const Pool& pool = rootPool();
  std::unordered_map<uint64_t, std::unique_ptr<World>> next;
  try {
    for (CellCursor cell = pool.cursor(); !cell.done(); cell.next()) {
      if (program_->masters[cell.master()].system < 0) continue;
      const uint64_t id = cell.id();
      std::unique_ptr<World> child;
      if (auto it = children_.find(id); it != children_.end()) {
        if (step) {
          World& stepped = *it->second;
          const WorldStats before = stepped.stats_;
          stepped.developStep(t1, stepRules, tree);
          stats_.events += stepped.stats_.events - before.events;
          stats_.ruleFirings += stepped.stats_.ruleFirings - before.ruleFirings;
          stats_.cellsBorn += stepped.stats_.cellsBorn - before.cellsBorn;
          stats_.crowded += stepped.stats_.crowded - before.crowded;
          stats_.stencilSteps += stepped.stats_.stencilSteps - before.stencilSteps;
          for (size_t k = 0; k < kRewriteStrategyCount; ++k)
            stats_.rewrites[k] += stepped.stats_.rewrites[k] - before.rewrites[k];
        }
        child = std::move(it->second);
      } else {
        child = std::make_unique<World>(*this, cell.view(), &tree);
        stats_.cellsBorn += child->stats_.cellsBorn;
      }
      next.emplace(id, std::move(child));
    }
  } catch (...) {
    // A child that failed (a limit, non-finite state) stops the run, which still counts
    // the cells and bytes of every world: the children moved out go back.
    for (auto& [id, child] : next)
      if (auto it = children_.find(id); it != children_.end() && !it->second) it->second = std::move(child);
    throw;
  }
  // The children whose cells are gone go, and what they held with them.
  for (const auto& [id, child] : children_) {
    if (!child) continue;
    const WorldHeld gone = child->held();
    tree.cells -= gone.cells;
    tree.bytes -= gone.bytes;
  }
  children_ = std::move(next);
  if (!parent_) checkTotalCellLimit(totalCells(), def_.limits);
}

void World::developedValues(const CellRecord& cell, std::vector<double>& out) const {
  developedValues(cell, rootPool().stateOf(cell), out);
}

void World::developedValues(const CellRecord& cell, const double* state, std::vector<double>& out) const {
  developedValues(CellView{cell.master, state, cell.birth, cell.id, 0}, out);
}

void World::developedValues(const CellView& cell, std::vector<double>& out) const {
  const double* state = cell.state;
  const MasterCell& master = program_->masters[cell.master];
  out.assign(state, state + master.stateCount());
  if (master.developmentFunction < 0) return;
  const DevelopmentFunction& function = program_->functions[master.developmentFunction];
  double frame[CompiledExpression::kMaxStack];
  double age = time_ - cell.birth;
  for (size_t i = 0; i < function.sources.size() && i < CompiledExpression::kMaxStack; ++i) {
    int source = function.sources[i];
    frame[i] = source == DevelopmentFunction::kFromAge           ? age
               : source == DevelopmentFunction::kFromTerminalAge ? master.lifetime
                                                                 : state[source];
  }
  FunctionTable table = program_->functionTable();
  RandomStream random(mixKey(mixKey(def_.seed ^ kDevelopSalt, cell.id), keyOf(time_)));
  EvalContext context{frame, EvalEnvironment{&random, def_.seed}, &table};
  double g = program_->functionBodies[master.developmentFunction].evaluate(context);
  for (double& value : out) value *= g;
}

}  // namespace ontogen
