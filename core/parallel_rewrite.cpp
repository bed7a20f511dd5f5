#include "core/parallel_rewrite.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <stdexcept>

#include "core/cell_frame.h"
#include "core/linear_context.h"
#include "core/parallel_for.h"
#include "core/parallel_rewrite_internal.h"
#include "core/rule_choice.h"
#include "core/rule_evaluator.h"
#include "core/salts.h"
#include "lang/expression_batch.h"
#include "lang/random.h"
#include "pools/large_page_allocator.h"

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

}  // namespace ontogen
