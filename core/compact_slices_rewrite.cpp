// The TableBounds and CompactSlices strategies (core/rewrite_plan.h): a compact word
// rewritten by slices, placed by the table's bounds (pools/table_rewrite.h) or counted
// then written. One executor: slices whose bounds miss are counted and written again.

#include "core/compact_rewrite_range.h"
#include "pools/table_rewrite.h"

namespace ontogen {

// Slices on several threads, or a large word counted first on one: every slice counts,
// then writes in place (CompactWord::Slice); or, for the table's words, each is placed by
// its bounds and written once.
std::optional<ParallelRewrite::CompactCounts> ParallelRewrite::rewriteBySlices(
    const CompactWord& word, double horizon, int group, unsigned threads, CompactWord& next, const CompactFits& fits,
    uint64_t seed, const double* ancestors, double expectedBirth, bool placeByBounds) {
  const size_t size = word.size();
  auto withLabels = [&](const auto& work) { return detail::withLabelsOf(word, work); };
  const size_t sliceCount = std::max<size_t>(1, std::min<size_t>(size, size_t{threads} * kSlicesPerThread));
  auto everySlice = [&](const auto& work) { detail::forEachIndex(sliceCount, threads, work); };

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
      detail::knowTheBirth(next, slices, expectedBirth);
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
  if (byTable_) detail::knowTheBirth(next, slices, expectedBirth);
  everySlice(pass);
  return joinTheSlices(counts);
}

}  // namespace ontogen
