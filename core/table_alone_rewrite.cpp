// The TableAlone strategy (core/rewrite_plan.h): a compact word walked by its table
// (pools/table_rewrite.h) in one pass on one thread, without counting first.

#include "core/compact_rewrite_range.h"
#include "pools/table_rewrite.h"

namespace ontogen {

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
  detail::knowTheBirth(next, {&slice, 1}, expectedBirth);
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

}  // namespace ontogen
