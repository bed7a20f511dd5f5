// What a system's rules allow the compact word's rewrites (ParallelRewrite's constructor,
// shape, facts), and the batches in which they evaluate successors' values. The strategies
// themselves are in core/compact_rewrite.cpp with the files it names.

#include "core/parallel_rewrite.h"

#include <algorithm>
#include <cstdint>

#include "core/parallel_rewrite_internal.h"
#include "core/rule_choice.h"
#include "core/rule_evaluator.h"
#include "core/salts.h"
#include "model/expression_batch.h"
#include "model/random.h"

namespace ontogen {

namespace {
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
    if (symbolClass & kSymbolCut) atInstants_ = false;
  if (system.backward || system.decomposes) atInstants_ = false;
  auto plain = [](const std::vector<uint8_t>& classes) {
    return std::all_of(classes.begin(), classes.end(), [](uint8_t c) { return c == kSymbolModule; });
  };
  plain_ = plain(system.symbolClass) && std::all_of(system.ruleClasses.begin(), system.ruleClasses.end(), plain);
  labelsOnly_.resize(program.masters.size());
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
    for (const LabelRule& choice : choices) allByPosition_ = allByPosition_ && (!choice.context || choice.byPosition);
    bool choosesInFrame = false;
    for (const CompiledRule& rule : master.terminalRules) {
      // Multiscale contexts are matched by the serial pass alone (core/multiscale_context.h).
      if (!rule.newLeft.empty() || !rule.newRight.empty() || !rule.aggregates.empty() || rule.contextDimensions != 1 ||
          rule.scales)
        atInstants_ = false;
      anyContext_ = anyContext_ || rule.hasContext() || !rule.leftItems.empty() || !rule.rightItems.empty();
      // A condition or a chance that is an expression is evaluated in the cell's frame, a
      // constant chance drawn from the cell's stream alone (drawByChances).
      choosesInFrame =
          choosesInFrame || !rule.predicate.empty() || (!rule.probability.empty() && !rule.probability.isConstant());
      oneForOne_ = oneForOne_ && (!rule.hasAction || rule.successors.size() == 1);
      for (const SuccessorTemplate& successor : rule.successors)
        if (!successor.birthAge.empty()) atInstants_ = false;
    }
    // Several rules: the first one, a draw among them when it has a chance, or a choice
    // in the cell's frame (also past kMostDrawn rules with a chance).
    choosesInFrame = choosesInFrame || !fewDrawn;
    const bool draws =
        !choosesInFrame && !master.terminalRules.empty() && !master.terminalRules.front().probability.empty();
    drawsByChance_.push_back(draws);
    const bool compactBatched = !labelsOnly_[m] && evaluatesInBatches(program, master, draws) && !drawsByLabels &&
                                !master.readsPosition && !master.readsParent;
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

uint64_t ParallelRewrite::heldBytes() const {
  uint64_t bytes = parts_.capacity() * sizeof(Part) + compactSlices_.capacity() * sizeof(CompactWord::Slice) +
                   partPlaces_.capacity() * sizeof(CompactWord::PartPlace);
  for (const Part& part : parts_) bytes += part.word.heldBytes();
  for (const CompactWord::Slice& slice : compactSlices_) bytes += slice.heldBytes();
  for (const CompactWord::PartPlace& place : partPlaces_)
    bytes += place.births.capacity() * sizeof(uint32_t) +
             place.sharedWords.capacity() * sizeof(std::pair<size_t, uint64_t>);
  return bytes;
}

RewriteShape ParallelRewrite::shape(bool compact) const {
  RewriteShape shape;
  shape.compact = compact && appliesToCompactWords();
  shape.byTable = byTable_;
  shape.choiceVaries = anyChoiceVaries_;
  shape.oneForOne = oneForOne_;
  shape.withValues = withValues_;
  shape.anyState = anyState_;
  shape.batched = anyCompactBatched_;
  return shape;
}

RewriteFacts ParallelRewrite::facts(size_t size, unsigned threads) const {
  RewriteFacts facts;
  facts.shape = shape(true);
  facts.pass = RewritePass::Compact;
  facts.size = size;
  facts.threads = threads;
  facts.withoutIds = withoutIds_;
  facts.growthKnown = lastGrowth_.modules > 0;
  facts.boundsMissed = boundsMissed_;
  facts.forced = forced_;
  return facts;
}

}  // namespace ontogen
