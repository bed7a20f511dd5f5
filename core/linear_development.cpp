#include "core/linear_development.h"

#include <algorithm>
#include <cmath>

#include "core/branch_cut.h"
#include "core/cell_frame.h"
#include "core/linear_context.h"
#include "core/parents.h"
#include "core/rate_integrator.h"
#include "core/rule_choice.h"
#include "core/table_replay.h"

namespace ontogen {

namespace {
// What a module without state of the next compact word may take at most, for the memory
// limit before it is written: a two-byte label, a run of its own (14 bytes) with its first
// k in the table of wide k (8 bytes), its bitmap bit and its share of the block index (10
// bytes a block of 64, its values' offset included). Its values take 8 bytes each more.
constexpr uint64_t kCompactModuleBound = 25;
}  // namespace

LinearDevelopment::LinearDevelopment(const Program& program, const SystemDefinition& system)
    : program_(program),
      system_(system),
      functions_(program.functionTable()),
      successors_(program),
      frame_(ruleFrameSize(program)),
      decompositionFrames_(static_cast<size_t>(system.decompositionDepth) + 1),
      parallel_(program, system),
      view_(pool_, system.symbolClass),
      evaluator_(program, view_) {
  for (const MasterCell& master : program.masters) readsParents_ = readsParents_ || master.readsParent;
  std::vector<uint32_t> values;
  for (const MasterCell& master : program.masters) values.push_back(master.stateCount());
  pool_.countValues(std::move(values));
  nextWord_ = pool_.emptyCompactWord();
  // An environment writes its answers into the query modules' values as records.
  compactWords_ = parallel_.appliesToCompactWords() && !system.sampledRules && !system.rates && !readsParents_ &&
                  !program.hasQueries;
  for (const MasterCell& master : program.masters)
    compactModuleBound_ = std::max<uint64_t>(compactModuleBound_, kCompactModuleBound + 8 * master.stateCount());
}

// A copy develops on its own: its views look at its own pool.
LinearDevelopment::LinearDevelopment(const LinearDevelopment& other)
    : Development(other),
      program_(other.program_),
      system_(other.system_),
      pool_(other.pool_),
      functions_(other.functions_),
      successors_(other.program_),
      frame_(other.frame_.size()),
      decompositionFrames_(other.decompositionFrames_.size()),
      lastGrowth_(other.lastGrowth_),
      readsParents_(other.readsParents_),
      parallel_(other.program_, other.system_),
      compactWords_(other.compactWords_),
      compactModuleBound_(other.compactModuleBound_),
      nextWord_(other.pool_.emptyCompactWord()),
      view_(pool_, other.system_.symbolClass),
      evaluator_(other.program_, view_) {}

// me.parent of every cell of the word as it is now (core/parents.h).
void LinearDevelopment::findParents() {
  if (!readsParents_) return;
  axialParents(pool_.cursor(), program_.masters, parentIndex_);
  parentValues_.resize(pool_.size());
  for (size_t i = 0; i < parentValues_.size(); ++i)
    parentValues_[i] =
        parentIndex_[i] < 0 ? context_->systemCellId : idValue(pool_.cellAt(static_cast<size_t>(parentIndex_[i])).id);
}

double LinearDevelopment::earliestDeath() {
  if (earliestVersion_ != pool_.structureVersion()) {
    double earliest = kForever;
    for (CellCursor cell = pool_.cursor(); !cell.done(); cell.next())
      earliest = std::min(earliest, cell.birth() + program_.masters[cell.master()].lifetime);
    earliestDeath_ = earliest;
    earliestVersion_ = pool_.structureVersion();
  }
  return earliestDeath_;
}

// Stops at the first cell that expires (in a growing word, the first one): a word
// rewritten every step is not scanned twice.
bool LinearDevelopment::anyExpires(double horizon) {
  if (earliestVersion_ == pool_.structureVersion()) return earliestDeath_ <= horizon;
  double earliest = kForever;
  for (CellCursor cell = pool_.cursor(); !cell.done(); cell.next()) {
    const double death = cell.birth() + program_.masters[cell.master()].lifetime;
    if (death <= horizon) return true;
    earliest = std::min(earliest, death);
  }
  earliestDeath_ = earliest;
  earliestVersion_ = pool_.structureVersion();
  return false;
}

uint64_t LinearDevelopment::heldBytes() const {
  // The compact words by what they have written: a word written after a larger one keeps
  // the larger one's pages (CompactWord::heldBytes).
  const uint64_t wordRoom =
      pool_.holdsCompactWord() ? pool_.compactWord().heldBytes() - pool_.compactWord().bytes() : 0;
  return pool_.bytes() + wordRoom + nextCells_.size() * sizeof(CellRecord) + nextState_.size() * sizeof(double) +
         nextWord_.heldBytes() + parallel_.heldBytes() + scratchBytes();
}

// By capacity: these grow by appending, so what they once held was written, and stays
// resident though they are emptied. (The previous word of records counts by its size:
// the room reserved past it for the next word is not written until that word is.)
uint64_t LinearDevelopment::scratchBytes() const {
  return (expandedCells_.capacity() + work_.capacity()) * sizeof(CellRecord) +
         (expandedState_.capacity() + workState_.capacity() + parentValues_.capacity()) * sizeof(double) +
         parentIndex_.capacity() * sizeof(int64_t) + dropped_.capacity();
}

void LinearDevelopment::seed(StepContext& context) {
  pool_.storeRecords();
  seedFromAxiom(pool_, context);
}

// A compact word's records take more than the word (36 bytes a module of one value
// against about 14): they count before they are made, beside the word they are made from.
void LinearDevelopment::storeRecords() {
  if (!pool_.holdsCompactWord()) return;
  pool_.ensureIds();
  checkGrowth(*context_, pool_.size(), pool_.bytes() + pool_.recordBytes());
  pool_.storeRecords();
}

void LinearDevelopment::step(StepContext& context, double t1, bool stepRules) {
  context_ = &context;
  successors_.recordLineage(context.lineage);
  double t = context.time;
  eventsThisStep_ = 0;
  activeGroup_ = activeGroup(program_, system_, t, context.seed);
  parallel_.force(context.forcedRewrite);
  if (keepsWordCompact(parallel_.shape(compactWords_), context.rewriteBySlices, context.lineage != nullptr,
                       context.forcedRewrite)) {
    expireCompact(t, t1);
    context_ = nullptr;
    return;
  }
  storeRecords();
  if (system_.sampledRules && stepRules) applyStepRules(t);
  if (system_.rates)
    integrateAndExpire(t, t1);
  else
    expireUntil(t, t1);
  context_ = nullptr;
}

void LinearDevelopment::expireCompact(double t, double t1) {
  const double horizon = t1 + timeTolerance(t1);
  // A word rewritten by a table is written without ids, which its replay makes again if
  // a reader asks (core/table_replay.h). The pool keeps the replay, not this development.
  parallel_.writeWithoutIds(
      writesWordsWithoutIds(parallel_.shape(compactWords_), context_->wordsWithoutIds, context_->forcedRewrite));
  if (!parallel_.writesWithoutIds()) pool_.ensureIds();
  for (;;) {
    const double earliest = earliestDeath();
    if (earliest > horizon) return;
    const double instant = earliest + timeTolerance(earliest);
    pool_.storeCompactWord(context_->idSalt);
    const CompactWord& word = pool_.compactWord();
    // The serial pass stops where a limit is passed and says so: a word that would pass
    // one is left to it.
    auto fits = [&](uint64_t modules, uint64_t events, uint64_t, uint64_t heldModules) {
      if (eventsThisStep_ + events > context_->limits.maxEventsPerStep) return false;
      try {
        checkGrowth(*context_, modules, pool_.bytes() + heldModules * compactModuleBound_);
      } catch (const LimitError&) {
        return false;
      }
      return true;
    };
    const auto counts = parallel_.rewriteCompact(word, instant, activeGroup_, context_->threads, nextWord_, fits,
                                                 context_->seed, context_->ancestors);
    if (!counts) {
      // The serial pass of records takes the word on: what was written of the next word
      // goes first (at a limit of 200 MiB the runaway word held 67 MB of it beside the
      // records made).
      nextWord_ = pool_.emptyCompactWord();
      storeRecords();
      expireUntil(t, t1);
      return;
    }
    std::shared_ptr<const IdReplay> before = pool_.idReplay();
    pool_.swapCompactWord(nextWord_);
    if (parallel_.writesWithoutIds()) {
      if (const auto chain = std::dynamic_pointer_cast<const TableReplay>(before)) {
        pool_.holdWithoutIds(chain->then(instant));
      } else {
        // The word before held its ids: it is the anchor of the replay, and the next word
        // is written into fresh storage.
        auto anchor = std::make_shared<const CompactWord>(std::move(nextWord_));
        nextWord_ = pool_.emptyCompactWord();
        pool_.holdWithoutIds(std::make_shared<const TableReplay>(std::move(anchor), parallel_.table(), instant,
                                                                 context_->limits, compactModuleBound_));
      }
    }
    eventsThisStep_ += counts->events;
    context_->stats.events += counts->events;
    context_->stats.cellsBorn += counts->born;
    ++context_->stats.rewrites[static_cast<size_t>(parallel_.lastStrategy())];
    earliestDeath_ = parallel_.earliestDeath();  // found while writing the word
    earliestVersion_ = pool_.structureVersion();
    // The old word is still held beside the new one until the next instant reuses it.
    checkGrowth(*context_, pool_.size(), pool_.bytes() + nextWord_.bytes());
  }
}

void LinearDevelopment::expireUntil(double t, double t1) {
  // Decomposition follows each production step: events go instant by instant.
  if (system_.terminalContext || system_.decomposes)
    expireInTimeOrder(t, t1);
  else
    expireContextFree(t1);
}

// Rates are integrated up to each terminal event, the event happens at its instant, and
// integration goes on with the new word: a cell's successors start from its values at
// the instant it expired.
void LinearDevelopment::integrateAndExpire(double t, double t1) {
  double now = t;
  while (now < t1 - timeTolerance(t1)) {
    const double next = earliestDeath();
    const double until = next < t1 ? std::max(next, now) : t1;
    pool_.indexBranches(system_.symbolClass);
    integrateRates(rates_, program_, *context_, pool_, view_, now, until);
    expireUntil(now, until);
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
  double growth = std::max(1.25, lastGrowth_ * 1.05);
  double cap = static_cast<double>(context_->limits.maxCells) + 16;
  double cells = std::min(pool_.size() * growth + 16, cap);
  double values = std::min(pool_.stateArena().size() * growth + 16, cap * std::max<size_t>(1, frame_.size()));
  // And by the room the memory limit leaves: a word that outgrows it is copied as it
  // grows, which emit() counts, while a reserve past the limit is memory the limit never
  // saw (157 MB at a limit of 200 MiB, when the compact pass gave the runaway word up).
  const uint64_t held = pool_.bytes() + context_->elsewhere.bytes;
  const uint64_t limit = context_->limits.maxMemoryBytes;
  const double room = limit > held ? static_cast<double>(limit - held) : 0.0;
  const double wanted = cells * sizeof(CellRecord) + values * sizeof(double);
  if (wanted > room) {
    cells = std::max(16.0, cells * room / wanted);
    values = std::max(16.0, values * room / wanted);
  }
  nextCells_.reserve(static_cast<size_t>(cells));
  nextState_.reserve(static_cast<size_t>(values));
  outCells_ = &nextCells_;
  outState_ = &nextState_;
  checkInterval_ = growthCheckInterval(context_->limits);
  sinceCheck_ = 0;
}

void LinearDevelopment::finishWord() {
  if (pool_.size() > 0) lastGrowth_ = static_cast<double>(nextCells_.size()) / pool_.size();
  pool_.swapContents(nextCells_, nextState_);
  // The old word is still held beside the new one until the next step reuses it.
  checkGrowth(*context_, pool_.size(),
              pool_.bytes() + nextCells_.size() * sizeof(CellRecord) + nextState_.size() * sizeof(double));
}

void LinearDevelopment::emit(const CellRecord& cell, const double* values, uint32_t count) {
  CellRecord copy = cell;
  copy.state = static_cast<uint32_t>(outState_->size());
  // An array that grows is copied into a buffer twice its size while the old one is
  // still held: the copy counts before it is made, or a word near the limit would pass
  // it by the size of its largest array at that instant (1.8 times the limit).
  const bool cellsGrow = outCells_->size() == outCells_->capacity();
  const bool stateGrows = outState_->capacity() - outState_->size() < count;
  if (cellsGrow || stateGrows) [[unlikely]]
    checkLimits((cellsGrow ? outCells_->size() * sizeof(CellRecord) : 0) +
                (stateGrows ? outState_->size() * sizeof(double) : 0));
  if (count > 0) outState_->insert(outState_->end(), values, values + count);
  outCells_->push_back(copy);
  if (++sinceCheck_ >= checkInterval_) [[unlikely]]
    checkLimits();
}

// Within a step the new word is being written beside the old one, and cells that expire
// within the step wait on the work list: all of it counts, as it is made.
void LinearDevelopment::checkLimits(uint64_t copying) {
  sinceCheck_ = 0;
  const uint64_t cells = nextCells_.size() + work_.size() + expandedCells_.size();
  const uint64_t values = nextState_.size() + workState_.size() + expandedState_.size();
  checkGrowth(*context_, cells, pool_.bytes() + cells * sizeof(CellRecord) + values * sizeof(double) + copying);
}

// The rule frame of model/program.h: [state...] [internal state] [context...]. The
// position (me.x) is the index in the word at the start of the step; a cell born and
// expiring within one step has its ancestor's.
double* LinearDevelopment::loadFrame(const CellRecord& cell, const double* state, double when, int64_t position) {
  const double parent = readsParents_ && position >= 0 && static_cast<size_t>(position) < parentValues_.size()
                            ? parentValues_[position]
                            : -1;
  return loadCellFrame(frame_.data(), program_.masters[cell.master], cell, state, when,
                       {static_cast<double>(position), 0, 0}, parent);
}

// ---- per-step rules ----

void LinearDevelopment::applyStepRules(double t) {
  pool_.indexBranches(system_.symbolClass);
  findParents();
  beginWord();
  auto cells = pool_.cells();
  for (CellCursor at = pool_.cursor(); !at.done(); at.next()) {
    const size_t i = at.index();
    const CellRecord& cell = cells[i];
    const MasterCell& master = program_.masters[cell.master];
    if (master.rules.empty())
      emit(cell, at.state(), master.stateCount());
    else
      fireStepRules(cell, t, i);
  }
  finishWord();
}

// The per-step rule pass every pool kind shares (RuleEvaluator::fireStepRules), one cell
// at a time, in word order.
void LinearDevelopment::fireStepRules(const CellRecord& cell, double t, size_t index) {
  const MasterCell& master = program_.masters[cell.master];
  evaluator_.useParents(readsParents_ ? parentValues_.data() : nullptr);
  double* frame = evaluator_.load(index, pool_.stateArena().data(), t);
  RandomStream random(mixKey(mixKey(context_->seed ^ kStepRuleSalt, cell.id), keyOf(t)));
  EvalContext context{frame, EvalEnvironment{&random, context_->seed}, &functions_, &evaluator_};
  context.ancestors = context_->ancestors;
  if (const CompiledRule* action = evaluator_.fireStepRules(master, context, random, context_->stats.ruleFirings))
    emitSuccessors(*action, cell, frame, t, BirthCause::StepRule, context);
  else
    emit(cell, frame, master.stateCount());
}

// ---- context ----

// An L-system rule sees the classes of the ignore:/consider: line above it; its new left
// context reads the word written so far.
bool LinearDevelopment::matchContext(const CompiledRule& rule, size_t index, double* frame) {
  const auto& classOf = rule.symbolClasses < 0 ? system_.symbolClass : system_.ruleClasses[rule.symbolClasses];
  return matchLinearContext(program_, rule, pool_, index, WrittenWord{*outCells_, outState_->data()}, classOf, frame,
                            matched_);
}

// ---- terminal ages ----

const CompiledRule* LinearDevelopment::chooseRule(const std::vector<CompiledRule>& rules, int64_t index, double* frame,
                                                  RandomStream& random, const EvalContext& context) {
  auto matches = [&](const CompiledRule& rule) {
    evaluator_.useRule(rule);
    rule.clearUnbound(frame);
    if (rule.hasContext() && (index < 0 || !matchContext(rule, static_cast<size_t>(index), frame))) return false;
    return rule.predicate.empty() || rule.predicate.evaluate(context) != 0.0;
  };
  const CompiledRule* chosen = ontogen::chooseRule(rules, activeGroup_, matches, context, random, candidates_);
  if (chosen && !chosen->probability.empty()) {
    evaluator_.useRule(*chosen);
    chosen->clearUnbound(frame);
    if (chosen->hasContext()) matchContext(*chosen, static_cast<size_t>(index), frame);  // rebind its values
  }
  return chosen;
}

void LinearDevelopment::expire(const CellRecord& cell, const double* state, double when, int64_t index,
                               int64_t position) {
  checkEventLimit(++eventsThisStep_, when, context_->limits);
  ++context_->stats.events;
  const MasterCell& master = program_.masters[cell.master];
  const uint32_t n = master.stateCount();
  double* frame = loadFrame(cell, state, when, position);
  RandomStream random(mixKey(mixKey(context_->seed, cell.id), keyOf(when)));
  if (index >= 0) evaluator_.focus(static_cast<size_t>(index), pool_.stateArena().data());
  EvalContext context{frame, EvalEnvironment{&random, context_->seed}, &functions_, &evaluator_};
  context.ancestors = context_->ancestors;
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
  emitSuccessors(*rule, cell, frame, when, BirthCause::Terminal, context);
}

void LinearDevelopment::emitSuccessors(const CompiledRule& rule, const CellRecord& cell, const double* frame,
                                       double when, BirthCause cause, const EvalContext& context) {
  context_->stats.cellsBorn += successors_.write(
      rule, cell, frame, when, cause, context,
      [this](const ModuleValue& born, const double* values, uint32_t count) { emit(recordOf(born), values, count); });
}

// Without context in terminal rules, each cell develops on its own: expand it, and its
// successors in turn, until everything is alive at the end of the step. One pass.
void LinearDevelopment::expireContextFree(double t1) {
  const double horizon = t1 + timeTolerance(t1);
  const auto& masters = program_.masters;
  // Nothing expires in most animation steps: keep the word as it is.
  if (!anyExpires(horizon)) return;
  auto cells = pool_.cells();
  findParents();
  beginWord();
  const auto& classOf = system_.symbolClass;
  BranchCut cut;
  for (CellCursor at = pool_.cursor(); !at.done(); at.next()) {
    const size_t position = at.index();
    const CellRecord& cell = cells[position];
    const MasterCell& master = masters[cell.master];
    if (cut.drops(classOf[cell.master])) continue;
    if (cell.birth + master.lifetime > horizon) {
      emit(cell, at.state(), master.stateCount());
      continue;
    }
    if (classOf[cell.master] & kSymbolCut) {
      cut.start();
      continue;
    }
    // Expire straight into the word: in most steps the successors live past the horizon
    // and stay where they are written.
    const size_t firstBorn = nextCells_.size();
    expire(cell, at.state(), cell.birth + master.lifetime, -1, static_cast<int64_t>(position));
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
      if (cut.drops(classOf[item.master])) continue;
      double death = item.birth + itemMaster.lifetime;
      if (death > horizon) {
        emit(item, workState_.data() + item.state, itemMaster.stateCount());
        continue;
      }
      if (classOf[item.master] & kSymbolCut) {
        cut.start();
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
  ++context_->stats.rewrites[static_cast<size_t>(RewriteStrategy::Serial)];
}

// With context, events are processed instant by instant: all cells that reach their
// terminal age at the earliest instant of the step rewrite together, reading the word
// as it was just before; then the next instant, until the end of the step. With
// decomposition rules, every such instant and every whole time unit (L-Py's derivation
// step, even when no production fires) ends with the decomposition pass.
void LinearDevelopment::expireInTimeOrder(double t, double t1) {
  const double horizon = t1 + timeTolerance(t1);
  const auto& masters = program_.masters;
  double last = t;  // the instant processed last
  for (;;) {
    double earliest = earliestDeath();
    if (system_.decomposes) earliest = std::min(earliest, std::floor(last + timeTolerance(last)) + 1);
    if (earliest > horizon) return;
    last = earliest;
    const double instant = earliest + timeTolerance(earliest);
    pool_.indexBranches(system_.symbolClass);
    findParents();
    auto cells = pool_.cells();
    const auto& classOf = system_.symbolClass;
    beginWord();
    if (system_.backward) {
      expireBackward(instant);
    } else {
      BranchCut cut;
      for (CellCursor at = pool_.cursor(); !at.done(); at.next()) {
        const size_t i = at.index();
        const CellRecord& cell = cells[i];
        const MasterCell& master = masters[cell.master];
        if (cut.drops(classOf[cell.master])) continue;
        double death = cell.birth + master.lifetime;
        if (death > instant)
          emit(cell, at.state(), master.stateCount());
        else if (classOf[cell.master] & kSymbolCut)
          cut.start();
        else
          expire(cell, at.state(), death, static_cast<int64_t>(i), static_cast<int64_t>(i));
      }
    }
    finishWord();
    ++context_->stats.rewrites[static_cast<size_t>(RewriteStrategy::Serial)];
    if (system_.decomposes) decomposeWord(earliest);
  }
}

// The production pass of a block with a new right context `>>`: right to left, each
// module's successors written after those of the modules right of it, so that `>>` reads
// them; the new word is written reversed and turned round at the end. Which cells a cut
// drops is found first, in word order.
void LinearDevelopment::expireBackward(double instant) {
  const auto& masters = program_.masters;
  const auto cells = pool_.cells();
  const auto& classOf = system_.symbolClass;
  dropped_.assign(cells.size(), 0);
  BranchCut cut;
  for (size_t i = 0; i < cells.size(); ++i) {
    const CellRecord& cell = cells[i];
    if (cut.drops(classOf[cell.master])) {
      dropped_[i] = 1;
    } else if ((classOf[cell.master] & kSymbolCut) && cell.birth + masters[cell.master].lifetime <= instant) {
      dropped_[i] = 1;
      cut.start();
    }
  }
  // The values of cell i start where those of cell i + 1 start, less its own.
  const double* arena = pool_.stateArena().data();
  size_t offset = pool_.stateArena().size();
  for (size_t i = cells.size(); i-- > 0;) {
    const CellRecord& cell = cells[i];
    const MasterCell& master = masters[cell.master];
    offset -= master.stateCount();
    if (dropped_[i]) continue;
    const size_t first = nextCells_.size();
    const double death = cell.birth + master.lifetime;
    if (death > instant)
      emit(cell, arena + offset, master.stateCount());
    else
      expire(cell, arena + offset, death, static_cast<int64_t>(i), static_cast<int64_t>(i));
    std::reverse(nextCells_.begin() + static_cast<std::ptrdiff_t>(first), nextCells_.end());
  }
  std::reverse(nextCells_.begin(), nextCells_.end());
  // The values were written right to left: put them in word order, where the pool's
  // readers find them by summing (Pool::countValues).
  expandedState_.clear();
  for (CellRecord& cell : nextCells_) {
    const uint32_t n = masters[cell.master].stateCount();
    const uint32_t at = static_cast<uint32_t>(expandedState_.size());
    expandedState_.insert(expandedState_.end(), nextState_.begin() + cell.state, nextState_.begin() + cell.state + n);
    cell.state = at;
  }
  nextState_.swap(expandedState_);
  expandedState_.clear();
}

// ---- decomposition ----

// L-Py's decomposition pass after a production step: every module of the word, in
// order, is rewritten by its first matching decomposition rule, and what that makes is
// decomposed in turn, at most decompositionDepth rewrites deep. Like L-Py's pass, it
// applies the cuts it meets at once.
void LinearDevelopment::decomposeWord(double when) {
  pool_.indexBranches(system_.symbolClass);
  beginWord();
  const auto cells = pool_.cells();
  const auto& classOf = system_.symbolClass;
  BranchCut cut;
  for (CellCursor at = pool_.cursor(); !at.done(); at.next()) {
    const size_t i = at.index();
    const CellRecord& cell = cells[i];
    if (cut.drops(classOf[cell.master])) continue;
    if (classOf[cell.master] & kSymbolCut) {
      cut.start();
      continue;
    }
    decompose(cell, at.state(), when, static_cast<int64_t>(i), 1);
  }
  finishWord();
}

void LinearDevelopment::decompose(const CellRecord& cell, const double* state, double when, int64_t position,
                                  int depth) {
  const MasterCell& master = program_.masters[cell.master];
  if (master.decompositionRules.empty() || depth > system_.decompositionDepth) {
    emit(cell, state, master.stateCount());
    return;
  }
  // One frame per level: a successor's arguments are evaluated after deeper levels ran.
  std::vector<double>& frameAtDepth = decompositionFrames_[static_cast<size_t>(depth)];
  frameAtDepth.resize(frame_.size());
  double* frame = frameAtDepth.data();
  loadCellFrame(frame, master, cell, state, when, {static_cast<double>(position), 0, 0}, -1);
  RandomStream random(mixKey(mixKey(context_->seed ^ kDecompositionSalt, cell.id), keyOf(when)));
  EvalContext context{frame, EvalEnvironment{&random, context_->seed}, &functions_};
  context.ancestors = context_->ancestors;
  // Context is read around the module in the word the production step made (the new
  // left context in the word decomposed so far); what a decomposition makes has no place
  // in that word, so rules with context do not apply to it.
  const bool inWord = depth == 1;
  auto matches = [&](const CompiledRule& rule) {
    rule.clearUnbound(frame);
    if (rule.hasContext() && (!inWord || !matchContext(rule, static_cast<size_t>(position), frame))) return false;
    return rule.predicate.empty() || rule.predicate.evaluate(context) != 0.0;
  };
  const CompiledRule* rule =
      ontogen::chooseRule(master.decompositionRules, activeGroup_, matches, context, random, candidates_);
  if (!rule) {
    emit(cell, state, master.stateCount());
    return;
  }
  if (!rule->probability.empty()) {  // rebind its values
    rule->clearUnbound(frame);
    if (rule->hasContext()) matchContext(*rule, static_cast<size_t>(position), frame);
  }
  checkEventLimit(++eventsThisStep_, when, context_->limits);
  context_->stats.cellsBorn += successors_.write(*rule, cell, frame, when, BirthCause::Terminal, context,
                                                 [&](const ModuleValue& born, const double* values, uint32_t) {
                                                   decompose(recordOf(born), values, when, position, depth + 1);
                                                 });
}

}  // namespace ontogen
