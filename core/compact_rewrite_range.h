#pragma once
// rewriteRange, the loop every compact strategy but the table's walk rewrites a range of
// a word by (core/compact_rewrite.cpp and the strategies' files beside it), with what it
// calls and what the strategies share: private to them. Templates, instantiated by each
// strategy for the writer and the labels it has.

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "core/cell_frame.h"
#include "core/parallel_for.h"
#include "core/parallel_rewrite.h"
#include "core/parallel_rewrite_internal.h"
#include "core/rule_choice.h"
#include "core/salts.h"
#include "model/expression_batch.h"
#include "model/random.h"
#include "pools/compact_word.h"

namespace ontogen {

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

namespace detail {
// The modules a step of a word rewritten by the table makes are born when their parents
// die, most often all at the earliest death of the word (the step's instant; the horizon
// is a little past it): that birth goes into the next word's table before the slices
// write, so that no slice adds it as a birth of its own, which Slice::place would have to
// renumber in every run. A guess that misses costs an unused entry.
void knowTheBirth(CompactWord& next, std::span<CompactWord::Slice> slices, double birth);

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
}  // namespace detail

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
  detail::KeptStretch kept;
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
    kept = detail::KeptStretch{cell.index(), 1, cell.key(), renewed, cell.birthIndex(), birth};
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

// As LinearDevelopment::expire writes a cell of records: the same rule, ids, births and
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

}  // namespace ontogen
