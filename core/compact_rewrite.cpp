// The compact word's rewrite (ParallelRewrite::rewriteCompact): the plan's strategy
// (core/rewrite_plan.h) run by its executor, each in a file of its own: one pass on one
// thread (core/compact_serial_rewrite.cpp), the table's walk (core/table_alone_rewrite.cpp),
// slices written one module for one (core/one_for_one_rewrite.cpp), parts copied in
// (core/parts_rewrite.cpp), slices placed by the table's bounds or counted then written
// (core/compact_slices_rewrite.cpp); what they share is here and in
// core/compact_rewrite_range.h. What the rules allow is in core/parallel_rewrite.cpp.

#include <stdexcept>

#include "core/compact_rewrite_range.h"

namespace ontogen {

void detail::knowTheBirth(CompactWord& next, std::span<CompactWord::Slice> slices, double birth) {
  if (!(birth < kForever)) return;
  const uint32_t index = next.birthIndexOf(birth);
  for (CompactWord::Slice& slice : slices) slice.knowBirth(birth, index);
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
  RewriteFacts known = facts(size, threads);
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

void ParallelRewrite::joinWrittenSlices(const CompactWord& word, CompactWord& next,
                                        std::span<CompactWord::Slice> slices, std::span<const double> earliest,
                                        bool closeGaps, unsigned threads) {
  if (closeGaps) next.closeRunGaps(slices);
  next.joinSlices(slices);
  detail::forEachIndex(slices.size(), threads, [&](size_t s) { slices[s].place(); });
  next.finish();
  for (double soonest : earliest) earliestDeath_ = std::min(earliestDeath_, soonest);
  lastGrowth_ = Growth::of(word, next);
}

}  // namespace ontogen
