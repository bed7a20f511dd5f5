// The RecordSlices strategy (core/rewrite_plan.h): a word of records counted, then
// written, by slices on every core, in the context-free pass or the pass of one instant
// (ParallelRewrite::rewriteContextFree, rewriteAtInstant). What the rules allow, and the
// batches both this and the compact word evaluate values in, are in
// core/parallel_rewrite.cpp.

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "core/cell_frame.h"
#include "core/linear_context.h"
#include "core/parallel_for.h"
#include "core/parallel_rewrite.h"
#include "core/parallel_rewrite_internal.h"
#include "core/rule_choice.h"
#include "core/rule_evaluator.h"
#include "core/salts.h"
#include "model/random.h"
#include "pools/large_page_allocator.h"

namespace ontogen {

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
  ++context.stats.rewrites[static_cast<size_t>(RewriteStrategy::RecordSlices)];
  return true;
}

}  // namespace ontogen
