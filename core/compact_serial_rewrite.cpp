// The CompactSerial strategy (core/rewrite_plan.h): a compact word rewritten in one pass
// on one thread.

#include "core/compact_rewrite_range.h"

namespace ontogen {

// One pass on one thread, writing the next word as it goes and asking `fits` on the way.
// A large word's arrays are reserved for the growth of the last rewrite, since growing
// them as it goes would hold a copy more (Koch at n = 10: 144 MB against 101 MB).
std::optional<ParallelRewrite::CompactCounts> ParallelRewrite::rewriteSerially(const CompactWord& word, double horizon,
                                                                               int group, CompactWord& next,
                                                                               const CompactFits& fits, uint64_t seed,
                                                                               const double* ancestors) {
  const size_t size = word.size();
  auto withLabels = [&](const auto& work) { return detail::withLabelsOf(word, work); };
  if (size >= kMinimumCells)
    next.reserve(Growth::room(size, lastGrowth_.modules), Growth::room(word.runCount(), lastGrowth_.runs),
                 withValues_ ? Growth::room(word.valueCount(), lastGrowth_.values) : 0);
  detail::SerialOut out{next, word};
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

}  // namespace ontogen
