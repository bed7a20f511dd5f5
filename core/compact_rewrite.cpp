// The compact word's strategies of ParallelRewrite (core/rewrite_plan.h): one pass on
// one thread (CompactSerial), the table's walk (TableAlone), slices written one module for
// one (OneForOne), parts copied in (Parts), slices placed by the table's bounds
// (TableBounds) and slices counted then written (CompactSlices), all through rewriteRange,
// which rewrites a range of the word whatever writes it. The records' slices, and what
// the rules allow, are in core/parallel_rewrite.cpp.

#include <algorithm>
#include <atomic>
#include <bit>
#include <cstdint>
#include <stdexcept>

#include "core/cell_frame.h"
#include "core/parallel_for.h"
#include "core/parallel_rewrite.h"
#include "core/parallel_rewrite_internal.h"
#include "core/rule_choice.h"
#include "core/salts.h"
#include "lang/expression_batch.h"
#include "lang/random.h"
#include "pools/large_page_allocator.h"

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
std::optional<ParallelRewrite::CompactCounts> ParallelRewrite::rewriteSerially(const CompactWord& word, double horizon,
                                                                               int group, CompactWord& next,
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
