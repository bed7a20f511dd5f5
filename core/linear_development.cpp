#include "core/linear_development.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/rate_integrator.h"
#include "lang/diagnostics.h"

namespace ontogen {

namespace {
std::string formatNumber(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

constexpr uint64_t kStepRuleSalt = 0x5354455052554c45ull;  // keeps per-step draws apart from terminal ones
constexpr size_t kLimitCheckInterval = 1 << 16;            // cells between memory checks
}  // namespace

LinearDevelopment::LinearDevelopment(World& world)
    : world_(world),
      program_(*world.program_),
      system_(world.rootSystem()),
      pool_(world.pool_),
      functions_(program_.functionTable()),
      nextCells_(world.scratchCells_),
      nextState_(world.scratchState_),
      view_(world.pool_, world.rootSystem().symbolClass),
      aggregates_(*world.program_, view_) {
  size_t frame = 0;
  size_t values = 1;
  for (const MasterCell& master : program_.masters) {
    frame = std::max<size_t>(frame, master.stateCount() + FrameSlot::kCount);
    values = std::max<size_t>(values, master.stateCount());
    for (const auto& rule : master.rules) frame = std::max<size_t>(frame, rule.frameSize);
    for (const auto& rule : master.terminalRules) frame = std::max<size_t>(frame, rule.frameSize);
  }
  frame_.resize(frame);
  values_.resize(values);
}

void LinearDevelopment::step(double t1, bool stepRules) {
  double t = world_.time_;
  eventsThisStep_ = 0;
  if (system_.sampledRules && stepRules) applyStepRules(t);
  if (system_.rates)
    integrateAndExpire(t, t1);
  else
    expireUntil(t1);
  world_.time_ = t1;
  ++world_.stats_.steps;
}

void LinearDevelopment::expireUntil(double t1) {
  if (system_.terminalContext)
    expireInTimeOrder(t1);
  else
    expireContextFree(t1);
}

// Rates are integrated up to each terminal event, the event happens at its instant, and
// integration goes on with the new word: a cell's successors start from its values at
// the instant it expired.
void LinearDevelopment::integrateAndExpire(double t, double t1) {
  const auto& masters = program_.masters;
  double now = t;
  RateIntegrator& rates = world_.rates();
  while (now < t1 - timeTolerance(t1)) {
    double next = kForever;
    for (const CellRecord& cell : pool_.cells()) next = std::min(next, cell.birth + masters[cell.master].lifetime);
    const double until = next < t1 ? std::max(next, now) : t1;
    pool_.indexBranches(system_.symbolClass);
    rates.integrate(pool_, view_, now, until);
    world_.stats_.rateEquations = rates.activeEquations();
    expireUntil(until);
    now = until;
  }
}

// ---- output ----

void LinearDevelopment::beginWord() {
  nextCells_.clear();
  nextState_.clear();
  // Expect the word to grow as it did last time (L-systems grow geometrically).
  // Capped by the cell limit: a word that would pass it stops the run anyway. Reserved
  // pages that are never written cost no memory, so the limit counts what is written.
  double growth = std::max(1.25, world_.lastGrowth_ * 1.05);
  double cap = static_cast<double>(world_.def_.limits.maxCells) + 16;
  double cells = std::min(pool_.size() * growth + 16, cap);
  double values = std::min(pool_.stateArena().size() * growth + 16, cap * std::max<size_t>(1, values_.size()));
  nextCells_.reserve(static_cast<size_t>(cells));
  nextState_.reserve(static_cast<size_t>(values));
  outCells_ = &nextCells_;
  outState_ = &nextState_;
}

void LinearDevelopment::finishWord() {
  if (pool_.size() > 0) world_.lastGrowth_ = static_cast<double>(nextCells_.size()) / pool_.size();
  pool_.swapContents(nextCells_, nextState_);
  checkLimits(pool_.size());
}

void LinearDevelopment::emit(const CellRecord& cell, const double* values, uint32_t count) {
  CellRecord copy = cell;
  copy.state = static_cast<uint32_t>(outState_->size());
  if (count > 0) outState_->insert(outState_->end(), values, values + count);
  pushCell(copy);
}

void LinearDevelopment::pushCell(const CellRecord& cell) {
  outCells_->push_back(cell);
  if (outCells_->size() % kLimitCheckInterval == 0) [[unlikely]]
    checkLimits(outCells_->size());
}

void LinearDevelopment::checkLimits(size_t cells) {
  const WorldLimits& limits = world_.def_.limits;
  if (cells > limits.maxCells)
    throw LimitError("the model grew past " + std::to_string(limits.maxCells) +
                     " cells, the cell limit; raise it with --max-cells N");
  size_t bytes = pool_.bytes() + nextCells_.size() * sizeof(CellRecord) + nextState_.size() * sizeof(double);
  if (bytes > limits.maxMemoryBytes)
    throw LimitError("the model's pools passed " + std::to_string(limits.maxMemoryBytes >> 20) +
                     " MiB, the memory limit; raise it with --max-memory MIB");
}

[[noreturn]] void LinearDevelopment::modelError(const SourceSpan& span, const std::string& message) const {
  throw ModelError(formatDiagnostic(Diagnostic{Severity::Error, span, message}));
}

// The rule frame of lang/program.h: [state...] [internal state] [context...]. The
// position (me.x) is the index in the word at the start of the step; a cell born and
// expiring within one step has its ancestor's.
double* LinearDevelopment::loadFrame(const CellRecord& cell, const double* state, double when, int64_t position) {
  const MasterCell& master = program_.masters[cell.master];
  const uint32_t n = master.stateCount();
  double* frame = frame_.data();
  std::copy(state, state + n, frame);
  frame[n + FrameSlot::kAge] = when - cell.birth;
  frame[n + FrameSlot::kTerminalAge] = master.lifetime;
  frame[n + FrameSlot::kTime] = when;
  frame[n + FrameSlot::kId] = static_cast<double>(cell.id & ((uint64_t{1} << 53) - 1));
  frame[n + FrameSlot::kX] = static_cast<double>(position);
  frame[n + FrameSlot::kY] = 0;
  frame[n + FrameSlot::kZ] = 0;
  return frame;
}

// ---- per-step rules ----

void LinearDevelopment::applyStepRules(double t) {
  pool_.indexBranches(system_.symbolClass);
  beginWord();
  auto cells = pool_.cells();
  for (size_t i = 0; i < cells.size(); ++i) {
    const CellRecord& cell = cells[i];
    const MasterCell& master = program_.masters[cell.master];
    if (master.rules.empty())
      emit(cell, pool_.stateOf(cell), master.stateCount());
    else
      fireStepRules(cell, pool_.stateOf(cell), t, i);
  }
  finishWord();
}

void LinearDevelopment::fireStepRules(const CellRecord& cell, const double* state, double t, size_t index) {
  const MasterCell& master = program_.masters[cell.master];
  const uint32_t n = master.stateCount();
  double* frame = loadFrame(cell, state, t, static_cast<int64_t>(index));
  RandomStream random(mixKey(mixKey(world_.def_.seed ^ kStepRuleSalt, cell.id), keyOf(t)));
  aggregates_.focus(index, pool_.stateArena().data());
  EvalContext context{frame, EvalEnvironment{&random, world_.def_.seed}, &functions_, &aggregates_};
  context.ancestors = world_.ancestorValues();
  for (const CompiledRule& rule : master.rules) {
    if (!rule.hasDiscrete) continue;  // rate-only rules act while integrating
    aggregates_.useRule(rule);
    if (rule.hasContext() && !matchContext(rule, index, frame)) continue;
    if (!rule.predicate.empty() && rule.predicate.evaluate(context) == 0.0) continue;
    // Per-step rules with a probability fire with that probability when they match.
    if (!rule.probability.empty() && !(random.uniform() < rule.probability.evaluate(context))) continue;
    for (const StateCalculation& calculation : rule.calculations)
      if (!calculation.isRate) frame[calculation.slot] = calculation.value.evaluate(context);
    ++world_.stats_.ruleFirings;
    if (rule.hasAction) {
      emitSuccessors(rule, cell, frame, t, /*renewMe=*/false, context);
      return;
    }
  }
  emit(cell, frame, n);
}

// ---- context ----

bool LinearDevelopment::matchContext(const CompiledRule& rule, size_t index, double* frame) {
  const auto& classOf = system_.symbolClass;
  if (!rule.leftItems.empty()) {
    if (!pool_.matchLeft(index, rule.leftItems, classOf, matched_)) return false;
    for (size_t k = 0; k < rule.left.size(); ++k) {
      const ContextBinding& binding = rule.left[k];
      if (binding.count == 0) continue;
      const double* values = pool_.stateOf(pool_.cells()[matched_[k]]);
      std::copy(values, values + binding.count, frame + binding.firstSlot);
    }
  }
  if (!rule.rightItems.empty()) {
    if (!pool_.matchRight(index, rule.rightItems, classOf, matched_)) return false;
    for (size_t k = 0; k < rule.right.size(); ++k) {
      const ContextBinding& binding = rule.right[k];
      if (binding.count == 0) continue;
      const double* values = pool_.stateOf(pool_.cells()[matched_[k]]);
      std::copy(values, values + binding.count, frame + binding.firstSlot);
    }
  }
  return true;
}

// ---- terminal ages ----

const CompiledRule* LinearDevelopment::chooseRule(const std::vector<CompiledRule>& rules, int64_t index, double* frame,
                                                  RandomStream& random, const EvalContext& context) {
  auto matches = [&](const CompiledRule& rule) {
    aggregates_.useRule(rule);
    if (rule.hasContext() && (index < 0 || !matchContext(rule, static_cast<size_t>(index), frame))) return false;
    return rule.predicate.empty() || rule.predicate.evaluate(context) != 0.0;
  };
  for (size_t r = 0; r < rules.size(); ++r) {
    const CompiledRule& rule = rules[r];
    if (!matches(rule)) continue;
    if (rule.probability.empty()) return &rule;
    // A stochastic production: choose among it and the later matching stochastic
    // alternatives, weighted by their probabilities.
    candidates_.clear();
    double total = 0;
    for (size_t s = r; s < rules.size(); ++s) {
      if (rules[s].probability.empty() || (s != r && !matches(rules[s]))) continue;
      double weight = std::max(0.0, rules[s].probability.evaluate(context));
      candidates_.push_back({&rules[s], weight});
      total += weight;
    }
    if (!(total > 0)) return nullptr;
    double x = random.uniform() * total;
    const CompiledRule* chosen = candidates_.back().first;
    for (const auto& [candidate, weight] : candidates_) {
      if (x < weight) {
        chosen = candidate;
        break;
      }
      x -= weight;
    }
    aggregates_.useRule(*chosen);
    if (chosen->hasContext()) matchContext(*chosen, static_cast<size_t>(index), frame);  // rebind its values
    return chosen;
  }
  return nullptr;
}

void LinearDevelopment::expire(const CellRecord& cell, const double* state, double when, int64_t index,
                               int64_t position) {
  if (++eventsThisStep_ > world_.def_.limits.maxEventsPerStep)
    throw LimitError("more than " + std::to_string(world_.def_.limits.maxEventsPerStep) +
                     " terminal-age events in one step (near t = " + std::to_string(when) +
                     "); a lifetime much shorter than the step? Use a smaller --step, or raise --max-events N");
  ++world_.stats_.events;
  const MasterCell& master = program_.masters[cell.master];
  const uint32_t n = master.stateCount();
  double* frame = loadFrame(cell, state, when, position);
  RandomStream random(mixKey(mixKey(world_.def_.seed, cell.id), keyOf(when)));
  if (index >= 0) aggregates_.focus(static_cast<size_t>(index), pool_.stateArena().data());
  EvalContext context{frame, EvalEnvironment{&random, world_.def_.seed}, &functions_, &aggregates_};
  context.ancestors = world_.ancestorValues();
  const CompiledRule* rule = chooseRule(master.terminalRules, index, frame, random, context);
  if (rule) {
    for (const StateCalculation& calculation : rule->calculations)
      frame[calculation.slot] = calculation.value.evaluate(context);
  }
  if (!rule || !rule->hasAction) {
    // No production applies: the cell renews itself (its age starts again from 0).
    CellRecord renewed = cell;
    renewed.birth = when;
    emit(renewed, frame, n);
    return;
  }
  emitSuccessors(*rule, cell, frame, when, /*renewMe=*/true, context);
}

void LinearDevelopment::emitSuccessors(const CompiledRule& rule, const CellRecord& cell, const double* frame,
                                       double when, bool renewMe, const EvalContext& context) {
  // Per-step births get other ids than terminal births of the same cell at the same instant.
  uint64_t lineage = mixKey(cell.id, keyOf(when)) ^ (renewMe ? 0 : kStepRuleSalt);
  uint64_t k = 0;
  uint64_t born = 0;
  for (const SuccessorTemplate& successor : rule.successors) {
    ++k;
    if (successor.stateless) {
      // The common case of a bare symbol born at age 0: nothing to evaluate or check.
      pushCell(CellRecord{successor.master, static_cast<uint32_t>(outState_->size()), when, mixKey(lineage, k)});
      ++born;
      continue;
    }
    if (successor.isMe) {
      CellRecord me = cell;
      if (renewMe) me.birth = when;
      emit(me, frame, program_.masters[cell.master].stateCount());
      continue;
    }
    const MasterCell& target = program_.masters[successor.master];
    const uint32_t count = target.stateCount();
    for (uint32_t j = 0; j < count; ++j) values_[j] = successor.args[j].evaluate(context);
    double age = successor.birthAge.empty() ? 0.0 : successor.birthAge.evaluate(context);
    if (!(age >= 0) || age >= target.lifetime) {
      modelError(successor.span,
                 "'" + target.label + "' would be born with age " + formatNumber(age) +
                     (age >= target.lifetime ? ", not below its terminal age " + formatNumber(target.lifetime)
                                             : ", but ages are ≥ 0") +
                     " (in a rule of '" + program_.masters[cell.master].label + "' at t = " + formatNumber(when) + ")");
    }
    emit(CellRecord{successor.master, 0, when - age, mixKey(lineage, k)}, values_.data(), count);
    ++born;
  }
  world_.stats_.cellsBorn += born;
}

// Without context in terminal rules, each cell develops on its own: expand it, and its
// successors in turn, until everything is alive at the end of the step. One pass.
void LinearDevelopment::expireContextFree(double t1) {
  const double horizon = t1 + timeTolerance(t1);
  const auto& masters = program_.masters;
  auto cells = pool_.cells();
  // Nothing expires in most animation steps: keep the word as it is.
  bool any = false;
  for (const CellRecord& cell : cells)
    if (cell.birth + masters[cell.master].lifetime <= horizon) {
      any = true;
      break;
    }
  if (!any) return;
  beginWord();
  for (size_t position = 0; position < cells.size(); ++position) {
    const CellRecord& cell = cells[position];
    const MasterCell& master = masters[cell.master];
    if (cell.birth + master.lifetime > horizon) {
      emit(cell, pool_.stateOf(cell), master.stateCount());
      continue;
    }
    // Expire straight into the word: in most steps the successors live past the horizon
    // and stay where they are written.
    const size_t firstBorn = nextCells_.size();
    expire(cell, pool_.stateOf(cell), cell.birth + master.lifetime, -1, static_cast<int64_t>(position));
    bool chained = false;
    for (size_t i = firstBorn; i < nextCells_.size() && !chained; ++i)
      chained = nextCells_[i].birth + masters[nextCells_[i].master].lifetime <= horizon;
    if (!chained) continue;
    // Some successors expire within the step too: take them back and expand depth first.
    work_.clear();
    workState_.clear();
    const uint32_t stateBase = nextCells_[firstBorn].state;
    workState_.assign(nextState_.begin() + stateBase, nextState_.end());
    for (size_t i = nextCells_.size(); i-- > firstBorn;) {
      CellRecord pending = nextCells_[i];
      pending.state -= stateBase;
      work_.push_back(pending);
    }
    nextCells_.resize(firstBorn);
    nextState_.resize(stateBase);
    while (!work_.empty()) {
      CellRecord item = work_.back();
      work_.pop_back();
      const MasterCell& itemMaster = masters[item.master];
      double death = item.birth + itemMaster.lifetime;
      if (death > horizon) {
        emit(item, workState_.data() + item.state, itemMaster.stateCount());
        continue;
      }
      // Expire into a side list, then push its results so the leftmost comes out first.
      CellArray* savedCells = outCells_;
      StateArray* savedState = outState_;
      expandedCells_.clear();
      expandedState_.clear();
      outCells_ = &expandedCells_;
      outState_ = &expandedState_;
      expire(item, workState_.data() + item.state, death, -1, static_cast<int64_t>(position));
      outCells_ = savedCells;
      outState_ = savedState;
      uint32_t base = static_cast<uint32_t>(workState_.size());
      workState_.insert(workState_.end(), expandedState_.begin(), expandedState_.end());
      for (auto it = expandedCells_.rbegin(); it != expandedCells_.rend(); ++it) {
        CellRecord next = *it;
        next.state += base;
        work_.push_back(next);
      }
    }
  }
  finishWord();
}

// With context, events are processed instant by instant: all cells that reach their
// terminal age at the earliest instant of the step rewrite together, reading the word
// as it was just before; then the next instant, until the end of the step.
void LinearDevelopment::expireInTimeOrder(double t1) {
  const double horizon = t1 + timeTolerance(t1);
  const auto& masters = program_.masters;
  for (;;) {
    double earliest = kForever;
    for (const CellRecord& cell : pool_.cells())
      earliest = std::min(earliest, cell.birth + masters[cell.master].lifetime);
    if (earliest > horizon) return;
    const double instant = earliest + timeTolerance(earliest);
    pool_.indexBranches(system_.symbolClass);
    beginWord();
    auto cells = pool_.cells();
    for (size_t i = 0; i < cells.size(); ++i) {
      const CellRecord& cell = cells[i];
      const MasterCell& master = masters[cell.master];
      double death = cell.birth + master.lifetime;
      if (death <= instant)
        expire(cell, pool_.stateOf(cell), death, static_cast<int64_t>(i), static_cast<int64_t>(i));
      else
        emit(cell, pool_.stateOf(cell), master.stateCount());
    }
    finishWord();
  }
}

}  // namespace ontogen
