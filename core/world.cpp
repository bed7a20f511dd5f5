#include "core/world.h"

#include "core/linear_development.h"

#include <cmath>

namespace ontogen {

World::World(std::shared_ptr<const Program> program, WorldDef def) : program_(std::move(program)), def_(def) {
  seedAxiom();
}

World::World(const World& other)
    : program_(other.program_), def_(other.def_), pool_(other.pool_), time_(other.time_), stats_(other.stats_) {}

void World::seedAxiom() {
  const SystemDefinition& system = rootSystem();
  uint64_t index = 0;
  for (const AxiomCell& axiom : system.axiom) {
    CellRecord cell;
    cell.master = axiom.master;
    cell.birth = -axiom.age;
    cell.id = mixKey(mixKey(0x6f6e746f67656eull, static_cast<uint64_t>(program_->root)), index++);
    pool_.append(cell, axiom.values.data(), static_cast<uint32_t>(axiom.values.size()));
  }
  stats_.cellsBorn = pool_.size();
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
    LinearDevelopment development(*this);
    development.step(next, onGrid);
  }
}

void World::step(double dt) {
  LinearDevelopment development(*this);
  development.step(time_ + dt, true);
}

void World::developedValues(const CellRecord& cell, std::vector<double>& out) const {
  const MasterCell& master = program_->masters[cell.master];
  const double* state = pool_.stateOf(cell);
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
