#include "core/parallel_rewrite.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <stdexcept>

#include "core/cell_frame.h"
#include "core/linear_context.h"
#include "core/parallel_for.h"
#include "core/rule_choice.h"
#include "core/rule_evaluator.h"
#include "core/salts.h"
#include "lang/expression_batch.h"
#include "lang/random.h"
#include "pools/large_page_allocator.h"

namespace ontogen {

namespace {
// Slices per thread: enough that one slice heavier than the others does not hold up the
// rest, few enough that their bookkeeping costs nothing.
constexpr size_t kSlicesPerThread = 4;

bool bindsNothing(const std::vector<ContextBinding>& side) {
  for (const ContextBinding& binding : side)
    if (binding.count > 0 || binding.arity >= 0) return false;
  return true;
}

// Whether a master's rules are chosen by comparing labels alone and write no state; with
// `chances`, rules with constant probabilities count too (a draw then chooses among them).
bool comparesLabelsOnly(const Program& program, const MasterCell& master, bool chances = false) {
  if (master.stateCount() > 0) return false;
  for (const CompiledRule& rule : master.terminalRules) {
    const bool chanceAllowed = rule.probability.empty() || (chances && rule.probability.isConstant());
    if (!rule.predicate.empty() || !chanceAllowed || !rule.calculations.empty() || !rule.aggregates.empty() ||
        !rule.unboundSlots.empty() || !bindsNothing(rule.left) || !bindsNothing(rule.right) ||
        !bindsNothing(rule.newLeft) || !bindsNothing(rule.newRight))
      return false;
    for (const SuccessorTemplate& successor : rule.successors)
      if (!successor.isMe && !(successor.stateless && program.masters[successor.master].stateCount() == 0))
        return false;
  }
  return true;
}
}  // namespace

ParallelRewrite::LabelRule ParallelRewrite::labelRule(const Program& program, uint32_t master,
                                                      const CompiledRule& rule) const {
  LabelRule choice;
  choice.rule = &rule;
  choice.group = rule.group;
  choice.context = rule.hasContext();
  choice.variant = rule.variant;
  choice.stochastic = !rule.probability.empty();
  if (choice.stochastic) choice.chance = rule.probability.constantValue();
  if (rule.hasAction)
    for (const SuccessorTemplate& successor : rule.successors) {
      ++choice.cells;
      choice.values += successor.isMe ? 0 : program.masters[successor.master].stateCount();
      choice.born += successor.isMe ? 0 : 1;
      const uint32_t label = successor.isMe ? master : successor.master;
      choice.written.push_back({label, successor.isMe || successor.keepsIdentity});
      choice.shortestLife = std::min(choice.shortestLife, program.masters[label].lifetime);
    }
  const bool allFresh = std::none_of(choice.written.begin(), choice.written.end(),
                                     [](const LabelRule::Written& successor) { return successor.keepsId; });
  if (allFresh && choice.cells <= CompactWord::kLargestRunK)
    for (const LabelRule::Written& successor : choice.written) choice.freshLabels.push_back(successor.label);
  auto code = [](const ContextItem& item) {
    switch (item.kind) {
      case ContextItem::Kind::Module:
        return static_cast<int32_t>(item.master);
      case ContextItem::Kind::Any:
        return kAnyLabel;
      case ContextItem::Kind::End:
        return kEndLabel;
      default:
        return kNoMatch;  // a bracket, in a word that has none
    }
  };
  if (plain_ && rule.leftItems.size() <= kPositionItems && rule.rightItems.size() <= kPositionItems &&
      rule.symbolClasses < 0) {
    choice.byPosition = true;
    choice.leftCount = static_cast<uint8_t>(rule.leftItems.size());
    choice.rightCount = static_cast<uint8_t>(rule.rightItems.size());
    for (size_t k = 0; k < rule.leftItems.size(); ++k) choice.left[k] = code(rule.leftItems[k]);
    for (size_t k = 0; k < rule.rightItems.size(); ++k) choice.right[k] = code(rule.rightItems[k]);
  }
  return choice;
}

ParallelRewrite::ParallelRewrite(const Program& program, const SystemDefinition& system)
    : program_(program), system_(system), functions_(program.functionTable()), frameSize_(ruleFrameSize(program)) {
  for (const MasterCell& master : program.masters) lifetimes_.push_back(master.lifetime);
  for (uint8_t symbolClass : system.symbolClass)
    if (symbolClass & kSymbolCut) contextFree_ = atInstants_ = false;
  if (system.backward || system.decomposes) atInstants_ = false;
  auto plain = [](const std::vector<uint8_t>& classes) {
    return std::all_of(classes.begin(), classes.end(), [](uint8_t c) { return c == kSymbolModule; });
  };
  plain_ = plain(system.symbolClass) && std::all_of(system.ruleClasses.begin(), system.ruleClasses.end(), plain);
  labelsOnly_.resize(program.masters.size());
  shortestLife_.resize(program.masters.size());
  for (size_t m = 0; m < program.masters.size(); ++m) {
    const MasterCell& master = program.masters[m];
    labelsOnly_[m] = comparesLabelsOnly(program, master) && master.terminalRules.size() < UINT16_MAX;
    // Rules with a chance: a draw weighs at most kMostDrawn of them.
    const bool fewDrawn = std::count_if(master.terminalRules.begin(), master.terminalRules.end(),
                                        [](const CompiledRule& rule) { return !rule.probability.empty(); }) <=
                          static_cast<std::ptrdiff_t>(kMostDrawn);
    const bool drawsByLabels = !labelsOnly_[m] && fewDrawn && comparesLabelsOnly(program, master, true);
    std::vector<LabelRule>& choices = labelRules_.emplace_back();
    if (labelsOnly_[m] || drawsByLabels)
      for (const CompiledRule& rule : master.terminalRules)
        choices.push_back(labelRule(program, static_cast<uint32_t>(m), rule));
    const bool fixed =
        master.terminalRules.empty() || (master.terminalRules.size() == 1 && master.terminalRules.front().group == 0 &&
                                         !master.terminalRules.front().hasContext());
    fixedChoice_.push_back(labelsOnly_[m] && fixed);
    anyChoiceVaries_ = anyChoiceVaries_ || (labelsOnly_[m] && !fixed) || drawsByLabels;
    allLabelsOnly_ = allLabelsOnly_ && labelsOnly_[m];
    for (const LabelRule& choice : choices) allByPosition_ = allByPosition_ && (!choice.context || choice.byPosition);
    double shortest = master.lifetime;  // a renewal
    bool choosesInFrame = false;
    for (const CompiledRule& rule : master.terminalRules) {
      if (!rule.newLeft.empty() || !rule.newRight.empty() || !rule.aggregates.empty() || rule.contextDimensions != 1)
        atInstants_ = false;
      anyContext_ = anyContext_ || rule.hasContext() || !rule.leftItems.empty() || !rule.rightItems.empty();
      // A condition or a chance that is an expression is evaluated in the cell's frame
      // (choose), a constant chance drawn from the cell's stream alone (drawByChances).
      if (rule.group != 0 || rule.hasContext() || !rule.aggregates.empty()) contextFree_ = false;
      choosesInFrame =
          choosesInFrame || !rule.predicate.empty() || (!rule.probability.empty() && !rule.probability.isConstant());
      oneForOne_ = oneForOne_ && (!rule.hasAction || rule.successors.size() == 1);
      for (const SuccessorTemplate& successor : rule.successors) {
        if (!successor.birthAge.empty()) contextFree_ = atInstants_ = false;
        shortest = std::min(shortest, successor.isMe ? master.lifetime : program.masters[successor.master].lifetime);
      }
    }
    // Several rules: the first one, a draw among them when it has a chance, or a choice
    // in the cell's frame (also past kMostDrawn rules with a chance).
    choosesInFrame = choosesInFrame || !fewDrawn;
    const bool draws =
        !choosesInFrame && !master.terminalRules.empty() && !master.terminalRules.front().probability.empty();
    drawsByChance_.push_back(draws);
    choosesInFrame_.push_back(choosesInFrame);
    shortestLife_[m] = shortest;
    evaluatesInBatches_.push_back(!labelsOnly_[m] && evaluatesInBatches(program, master, draws));
    const bool compactBatched =
        evaluatesInBatches_[m] && !drawsByLabels && !master.readsPosition && !master.readsParent;
    compactBatched_.push_back(compactBatched);
    anyCompactBatched_ = anyCompactBatched_ || compactBatched;
    allCompact_ = allCompact_ && (labelsOnly_[m] || drawsByLabels || compactBatched);
    anyState_ = anyState_ || master.stateCount() > 0;
    withValues_ = anyState_ || anyCompactBatched_;
    firstRule_.push_back(static_cast<uint32_t>(batchedValues_.size()));
    for (const CompiledRule& rule : master.terminalRules) {
      uint32_t values = 0;
      for (const SuccessorTemplate& successor : rule.successors)
        if (!successor.isMe && !successor.stateless) values += program.masters[successor.master].stateCount();
      batchedValues_.push_back(values);
      batchedRules_.push_back(compactBatched ? labelRule(program, static_cast<uint32_t>(m), rule) : LabelRule{});
    }
    allInBatchesOrLabelsOnly_ = allInBatchesOrLabelsOnly_ && (labelsOnly_[m] || evaluatesInBatches_[m]);
  }

  byTable_ = program.masters.size() <= 256;  // one-byte labels
  std::vector<uint32_t> stateCounts;
  for (uint32_t m = 0; byTable_ && m < program.masters.size(); ++m) {
    byTable_ = tableEntry(program, m);
    stateCounts.push_back(program.masters[m].stateCount());
  }
  if (byTable_) table_.finish(std::move(stateCounts));
}

// What master m does by the table, when it always does the same: a master of labels alone
// with a fixed choice, or one whose one rule (group 0, no chance, condition, context or
// calculation) computes each of its successors' values by one operation on the cell's
// own values (ValueOperation: `A(x) -> A(x + 1) B(x * 0.5)`). New successors all take
// fresh ids; a master without a rule is renewed with its values.
bool ParallelRewrite::tableEntry(const Program& program, uint32_t m) {
  const MasterCell& master = program.masters[m];
  RewriteTable::Entry entry;
  entry.lifetime = entry.lifeAfter = master.lifetime;
  if (labelsOnly_[m] && fixedChoice_[m]) {
    const LabelRule* choice = fixedRule(m);
    if (choice && choice->rule->hasAction) {
      if (choice->freshLabels.empty()) return false;  // a successor keeps the cell's id
      entry.lifeAfter = choice->shortestLife;
      table_.setSuccessors(entry, choice->freshLabels);
    }
    table_.entries.push_back(entry);
    return true;
  }
  if (!compactBatched_[m] || master.terminalRules.size() > 1) return false;
  if (!master.terminalRules.empty() && master.terminalRules.front().hasAction) {
    const CompiledRule& rule = master.terminalRules.front();
    if (rule.group != 0 || !rule.probability.empty() || rule.hasContext()) return false;
    const LabelRule& choice = batchedRules_[firstRule_[m]];
    if (choice.freshLabels.empty()) return false;
    std::vector<ValueOperation> operations;
    for (const SuccessorTemplate& successor : rule.successors) {
      if (successor.stateless) continue;
      for (uint32_t v = 0; v < program.masters[successor.master].stateCount(); ++v)
        if (!successor.args[v].asValueOperation(static_cast<int>(master.stateCount()), operations.emplace_back()))
          return false;
    }
    entry.lifeAfter = choice.shortestLife;
    table_.setSuccessors(entry, choice.freshLabels);
    table_.setOperations(entry, operations);
  }
  table_.entries.push_back(entry);
  return true;
}

bool ParallelRewrite::evaluatesInBatches(const Program& program, const MasterCell& master, bool draws) const {
  if (master.terminalRules.empty()) return true;  // renews itself
  if (master.terminalRules.size() > 1 && !draws) return false;
  const int slots = static_cast<int>(frameSize_);
  for (const CompiledRule& rule : master.terminalRules) {
    const bool constantChance = rule.probability.empty() || rule.probability.isConstant();
    if (rule.group != 0 || !rule.predicate.empty() || !constantChance || rule.hasContext() ||
        !rule.aggregates.empty() || !rule.calculations.empty() || !rule.unboundSlots.empty())
      return false;
    for (const SuccessorTemplate& successor : rule.successors) {
      if (!successor.birthAge.empty()) return false;
      if (successor.isMe || successor.stateless) continue;
      const uint32_t count = program.masters[successor.master].stateCount();
      if (successor.args.size() < count) return false;
      for (uint32_t j = 0; j < count; ++j)
        if (!successor.args[j].batchable(slots)) return false;
    }
  }
  return true;
}

// As ontogen::chooseRule draws for rules that all apply (core/rule_choice.h; no context,
// so no variants): the first rule's draw among the rules with a chance, from the stream
// LinearDevelopment::expire gives the cell.
const CompiledRule* ParallelRewrite::drawByChances(const MasterCell& master, uint64_t seed, uint64_t id, double death) {
  const std::vector<CompiledRule>& rules = master.terminalRules;
  double total = 0;
  for (const CompiledRule& rule : rules)
    if (!rule.probability.empty()) total += std::max(0.0, rule.probability.constantValue());
  if (!(total > 0)) return nullptr;
  const CompiledRule* drawn[kMostDrawn];
  size_t count = 0;
  for (const CompiledRule& rule : rules)
    if (!rule.probability.empty()) drawn[count++] = &rule;
  RandomStream random(mixKey(mixKey(seed, id), keyOf(death)));
  return drawn[pickByWeight(random.uniform(), total, count,
                            [&](size_t c) { return std::max(0.0, drawn[c]->probability.constantValue()); })];
}

const CompiledRule* ParallelRewrite::contextFreeRule(const MasterCell& master, uint32_t label, uint64_t seed,
                                                     uint64_t id, double death) const {
  if (master.terminalRules.empty()) return nullptr;
  return drawsByChance_[label] ? drawByChances(master, seed, id, death) : &master.terminalRules.front();
}

bool ParallelRewrite::matchesLabels(const Step& step, const CompiledRule& rule, size_t i, Worker& worker) const {
  if (plain_) {
    // No bracket and nothing ignored: the k-th context item is the k-th cell away, and a
    // match compares labels, as LinearPool::matchLeft and matchRight find it there.
    const auto cells = step.pool.cells();
    for (size_t k = 0; k < rule.leftItems.size(); ++k) {
      const ContextItem& item = rule.leftItems[k];
      if (i < k + 1) return item.kind == ContextItem::Kind::End;  // the start of the word
      if (item.kind != ContextItem::Kind::Any &&
          (item.kind != ContextItem::Kind::Module || cells[i - 1 - k].master != item.master))
        return false;
    }
    for (size_t k = 0; k < rule.rightItems.size(); ++k) {
      const ContextItem& item = rule.rightItems[k];
      if (i + 1 + k >= cells.size()) return item.kind == ContextItem::Kind::End;  // the end of the word
      if (item.kind != ContextItem::Kind::Any &&
          (item.kind != ContextItem::Kind::Module || cells[i + 1 + k].master != item.master))
        return false;
    }
    return true;
  }
  const auto& classOf = rule.symbolClasses < 0 ? system_.symbolClass : system_.ruleClasses[rule.symbolClasses];
  if (!rule.leftItems.empty() && !step.pool.matchLeft(i, rule.leftItems, classOf, worker.matched)) return false;
  if (!rule.rightItems.empty() && !step.pool.matchRight(i, rule.rightItems, classOf, worker.matched)) return false;
  return true;
}

// As matchesLabels in a plain word, from the codes labelRule made.
template <class Labels>
inline bool ParallelRewrite::matchesByPosition(const Labels& labels, size_t size, const LabelRule& choice, size_t i) {
  for (size_t k = 0; k < choice.leftCount; ++k) {
    const int32_t expected = choice.left[k];
    if (i < k + 1) return expected == kEndLabel;  // the start of the word
    if (expected != kAnyLabel && (expected < 0 || labels[i - 1 - k] != static_cast<uint32_t>(expected))) return false;
  }
  for (size_t k = 0; k < choice.rightCount; ++k) {
    const int32_t expected = choice.right[k];
    if (i + 1 + k >= size) return expected == kEndLabel;  // the end of the word
    if (expected != kAnyLabel && (expected < 0 || labels[i + 1 + k] != static_cast<uint32_t>(expected))) return false;
  }
  return true;
}

namespace {
// The labels of a word of records, and of a compact word, as matchesByPosition reads them.
struct RecordLabels {
  std::span<const CellRecord> cells;
  uint32_t operator[](size_t i) const { return cells[i].master; }
};
struct CompactLabels {
  const CompactWord& word;
  uint32_t operator[](size_t i) const { return word.label(i); }
};
// The same for a word of one-byte labels, the usual case, without a test per read.
struct ByteLabels {
  const uint8_t* labels;
  uint32_t operator[](size_t i) const { return labels[i]; }
};
}  // namespace

inline const ParallelRewrite::LabelRule* ParallelRewrite::chooseByLabels(Pass pass, const Step& step, size_t i,
                                                                         Worker& worker) const {
  const CellRecord& cell = step.pool.cells()[i];
  for (const LabelRule& choice : labelRules_[cell.master]) {
    if (choice.group != 0 && choice.group != step.group) continue;
    if (!choice.context) return &choice;
    if (pass != Pass::AtInstant) continue;
    const auto cells = step.pool.cells();
    if (choice.byPosition ? matchesByPosition(RecordLabels{cells}, cells.size(), choice, i)
                          : matchesLabels(step, *choice.rule, i, worker))
      return &choice;
  }
  return nullptr;
}

const CompiledRule* ParallelRewrite::choose(Pass pass, const Step& step, size_t i, const double* state, double death,
                                            Worker& worker, RandomStream& random, const EvalContext& evaluation) const {
  const CellRecord& cell = step.pool.cells()[i];
  const MasterCell& master = program_.masters[cell.master];
  double* frame = worker.frame.data();
  loadCellFrame(frame, master, cell, state, death, {static_cast<double>(i), 0, 0}, step.parents ? step.parents[i] : -1);
  auto classOf = [&](const CompiledRule& rule) -> const std::vector<uint8_t>& {
    return rule.symbolClasses < 0 ? system_.symbolClass : system_.ruleClasses[rule.symbolClasses];
  };
  auto matches = [&](const CompiledRule& rule) {
    rule.clearUnbound(frame);
    if (rule.hasContext() &&
        (pass == Pass::ContextFree ||
         !matchLinearContext(program_, rule, step.pool, i, WrittenWord{}, classOf(rule), frame, worker.matched)))
      return false;
    return rule.predicate.empty() || rule.predicate.evaluate(evaluation) != 0.0;
  };
  const CompiledRule* chosen =
      ontogen::chooseRule(master.terminalRules, step.group, matches, evaluation, random, worker.candidates);
  if (chosen && !chosen->probability.empty()) {  // rebind its values
    chosen->clearUnbound(frame);
    if (chosen->hasContext())
      matchLinearContext(program_, *chosen, step.pool, i, WrittenWord{}, classOf(*chosen), frame, worker.matched);
  }
  return chosen;
}

void ParallelRewrite::count(Pass pass, const Step& step, Slice& slice, Worker& worker) {
  const auto cells = step.pool.cells();
  const auto& masters = program_.masters;
  worker.frame.resize(frameSize_);
  // The values of the slice's cells, in order (the pool counts them: Pool::countValues).
  for (CellCursor at = step.pool.cursor(slice.begin); at.index() < slice.end; at.next()) {
    const size_t i = at.index();
    const CellRecord& cell = cells[i];
    const MasterCell& master = masters[cell.master];
    const double death = cell.birth + master.lifetime;
    if (death > step.horizon) {
      ++slice.cells;
      slice.values += master.stateCount();
      continue;
    }
    ++slice.events;
    // As the serial pass finds it: a successor born at `death` that expires by the horizon.
    if (pass == Pass::ContextFree && death + shortestLife_[cell.master] <= step.horizon) slice.chained = true;
    if (labelsOnly_[cell.master]) {
      const std::vector<LabelRule>& rules = labelRules_[cell.master];
      const LabelRule* choice = fixedChoice_[cell.master] ? (rules.empty() ? nullptr : &rules.front())
                                                          : chooseByLabels(pass, step, i, worker);
      if (!fixedChoice_[cell.master])
        chosen_[i] = choice ? static_cast<uint16_t>(choice->rule - master.terminalRules.data() + 1) : 0;
      if (choice && choice->rule->hasAction) {
        slice.cells += choice->cells;
        slice.values += choice->values;
        slice.born += choice->born;
      } else {
        ++slice.cells;  // renewed, without state
      }
      continue;
    }
    const CompiledRule* rule = nullptr;
    if (pass == Pass::ContextFree && !choosesInFrame_[cell.master]) {
      // No choice to make but a draw among constant chances (rules of group 0, without
      // condition or context): what it writes is counted without loading the cell's frame.
      rule = contextFreeRule(master, cell.master, step.context.seed, cell.id, death);
    } else {
      RandomStream random(mixKey(mixKey(step.context.seed, cell.id), keyOf(death)));
      EvalContext evaluation{worker.frame.data(), EvalEnvironment{&random, step.context.seed}, &functions_, nullptr};
      evaluation.ancestors = step.context.ancestors;
      rule = choose(pass, step, i, at.state(), death, worker, random, evaluation);
    }
    if (!rule || !rule->hasAction) {
      ++slice.cells;
      slice.values += master.stateCount();
      continue;
    }
    for (const SuccessorTemplate& successor : rule->successors) {
      ++slice.cells;
      slice.values += successor.isMe ? master.stateCount() : masters[successor.master].stateCount();
      slice.born += successor.isMe ? 0 : 1;
    }
  }
}

// What LinearDevelopment::expire does, written in place.
void ParallelRewrite::write(Pass pass, const Step& step, Slice& slice, uint64_t firstCell, uint64_t firstValue,
                            Worker& worker, CellArray& cells, StateArray& state) const {
  const auto word = step.pool.cells();
  const auto& masters = program_.masters;
  CellRecord* outCells = cells.data() + firstCell;
  double* outValues = state.data();
  uint64_t valueAt = firstValue;
  double earliest = kForever;
  const double* lifetimes = lifetimes_.data();
  auto put = [&](const CellRecord& record, const double* values, uint32_t count) {
    earliest = std::min(earliest, record.birth + lifetimes[record.master]);
    CellRecord copy = record;
    copy.state = static_cast<uint32_t>(valueAt);
    *outCells++ = copy;
    if (values) std::copy(values, values + count, outValues + valueAt);  // null: written later, by a batch
    valueAt += count;
  };
  auto putModule = [&](const ModuleValue& module, const double* values, uint32_t count) {
    put(recordOf(module), values, count);
  };
  worker.frame.resize(frameSize_);
  double* frame = worker.frame.data();
  for (CellCursor at = step.pool.cursor(slice.begin); at.index() < slice.end; at.next()) {
    const size_t i = at.index();
    const CellRecord& cell = word[i];
    const MasterCell& master = masters[cell.master];
    const uint32_t n = master.stateCount();
    const double death = cell.birth + master.lifetime;
    if (death > step.horizon) {
      put(cell, at.state(), n);
      continue;
    }
    if (labelsOnly_[cell.master]) {
      // Nothing to evaluate: no frame, no random stream.
      const CompiledRule* rule = fixedChoice_[cell.master]
                                     ? (master.terminalRules.empty() ? nullptr : &master.terminalRules.front())
                                     : (chosen_[i] ? &master.terminalRules[chosen_[i] - 1u] : nullptr);
      if (rule && rule->hasAction) {
        const EvalContext none{};
        worker.successors.write(*rule, cell, nullptr, death, BirthCause::Terminal, none, putModule);
      } else {
        CellRecord renewed = cell;
        renewed.birth = death;
        put(renewed, nullptr, 0);
      }
      continue;
    }
    if (pass == Pass::ContextFree && evaluatesInBatches_[cell.master]) {
      writeBatched(step, cell, at.state(), death, i, worker, outValues, valueAt, put);
      continue;
    }
    RandomStream random(mixKey(mixKey(step.context.seed, cell.id), keyOf(death)));
    EvalContext evaluation{frame, EvalEnvironment{&random, step.context.seed}, &functions_, nullptr};
    evaluation.ancestors = step.context.ancestors;
    const CompiledRule* rule = choose(pass, step, i, at.state(), death, worker, random, evaluation);
    if (rule)
      for (const StateCalculation& calculation : rule->calculations)
        frame[calculation.slot] = calculation.value.evaluate(evaluation);
    if (!rule || !rule->hasAction) {
      CellRecord renewed = cell;
      renewed.birth = death;
      put(renewed, frame, n);
      continue;
    }
    worker.successors.write(*rule, cell, frame, death, BirthCause::Terminal, evaluation, putModule);
  }
  flushWaiting(worker.batches, step.context.seed, step.context.ancestors, outValues);
  slice.earliestDeath = earliest;
  // Counting and writing choose alike by construction; a slice that wrote other than it
  // counted is a defect of this file, stopped here rather than left in the word.
  if (outCells != cells.data() + firstCell + slice.cells || valueAt != firstValue + slice.values) [[unlikely]]
    throw std::logic_error("ontogen: internal error: a slice of the parallel rewrite wrote other than it counted");
}

// As choose() and SuccessorWriter::write do for a rule without choice or calculation: the
// same records, ids and births, and the same frame for the arguments, evaluated later.
template <class Put>
void ParallelRewrite::writeBatched(const Step& step, const CellRecord& cell, const double* state, double death,
                                   size_t i, Worker& worker, double* outValues, uint64_t& valueAt,
                                   const Put& put) const {
  const MasterCell& master = program_.masters[cell.master];
  const uint32_t n = master.stateCount();
  const CompiledRule* rule = contextFreeRule(master, cell.master, step.context.seed, cell.id, death);
  if (!rule || !rule->hasAction) {  // renewed
    CellRecord renewed = cell;
    renewed.birth = death;
    put(renewed, state, n);
    return;
  }
  const uint32_t ruleIndex = firstRule_[cell.master] + static_cast<uint32_t>(rule - master.terminalRules.data());
  Batch* batch = nullptr;
  uint64_t* laneValueAt = nullptr;
  if (batchedValues_[ruleIndex] > 0) {
    batch = &batchOf(worker.batches, ruleIndex, *rule);
    loadCellFrame(batch->frames.data() + size_t(batch->lanes) * frameSize_, master, cell, state, death,
                  {static_cast<double>(i), 0, 0}, step.parents ? step.parents[i] : -1);
    laneValueAt = batch->valueAt.data() + size_t(batch->lanes) * rule->successors.size();
  }
  const uint64_t lineage = lineageKey(cell.id, death, BirthCause::Terminal);
  uint32_t k = 0;
  size_t withValues = 0;
  for (const SuccessorTemplate& successor : rule->successors) {
    ++k;
    if (successor.isMe) {
      CellRecord me = cell;
      me.birth = death;
      put(me, state, n);
      continue;
    }
    ModuleValue made{successor.master, k, death, lineage};
    if (successor.keepsIdentity) made = ModuleValue{successor.master, ModuleValue::kOwnId, death, cell.id};
    if (successor.stateless) {
      put(recordOf(made), nullptr, 0);
      continue;
    }
    laneValueAt[withValues++] = valueAt;
    put(recordOf(made), nullptr, program_.masters[successor.master].stateCount());
  }
  if (batch && ++batch->lanes == CompiledExpression::kBatchLanes)
    flushBatch(*rule, *batch, step.context.seed, step.context.ancestors, outValues);
}

void ParallelRewrite::flushWaiting(std::vector<Batch>& batches, uint64_t seed, const double* ancestors,
                                   double* outValues) const {
  const auto& masters = program_.masters;
  for (size_t m = 0; m < masters.size(); ++m)
    for (size_t r = 0; r < masters[m].terminalRules.size(); ++r) {
      const size_t index = firstRule_[m] + r;
      if (index < batches.size() && batches[index].lanes > 0)
        flushBatch(masters[m].terminalRules[r], batches[index], seed, ancestors, outValues);
    }
}

void ParallelRewrite::makeFrames(Batch& batch, const CompiledRule& rule) const {
  batch.frames.resize(size_t{CompiledExpression::kBatchLanes} * frameSize_);
  batch.valueAt.resize(size_t{CompiledExpression::kBatchLanes} * rule.successors.size());
}

void ParallelRewrite::flushBatch(const CompiledRule& rule, Batch& batch, uint64_t seed, const double* ancestors,
                                 double* outValues) const {
  const size_t successors = rule.successors.size();
  const double* frames = batch.frames.data();
  const size_t frameSize = frameSize_;
  auto load = [&](int lane, int slot) { return frames[size_t(lane) * frameSize + size_t(slot)]; };
  auto noAggregate = [](int, int) { return 0.0; };
  EvalContext context{nullptr, EvalEnvironment{nullptr, seed}, &functions_, nullptr};
  context.ancestors = ancestors;
  double out[CompiledExpression::kBatchLanes];
  size_t withValues = 0;
  for (const SuccessorTemplate& successor : rule.successors) {
    if (successor.isMe || successor.stateless) continue;
    const uint32_t count = program_.masters[successor.master].stateCount();
    for (uint32_t j = 0; j < count; ++j) {
      successor.args[j].evaluateBatch(batch.lanes, load, noAggregate, context, out);
      for (int lane = 0; lane < batch.lanes; ++lane)
        outValues[batch.valueAt[size_t(lane) * successors + withValues] + j] = out[lane];
    }
    ++withValues;
  }
  batch.lanes = 0;
}

RewriteShape ParallelRewrite::shape(bool compact) const {
  RewriteShape shape;
  shape.compact = compact && appliesToCompactWords();
  shape.contextFreeSlices = contextFree_;
  shape.atInstantSlices = atInstants_;
  shape.labelsOnly = allLabelsOnly_;
  shape.inBatchesOrLabelsOnly = allInBatchesOrLabelsOnly_;
  shape.byTable = byTable_;
  shape.choiceVaries = anyChoiceVaries_;
  shape.oneForOne = oneForOne_;
  shape.withValues = withValues_;
  shape.anyState = anyState_;
  shape.batched = anyCompactBatched_;
  return shape;
}

RewriteFacts ParallelRewrite::facts(RewritePass pass, size_t size, unsigned threads, const StepContext* context) const {
  RewriteFacts facts;
  facts.shape = shape(true);
  facts.pass = pass;
  facts.size = size;
  facts.threads = threads;
  if (context) {
    facts.slices = context->rewriteBySlices;
    facts.lineage = context->lineage != nullptr;
  }
  facts.withoutIds = withoutIds_;
  facts.growthKnown = lastGrowth_.modules > 0;
  facts.boundsMissed = boundsMissed_;
  facts.forced = forced_;
  return facts;
}

bool ParallelRewrite::rewriteContextFree(const LinearPool& pool, double horizon, StepContext& context,
                                         const double* parents, uint64_t& events, CellArray& cells, StateArray& state) {
  cells.clear();
  state.clear();
  if (!contextFree_) return false;
  return rewrite(Pass::ContextFree, Step{pool, horizon, 0, context, parents}, context, events, cells, state);
}

bool ParallelRewrite::rewriteAtInstant(const LinearPool& pool, double instant, int group, StepContext& context,
                                       const double* parents, uint64_t& events, CellArray& cells, StateArray& state) {
  cells.clear();
  state.clear();
  if (!atInstants_) return false;
  return rewrite(Pass::AtInstant, Step{pool, instant, group, context, parents}, context, events, cells, state);
}

bool ParallelRewrite::rewrite(Pass pass, const Step& step, StepContext& context, uint64_t& events, CellArray& cells,
                              StateArray& state) {
  const size_t size = step.pool.size();
  const RewritePlan plan = planRewrite(
      facts(pass == Pass::ContextFree ? RewritePass::ContextFree : RewritePass::AtInstant, size, context.threads,
            &context));
  if (plan.strategy != RewriteStrategy::RecordSlices) return false;
  const unsigned threads = plan.threads;
  while (workers_.size() < threads) workers_.push_back(std::make_unique<Worker>(program_));
  if (anyChoiceVaries_ && chosen_.size() < size) chosen_.resize(size);
  const size_t sliceCount = std::min<size_t>(size, size_t{threads} * kSlicesPerThread);
  slices_.assign(sliceCount, Slice{});
  for (size_t s = 0; s < sliceCount; ++s) {
    slices_[s].begin = size * s / sliceCount;
    slices_[s].end = size * (s + 1) / sliceCount;
  }
  parallelFor(
      sliceCount, threads,
      [&](size_t begin, size_t end, unsigned worker) {
        for (size_t s = begin; s < end; ++s) count(pass, step, slices_[s], *workers_[worker]);
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
                step.pool.bytes() + totalCells * sizeof(CellRecord) + totalValues * sizeof(double));
  } catch (const LimitError&) {
    return false;  // the serial pass stops where it passes the limit, as it always did
  }
  resizeForOverwrite(cells, totalCells);
  resizeForOverwrite(state, totalValues);
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
          write(pass, step, slices_[s], firstCell[s], firstValue[s], *workers_[worker], cells, state);
      },
      1);
  earliestDeath_ = kForever;
  for (const Slice& slice : slices_) earliestDeath_ = std::min(earliestDeath_, slice.earliestDeath);
  events += totalEvents;
  context.stats.events += totalEvents;
  context.stats.cellsBorn += totalBorn;
  ++context.stats.rewritesBySlices;
  ++context.stats.rewrites[static_cast<size_t>(RewriteStrategy::RecordSlices)];
  return true;
}

template <class Labels, class Draw>
inline const ParallelRewrite::LabelRule* ParallelRewrite::chooseByPosition(const Labels& labels, size_t size,
                                                                           uint32_t master, int group, size_t i,
                                                                           const Draw& draw) const {
  const std::vector<LabelRule>& rules = labelRules_[master];
  for (size_t r = 0; r < rules.size(); ++r) {
    const LabelRule& choice = rules[r];
    if (choice.group != 0 && choice.group != group) continue;
    if (choice.context && !matchesByPosition(labels, size, choice, i)) continue;
    if (!choice.stochastic) return &choice;
    return drawAmong(labels, size, master, group, i, r, draw());
  }
  return nullptr;
}

// As ontogen::chooseRule draws (core/rule_choice.h): rule r and the later stochastic rules
// that apply, each once however many of its variants apply, weighted by their chances;
// `uniform` is the cell's first draw.
template <class Labels>
const ParallelRewrite::LabelRule* ParallelRewrite::drawAmong(const Labels& labels, size_t size, uint32_t master,
                                                             int group, size_t i, size_t r, double uniform) const {
  const std::vector<LabelRule>& rules = labelRules_[master];
  auto applies = [&](const LabelRule& choice) {
    return (choice.group == 0 || choice.group == group) &&
           (!choice.context || matchesByPosition(labels, size, choice, i));
  };
  const LabelRule* candidates[kMostDrawn];
  double weights[kMostDrawn];
  size_t count = 0;
  double total = 0;
  bool taken = false;
  for (size_t s = r; s < rules.size(); ++s) {
    if (s == r || rules[s].variant == 0) taken = false;
    if (taken || !rules[s].stochastic || (s != r && !applies(rules[s]))) continue;
    candidates[count] = &rules[s];
    weights[count] = std::max(0.0, rules[s].chance);
    total += weights[count];
    ++count;
    taken = true;
  }
  if (!(total > 0)) return nullptr;
  return candidates[pickByWeight(uniform, total, count, [&](size_t c) { return weights[c]; })];
}

namespace {
// The modules a step of a word rewritten by the table makes are born when their parents
// die, most often all at the earliest death of the word (the step's instant; the horizon
// is a little past it): that birth goes into the next word's table before the slices
// write, so that no slice adds it as a birth of its own, which Slice::place would have to
// renumber in every run. A guess that misses costs an unused entry.
void knowTheBirth(CompactWord& next, std::span<CompactWord::Slice> slices, double birth) {
  if (!(birth < kForever)) return;
  const uint32_t index = next.birthIndexOf(birth);
  for (CompactWord::Slice& slice : slices) slice.knowBirth(birth, index);
}

// Calls `work(labels)` with `word`'s labels read the quickest way.
template <class Work>
auto withLabelsOf(const CompactWord& word, const Work& work) {
  return word.wideLabels() ? work(CompactLabels{word}) : work(ByteLabels{word.labels8().data()});
}

// Calls `work(i)` for i in [0, count), each index on one of `threads` threads.
template <class Work>
void forEachIndex(size_t count, unsigned threads, const Work& work) {
  parallelFor(
      count, threads,
      [&](size_t begin, size_t end, unsigned) {
        for (size_t i = begin; i < end; ++i) work(i);
      },
      1);
}

// Modules first .. first + n - 1 of a word, in one run, born at `birth`: kept with their
// birth index, or renewed (rewriteRange).
struct KeptStretch {
  size_t first = 0;
  uint32_t n = 0;
  IdKey key{};
  bool renewed = false;
  uint32_t birthIndex = 0;
  double birth = 0;
};

// The next word itself as the output of rewriteCompact's one pass on one thread, with the
// calls of a CompactWord::Slice.
struct SerialOut {
  CompactWord& word;
  const CompactWord& from;  // the word rewritten
  bool writing() const { return true; }
  void appendKept(size_t first, uint32_t n, IdKey key, uint32_t birthIndex) {
    word.appendStretch(from, first, n, key, birthIndex);
  }
  void appendRenewed(size_t first, uint32_t n, IdKey key, double birth) {
    word.appendStretch(from, first, n, key, word.birthIndexOf(birth));
  }
  void appendCopy(uint32_t label, IdKey key, uint32_t birthIndex, const double* values) {
    word.append(label, key, birthIndex, values);
  }
  void append(uint32_t label, IdKey key, double birth, const double* values) { word.append(label, key, birth, values); }
  void appendBorn(uint32_t label, uint64_t, uint64_t lineage, uint32_t k, double birth, const double* values) {
    word.append(label, IdKey{lineage, k}, birth, values);
  }
  void appendFreshRun(const uint32_t* labels, uint32_t n, uint64_t, uint64_t lineage, double birth) {
    word.appendRun(labels, n, lineage, word.birthIndexOf(birth));
  }
  size_t nextValue() const { return word.valueCount(); }
  double* wordValues() const { return word.values().data(); }
};
// A slice written in place by rewriteOneForOne, its appends called, not inlined: in a word
// whose choices vary, most modules join a stretch of modules kept or renewed, and the
// slice's appends inlined into the loop of rewriteRange slowed every module.
struct SliceOut {
  CompactWord::Slice& slice;
  bool writing() const { return true; }
  [[gnu::noinline]] void appendKept(size_t first, uint32_t n, IdKey key, uint32_t birthIndex) {
    slice.appendKept(first, n, key, birthIndex);
  }
  [[gnu::noinline]] void appendRenewed(size_t first, uint32_t n, IdKey key, double birth) {
    slice.appendRenewed(first, n, key, birth);
  }
  [[gnu::noinline]] void appendCopy(uint32_t label, IdKey key, uint32_t birthIndex, const double* values) {
    slice.appendCopy(label, key, birthIndex, values);
  }
  [[gnu::noinline]] void append(uint32_t label, IdKey key, double birth, const double* values) {
    slice.append(label, key, birth, values);
  }
  [[gnu::noinline]] void appendBorn(uint32_t label, uint64_t event, uint64_t lineage, uint32_t k, double birth,
                                    const double* values) {
    slice.appendBorn(label, event, lineage, k, birth, values);
  }
  [[gnu::noinline]] void appendFreshRun(const uint32_t* labels, uint32_t n, uint64_t event, uint64_t lineage,
                                        double birth) {
    slice.appendFreshRun(labels, n, event, lineage, birth);
  }
  size_t nextValue() const { return slice.nextValue(); }
  double* wordValues() const { return slice.wordValues(); }
};
}  // namespace

// Cells [begin, end) of `word` through `out`: a slice counting or writing, or the next word
// on one thread. The counting pass chooses but hashes nothing: new successors are named by
// their event (CompactWord::Slice::appendBorn) until the writing pass computes their
// lineage. `stop(counts so far)` is asked every 2^16 cells whether to give up.
template <bool kWithValues, class Out, class Labels, class Stop>
ParallelRewrite::CompactCounts ParallelRewrite::rewriteRange(const CompactWord& word, size_t begin, size_t end,
                                                             double horizon, int group, const Labels& labels, Out& out,
                                                             const Stop& stop, double& soonest,
                                                             CompactEvaluation& evaluation) const {
  const bool writing = out.writing();
  const double* lifetimes = lifetimes_.data();
  const size_t size = word.size();
  // In a local: a label stored through a byte pointer may alias any member.
  const uint8_t* batched = compactBatched_.data();
  CompactCounts counts;
  // In a word of labels alone, modules kept or renewed one after another in one run go
  // out as one stretch (appendKept, appendRenewed): the writer continues their run
  // without asking module by module (the signal renews 10^5 modules a step).
  KeptStretch kept;
  auto flushKept = [&] {
    if (kept.n == 0) return;
    if (kept.renewed)
      out.appendRenewed(kept.first, kept.n, kept.key, kept.birth);
    else
      out.appendKept(kept.first, kept.n, kept.key, kept.birthIndex);
    kept.n = 0;
  };
  // The cell joins the stretch when it continues the stretch's last module in its run
  // and goes out the same way, at the same birth (a run's modules share theirs, but
  // labels of other lifetimes die at other instants); else it starts one.
  auto keep = [&](const CompactWordCursor& cell, bool renewed, double birth) {
    if (kept.n > 0 && kept.renewed == renewed && cell.continuesRun() &&
        std::bit_cast<uint64_t>(birth) == std::bit_cast<uint64_t>(kept.birth)) {
      ++kept.n;
      return;
    }
    flushKept();
    kept = KeptStretch{cell.index(), 1, cell.key(), renewed, cell.birthIndex(), birth};
  };
  size_t untilCheck = size_t{1} << 16;
  for (CompactWordCursor cell(word, begin); !cell.done() && cell.index() < end; cell.next()) {
    if (--untilCheck == 0) [[unlikely]] {
      untilCheck = size_t{1} << 16;
      if constexpr (!kWithValues) flushKept();  // `stop` reads what was written
      if (stop(counts)) break;
    }
    const uint32_t label = labels[cell.index()];
    const double lifetime = lifetimes[label];
    const double death = cell.birth() + lifetime;
    if (death > horizon) {
      soonest = std::min(soonest, death);
      if constexpr (!kWithValues)
        keep(cell, false, cell.birth());
      else
        out.appendCopy(label, cell.key(), cell.birthIndex(), cell.state());
      continue;
    }
    ++counts.events;
    if constexpr (kWithValues) {
      if (batched[label]) {
        expireBatched(cell, label, death, out, counts, soonest, evaluation);
        continue;
      }
    }
    const LabelRule* choice =
        fixedChoice_[label] ? fixedRule(label) : chooseByPosition(labels, size, label, group, cell.index(), [&] {
          // The stream the records' passes draw from (LinearDevelopment::expire).
          RandomStream random(mixKey(mixKey(evaluation.seed, cell.id()), keyOf(death)));
          return random.uniform();
        });
    if (!choice || !choice->rule->hasAction) {  // renewed: the same id, born again
      soonest = std::min(soonest, death + lifetime);
      if constexpr (!kWithValues)
        keep(cell, true, death);
      else
        out.append(label, cell.key(), death, nullptr);
      continue;
    }
    if constexpr (!kWithValues) flushKept();
    // As SuccessorWriter::write: `me` and `=X` keep the cell's id, the others take the
    // event's lineage and their number.
    const IdKey own = cell.key();
    const uint64_t lineage = writing ? lineageKey(own.id(), death, BirthCause::Terminal) : 0;
    counts.born += choice->born;
    soonest = std::min(soonest, death + choice->shortestLife);
    if (!choice->freshLabels.empty()) {  // one run, written at once
      out.appendFreshRun(choice->freshLabels.data(), choice->cells, counts.events, lineage, death);
      continue;
    }
    uint32_t k = 0;
    for (const LabelRule::Written& successor : choice->written) {
      ++k;
      if (successor.keepsId)
        out.append(successor.label, own, death, nullptr);
      else
        out.appendBorn(successor.label, counts.events, lineage, k, death, nullptr);
    }
  }
  if constexpr (!kWithValues) flushKept();
  if (kWithValues && writing)  // the values of the cells still waiting in a batch
    flushWaiting(evaluation.batches, evaluation.seed, evaluation.ancestors, out.wordValues());
  return counts;
}

template <class Out, class Labels, class Stop>
[[gnu::noinline]] ParallelRewrite::CompactCounts ParallelRewrite::rewriteRangeWithValues(
    const CompactWord& word, size_t begin, size_t end, double horizon, int group, const Labels& labels, Out& out,
    const Stop& stop, double& soonest, CompactEvaluation& evaluation) const {
  return rewriteRange<true>(word, begin, end, horizon, group, labels, out, stop, soonest, evaluation);
}

// As writeBatched writes a cell in the records' pass: the same rule, ids, births and
// values. The id is hashed only where it is read: for a draw, and for the frame and the
// lineage while writing.
template <class Out>
void ParallelRewrite::expireBatched(const CompactWordCursor& cell, uint32_t label, double death, Out& out,
                                    CompactCounts& counts, double& soonest, CompactEvaluation& evaluation) const {
  const MasterCell& master = program_.masters[label];
  const bool writing = out.writing();
  const IdKey own = cell.key();
  const uint64_t id = writing || drawsByChance_[label] ? own.id() : 0;
  const CompiledRule* rule = contextFreeRule(master, label, evaluation.seed, id, death);
  if (!rule || !rule->hasAction) {  // renewed, with its values
    out.append(label, own, death, cell.state());
    soonest = std::min(soonest, death + master.lifetime);
    return;
  }
  const uint32_t ruleIndex = firstRule_[label] + static_cast<uint32_t>(rule - master.terminalRules.data());
  const LabelRule& writes = batchedRules_[ruleIndex];
  counts.born += writes.born;
  soonest = std::min(soonest, death + writes.shortestLife);
  Batch* batch = nullptr;
  uint64_t* laneValueAt = nullptr;
  if (writing && batchedValues_[ruleIndex] > 0) {
    batch = &batchOf(evaluation.batches, ruleIndex, *rule);
    // Its values, age and id: a master of compactBatched_ reads neither place nor parent.
    double* frame = batch->frames.data() + size_t(batch->lanes) * frameSize_;
    const uint32_t n = master.stateCount();
    std::copy(cell.state(), cell.state() + n, frame);
    loadAgeAndId(frame + n, cell.birth(), id, master.lifetime, death);
    laneValueAt = batch->valueAt.data() + size_t(batch->lanes) * rule->successors.size();
  }
  const uint64_t lineage = writing ? lineageKey(id, death, BirthCause::Terminal) : 0;
  size_t withValues = 0;
  if (!writes.freshLabels.empty()) {  // all new: one run, written at once, its values after it
    if (laneValueAt) {
      size_t value = out.nextValue();
      for (const SuccessorTemplate& successor : rule->successors) {
        if (successor.stateless) continue;
        laneValueAt[withValues++] = value;
        value += program_.masters[successor.master].stateCount();
      }
    }
    out.appendFreshRun(writes.freshLabels.data(), writes.cells, counts.events, lineage, death);
  } else {
    uint32_t k = 0;
    for (const SuccessorTemplate& successor : rule->successors) {
      ++k;
      if (successor.isMe) {
        out.append(label, own, death, cell.state());
        continue;
      }
      if (laneValueAt && !successor.stateless) laneValueAt[withValues++] = out.nextValue();
      if (successor.keepsIdentity)
        out.append(successor.master, own, death, nullptr);
      else
        out.appendBorn(successor.master, counts.events, lineage, k, death, nullptr);
    }
  }
  if (batch && ++batch->lanes == CompiledExpression::kBatchLanes)
    flushBatch(*rule, *batch, evaluation.seed, evaluation.ancestors, out.wordValues());
}

std::optional<ParallelRewrite::CompactCounts> ParallelRewrite::rewriteCompact(const CompactWord& word, double horizon,
                                                                              int group, unsigned threads,
                                                                              CompactWord& next,
                                                                              const CompactFits& fits, uint64_t seed,
                                                                              const double* ancestors) {
  if (!appliesToCompactWords())
    throw std::logic_error("ontogen: internal error: a compact rewrite of a word whose rules are not label-only");
  if (!word.holdsIds() && !withoutIds_)
    throw std::logic_error("ontogen: internal error: a compact word held without ids rewritten with ids");
  const size_t size = word.size();
  next.clearWithBirthsOf(word);
  const double expectedBirth = earliestDeath_;  // the last rewrite's, at this word's first death
  earliestDeath_ = kForever;
  RewriteFacts known = facts(RewritePass::Compact, size, threads, nullptr);
  RewritePlan plan = planRewrite(known);
  // In place, its bounds being at most every module expiring and giving birth to one.
  // When they pass a limit, the strategies that count as they go decide.
  if (plan.strategy == RewriteStrategy::OneForOne) {
    if (!fits || fits(size, size, size, size)) {
      ran_ = RewriteStrategy::OneForOne;
      return rewriteOneForOne(word, horizon, group, plan.threads, next, seed, expectedBirth);
    }
    known.inPlaceRefused = true;
    plan = planRewrite(known);
  }
  ran_ = plan.strategy;
  switch (plan.strategy) {
    case RewriteStrategy::CompactSerial:
      return rewriteSerially(word, horizon, group, next, fits, seed, ancestors);
    case RewriteStrategy::TableAlone:
      return rewriteByTableAlone(word, horizon, next, fits, expectedBirth);
    case RewriteStrategy::Parts:
      return rewriteInParts(word, horizon, group, plan.threads, next, fits, seed);
    default:
      return rewriteBySlices(word, horizon, group, plan.threads, next, fits, seed, ancestors, expectedBirth,
                             plan.strategy == RewriteStrategy::TableBounds);
  }
}

// One pass on one thread, writing the next word as it goes and asking `fits` on the way.
// A large word's arrays are reserved for the growth of the last rewrite, since growing
// them as it goes would hold a copy more (Koch at n = 10: 144 MB against 101 MB).
std::optional<ParallelRewrite::CompactCounts> ParallelRewrite::rewriteSerially(const CompactWord& word,
                                                                               double horizon, int group,
                                                                               CompactWord& next,
                                                                               const CompactFits& fits, uint64_t seed,
                                                                               const double* ancestors) {
  const size_t size = word.size();
  auto withLabels = [&](const auto& work) { return withLabelsOf(word, work); };
  if (size >= kMinimumCells)
    next.reserve(Growth::room(size, lastGrowth_.modules), Growth::room(word.runCount(), lastGrowth_.runs),
                 withValues_ ? Growth::room(word.valueCount(), lastGrowth_.values) : 0);
  SerialOut out{next, word};
  bool refused = false;
  auto stop = [&](const CompactCounts& sofar) {
    refused = fits && !fits(next.size(), sofar.events, sofar.born, next.size());
    return refused;
  };
  CompactEvaluation evaluation{seed, ancestors, {}};
  const CompactCounts counts = withLabels([&](const auto& labels) {
    return withValues_
               ? rewriteRangeWithValues(word, 0, size, horizon, group, labels, out, stop, earliestDeath_, evaluation)
               : rewriteRange<false>(word, 0, size, horizon, group, labels, out, stop, earliestDeath_, evaluation);
  });
  if (refused || (fits && !fits(next.size(), counts.events, counts.born, next.size()))) {
    next.clear();
    return std::nullopt;
  }
  next.finish();
  lastGrowth_ = Growth::of(word, next);
  return counts;
}

// Slices on several threads, or a large word counted first on one: every slice counts,
// then writes in place (CompactWord::Slice); or, for the table's words, each is placed by
// its bounds and written once.
std::optional<ParallelRewrite::CompactCounts> ParallelRewrite::rewriteBySlices(
    const CompactWord& word, double horizon, int group, unsigned threads, CompactWord& next, const CompactFits& fits,
    uint64_t seed, const double* ancestors, double expectedBirth, bool placeByBounds) {
  const size_t size = word.size();
  auto withLabels = [&](const auto& work) { return withLabelsOf(word, work); };
  const size_t sliceCount = std::max<size_t>(1, std::min<size_t>(size, size_t{threads} * kSlicesPerThread));
  auto everySlice = [&](const auto& work) { forEachIndex(sliceCount, threads, work); };

  // Several threads, or a large word counted first: every slice counts, then writes in
  // place (CompactWord::Slice).
  std::vector<CompactWord::Slice>& slices = compactSlices_;  // kept from step to step
  slices.resize(sliceCount, CompactWord::Slice(word));
  for (CompactWord::Slice& slice : slices) slice.restart(word);
  std::vector<CompactCounts> counted(sliceCount);
  std::vector<double> earliest(sliceCount, kForever);
  auto never = [](const CompactCounts&) { return false; };
  // After every slice wrote: their seams and births joined, the word finished.
  auto joinTheSlices = [&](const CompactCounts& counts) {
    joinWrittenSlices(word, next, slices, earliest, withoutIds_, threads);
    return std::optional<CompactCounts>(counts);
  };
  bool byBounds = false;  // the slices are being placed by their bounds, not counted
  auto pass = [&](size_t s) {
    CompactWord::Slice& out = slices[s];
    const bool writing = out.writing();
    double soonest = kForever;
    const size_t begin = size * s / sliceCount, end = size * (s + 1) / sliceCount;
    CompactCounts counts;
    if (byTable_) {
      TerminalLineage lineage;
      const TableRewriteCounts walked =
          TableRewrite::rewrite(out, word, begin, end, table_, horizon, lineage, !withoutIds_);
      counts = {walked.events, walked.born};
      soonest = walked.soonest;
    } else {
      CompactEvaluation evaluation{seed, ancestors, {}};
      counts = withLabels([&](const auto& labels) {
        return withValues_
                   ? rewriteRangeWithValues(word, begin, end, horizon, group, labels, out, never, soonest, evaluation)
                   : rewriteRange<false>(word, begin, end, horizon, group, labels, out, never, soonest, evaluation);
      });
    }
    if (byBounds) {
      counted[s] = counts;
      // The word is given up; nothing to finish. Without ids a slice writes fewer runs
      // than its bound, and closeRunGaps closes the gaps.
      if (!(withoutIds_ ? out.wroteModulesAsAssumed() : out.wroteAsAssumed())) return;
      if (withoutIds_) out.keepRunsWritten();
    }
    out.finish();
    if (!writing) counted[s] = counts;
    earliest[s] = soonest;
  };

  // A word rewritten by the table, placed by bounds instead of counted: each slice is
  // given what it writes if every module of it that can expire does, and each module
  // starts a run. Both hold in Koch and Thue-Morse at every step, and the count (a sixth
  // of the writing there) is saved. When a slice writes less, the word is written again
  // after counting, and this development counts from then on.
  if (placeByBounds) {
    std::vector<TableBound> bounds(sliceCount);
    everySlice([&](size_t s) {
      const size_t begin = size * s / sliceCount, end = size * (s + 1) / sliceCount;
      bounds[s] = TableRewrite::bound(word, begin, end, table_);
      slices[s].assume(bounds[s].modules, end - begin, bounds[s].values);
    });
    TableBound total;
    for (const TableBound& bound : bounds) {
      total.modules += bound.modules;
      total.events += bound.events;
      total.born += bound.born;
    }
    // The bounds passing a limit may still fit: counting decides.
    if (!fits || fits(total.modules, total.events, total.born, total.modules)) {
      byBounds = true;
      next.beginSlices(slices);
      if (withoutIds_) next.markWithoutIds();
      knowTheBirth(next, slices, expectedBirth);
      everySlice(pass);
      byBounds = false;
      const bool asBounded = std::all_of(slices.begin(), slices.end(),
                                         [](const CompactWord::Slice& slice) { return slice.wroteAsAssumed(); });
      if (asBounded) {
        ran_ = RewriteStrategy::TableBounds;
        CompactCounts counts;
        for (const CompactCounts& slice : counted) {
          counts.events += slice.events;
          counts.born += slice.born;
        }
        if (fits && !fits(total.modules, counts.events, counts.born, total.modules)) return std::nullopt;
        return joinTheSlices(counts);
      }
      boundsMissed_ = true;
      next.clearWithBirthsOf(word);
      for (CompactWord::Slice& slice : slices) slice.restart(word);
      std::fill(earliest.begin(), earliest.end(), kForever);
    }
  }

  ran_ = RewriteStrategy::CompactSlices;
  everySlice(pass);
  CompactCounts counts;
  uint64_t modules = 0;
  for (size_t s = 0; s < sliceCount; ++s) {
    modules += slices[s].modules();
    counts.events += counted[s].events;
    counts.born += counted[s].born;
  }
  if (fits && !fits(modules, counts.events, counts.born, modules)) return std::nullopt;
  next.beginSlices(slices);
  if (withoutIds_) next.markWithoutIds();
  if (byTable_) knowTheBirth(next, slices, expectedBirth);
  everySlice(pass);
  return joinTheSlices(counts);
}

// One pass on one thread, without counting first (which took a seventh of Thue-Morse's
// time): the next word is sized for the most it can hold, each module that can expire
// replaced by its successors (the counts of the labels give that), and cut to what was
// written. Where every such module expires (Koch, Thue-Morse) the bound is the size. The
// walk goes by chunks, asking `fits` after each, so that a word past a limit is given up
// on the way; each chunk starts a run, as a slice does.
std::optional<ParallelRewrite::CompactCounts> ParallelRewrite::rewriteByTableAlone(const CompactWord& word,
                                                                                   double horizon, CompactWord& next,
                                                                                   const CompactFits& fits,
                                                                                   double expectedBirth) {
  constexpr size_t kChunk = size_t{1} << 16;
  const size_t size = word.size();
  const TableBound bound = TableRewrite::bound(word, 0, size, table_);
  std::vector<CompactWord::Slice>& slices = compactSlices_;
  slices.resize(1, CompactWord::Slice(word));
  CompactWord::Slice& slice = slices.front();
  slice.restart(word);
  // A module starts at most one run: its successors, or itself kept or renewed.
  next.beginWholeSlice(slice, bound.modules, size, bound.values);
  if (withoutIds_) next.markWithoutIds();
  knowTheBirth(next, {&slice, 1}, expectedBirth);
  TerminalLineage lineage;
  CompactCounts counts;
  for (size_t begin = 0; begin < size; begin += kChunk) {
    const TableRewriteCounts walked = TableRewrite::rewrite(slice, word, begin, std::min(size, begin + kChunk), table_,
                                                            horizon, lineage, !withoutIds_);
    counts.events += walked.events;
    counts.born += walked.born;
    earliestDeath_ = std::min(earliestDeath_, walked.soonest);
    if (fits && !fits(slice.written(), counts.events, counts.born, slice.written())) {
      next.clear();
      return std::nullopt;
    }
  }
  next.endWholeSlice(slice);
  next.finish();
  lastGrowth_ = Growth::of(word, next);
  return counts;
}

// Each module of the word writes one module, so each thread's slice of the word knows
// where it goes in the next word: the threads write in place, in one pass, and meet once.
// A slice is given a run a module, and CompactWord::closeRunGaps moves the runs it wrote
// after the last slice's. The thread that writes a slice reads it at the next rewrite (as
// in rewriteInParts), from its own core's cache. Against parts copied after writing, the
// signal took 215 ms on two threads instead of 243, and 392 on one instead of 434 (one
// slice, against the serial append). The caller asked the limits with the word's bounds,
// so the word written fits them (CompactFits).
ParallelRewrite::CompactCounts ParallelRewrite::rewriteOneForOne(const CompactWord& word, double horizon, int group,
                                                                 unsigned threads, CompactWord& next, uint64_t seed,
                                                                 double expectedBirth) {
  const size_t size = word.size();
  const size_t sliceCount = threads;
  std::vector<CompactWord::Slice>& slices = compactSlices_;
  slices.resize(sliceCount, CompactWord::Slice(word));
  for (size_t s = 0; s < sliceCount; ++s) {
    const size_t modules = size * (s + 1) / sliceCount - size * s / sliceCount;
    slices[s].restart(word);
    slices[s].assume(modules, modules);
  }
  next.beginSlices(slices);
  knowTheBirth(next, slices, expectedBirth);
  std::vector<CompactCounts> counted(sliceCount);
  std::vector<double> earliest(sliceCount, kForever);
  auto never = [](const CompactCounts&) { return false; };
  forEachIndex(sliceCount, threads, [&](size_t s) {
    CompactWord::Slice& out = slices[s];
    CompactEvaluation evaluation{seed, nullptr, {}};  // no state: nothing is evaluated
    double soonest = kForever;                        // on the thread's stack: `earliest` shares a cache line
    SliceOut written{out};
    counted[s] = withLabelsOf(word, [&](const auto& labels) {
      return rewriteRange<false>(word, size * s / sliceCount, size * (s + 1) / sliceCount, horizon, group, labels,
                                 written, never, soonest, evaluation);
    });
    earliest[s] = soonest;
    if (!out.wroteModulesAsAssumed())
      throw std::logic_error("ontogen: internal error: a module of a one-for-one word wrote other than one");
    out.keepRunsWritten();
    out.finish();
  });
  CompactCounts counts;
  for (const CompactCounts& slice : counted) {
    counts.events += slice.events;
    counts.born += slice.born;
  }
  // Renumbered on this thread: a slice has few runs, and none when the birth was known.
  joinWrittenSlices(word, next, slices, earliest, true, 1);
  return counts;
}

void ParallelRewrite::joinWrittenSlices(const CompactWord& word, CompactWord& next,
                                        std::span<CompactWord::Slice> slices, std::span<const double> earliest,
                                        bool closeGaps, unsigned threads) {
  if (closeGaps) next.closeRunGaps(slices);
  next.joinSlices(slices);
  forEachIndex(slices.size(), threads, [&](size_t s) { slices[s].place(); });
  next.finish();
  for (double soonest : earliest) earliestDeath_ = std::min(earliestDeath_, soonest);
  lastGrowth_ = Growth::of(word, next);
}

// Each thread writes its share of the word in one pass into a part of its own, then
// copies that part into its place in `next` (CompactWord::copyPart: labels and runs
// copied, the bitmap shifted, a small fraction of choosing). Counting first chose every
// module twice: the signal on two threads took 1.27 times less than on one. A thread
// copies the part it wrote, and oneTBB gives the calling thread the first chunk of a
// loop and a worker the second, step after step, so each core reads at the next rewrite
// what it wrote: with the first part written straight into `next` and the others copied
// after it by the calling thread, the other core read its share back from the first
// core's cache at every step, and two threads took 0.44 s where one took 0.64 (now 0.33).
// The parts hold a second copy of the word until they are copied, which `fits` is told.
std::optional<ParallelRewrite::CompactCounts> ParallelRewrite::rewriteInParts(const CompactWord& word, double horizon,
                                                                              int group, unsigned threads,
                                                                              CompactWord& next,
                                                                              const CompactFits& fits, uint64_t seed) {
  const size_t size = word.size();
  const size_t partCount = threads;
  if (parts_.size() < partCount) parts_.resize(partCount);

  // What the parts have written so far, added up every 2^16 cells. Each figure only grows
  // and stays below its final value, so a word is given up on the way only if it would
  // be given up at the end, whatever the threads' timing.
  std::atomic<uint64_t> modulesSoFar{0}, eventsSoFar{0}, bornSoFar{0};
  std::atomic<bool> refused{false};
  std::vector<CompactCounts> counted(partCount);
  std::vector<double> earliest(partCount, kForever);
  auto writePart = [&](size_t p) {
    CompactWord& out = parts_[p].word;
    const size_t begin = size * p / partCount, end = size * (p + 1) / partCount;
    if (out.stateCounts() != word.stateCounts()) out = CompactWord(word.stateCounts());
    out.clearWithBirthsOf(word);
    out.reserve(Growth::room(end - begin, lastGrowth_.modules),
                Growth::room(word.runCount() * (end - begin) / size, lastGrowth_.runs), 0);
    CompactCounts reported;
    uint64_t reportedModules = 0;
    auto stop = [&](const CompactCounts& sofar) {
      const uint64_t modules = out.size() - reportedModules, events = sofar.events - reported.events,
                     born = sofar.born - reported.born;
      reportedModules = out.size();
      reported = sofar;
      const uint64_t allModules = modulesSoFar.fetch_add(modules) + modules;
      const uint64_t allEvents = eventsSoFar.fetch_add(events) + events;
      const uint64_t allBorn = bornSoFar.fetch_add(born) + born;
      if (!refused.load(std::memory_order_relaxed) && fits && !fits(allModules, allEvents, allBorn, 2 * allModules))
        refused.store(true, std::memory_order_relaxed);
      return refused.load(std::memory_order_relaxed);
    };
    SerialOut serial{out, word};
    double soonest = kForever;
    CompactEvaluation evaluation{seed, nullptr, {}};  // no state: nothing is evaluated
    counted[p] = withLabelsOf(word, [&](const auto& labels) {
      return withValues_
                 ? rewriteRangeWithValues(word, begin, end, horizon, group, labels, serial, stop, soonest, evaluation)
                 : rewriteRange<false>(word, begin, end, horizon, group, labels, serial, stop, soonest, evaluation);
    });
    earliest[p] = soonest;
  };
  forEachIndex(partCount, threads, writePart);

  CompactCounts counts;
  uint64_t modules = 0;
  for (size_t p = 0; p < partCount; ++p) {
    modules += parts_[p].word.size();
    counts.events += counted[p].events;
    counts.born += counted[p].born;
  }
  if (refused.load() || (fits && !fits(modules, counts.events, counts.born, 2 * modules))) return std::nullopt;
  std::vector<CompactWord::PartPlace>& places = partPlaces_;
  places.resize(partCount);
  for (size_t p = 0; p < partCount; ++p) places[p].part = &parts_[p].word;
  next.placeParts(places, word.birthCount());
  forEachIndex(partCount, threads, [&](size_t p) { next.copyPart(places[p], word.birthCount()); });
  next.endParts(places);
  next.finish();
  for (size_t p = 0; p < partCount; ++p) earliestDeath_ = std::min(earliestDeath_, earliest[p]);
  lastGrowth_ = Growth::of(word, next);
  return counts;
}

}  // namespace ontogen
