#include "core/rewrite_plan.h"

#include <algorithm>

namespace ontogen {

std::string_view rewriteStrategyName(RewriteStrategy strategy) {
  switch (strategy) {
    case RewriteStrategy::Serial:
      return "serial";
    case RewriteStrategy::CompactSerial:
      return "compact-serial";
    case RewriteStrategy::TableAlone:
      return "table-alone";
    case RewriteStrategy::OneForOne:
      return "one-for-one";
    case RewriteStrategy::Parts:
      return "parts";
    case RewriteStrategy::TableBounds:
      return "table-bounds";
    case RewriteStrategy::CompactSlices:
      return "compact-slices";
  }
  return "serial";
}

std::string formatRewriteCounts(const RewriteCounts& counts) {
  std::string text;
  for (size_t k = 0; k < kRewriteStrategyCount; ++k) {
    if (counts[k] == 0) continue;
    if (!text.empty()) text += ", ";
    text += rewriteStrategyName(static_cast<RewriteStrategy>(k));
    text += ' ';
    text += std::to_string(counts[k]);
  }
  return text;
}

namespace {

bool onOneThread(RewriteStrategy strategy) {
  return strategy == RewriteStrategy::Serial || strategy == RewriteStrategy::CompactSerial ||
         strategy == RewriteStrategy::TableAlone;
}

// What the development does unforced: the fastest strategy that applies, by the sizes
// and threads the benchmarks of bench/ measured. A word smaller than kMinimumSliceCells
// is planned as on one thread.
RewriteStrategy choose(const RewriteFacts& facts) {
  const RewriteShape& shape = facts.shape;
  const bool large = facts.size >= kMinimumSliceCells;
  const bool oneThread = !large || facts.threads <= 1;
  // A word of records has one pass; the words of bench/ that pay for more are kept compact.
  if (facts.pass != RewritePass::Compact) return RewriteStrategy::Serial;
  // A word written without ids takes the table's walk at every size on one thread.
  if (facts.withoutIds && oneThread) return RewriteStrategy::TableAlone;
  // A large word whose modules each write one, on any number of threads: in place, in one pass.
  if (large && rewriteApplies(RewriteStrategy::OneForOne, facts)) return RewriteStrategy::OneForOne;
  // One thread: one pass for a small word, and for a large one whose choices vary (counting
  // first would choose twice) or whose values are evaluated (it would walk the events
  // twice), once the growth to reserve by is known.
  const bool onePass = shape.choiceVaries || shape.batched;
  if (oneThread && (!large || (onePass && facts.growthKnown))) return RewriteStrategy::CompactSerial;
  if (oneThread && shape.byTable) return RewriteStrategy::TableAlone;
  if (large && rewriteApplies(RewriteStrategy::Parts, facts)) return RewriteStrategy::Parts;
  if (rewriteApplies(RewriteStrategy::TableBounds, facts)) return RewriteStrategy::TableBounds;
  return RewriteStrategy::CompactSlices;
}

}  // namespace

bool rewriteApplies(RewriteStrategy strategy, const RewriteFacts& facts) {
  const RewriteShape& shape = facts.shape;
  const bool compact = facts.pass == RewritePass::Compact;
  switch (strategy) {
    case RewriteStrategy::Serial:
      return !compact;
    case RewriteStrategy::CompactSerial:
      return compact && !facts.withoutIds;
    case RewriteStrategy::TableAlone:
      return compact && shape.byTable;
    case RewriteStrategy::OneForOne:
      return compact && !facts.withoutIds && shape.choiceVaries && !shape.withValues && shape.oneForOne &&
             !facts.inPlaceRefused;
    case RewriteStrategy::Parts:
      // Parts are reserved by the growth of the last rewrite and hold no state values.
      return compact && !facts.withoutIds && shape.choiceVaries && !shape.anyState && facts.growthKnown;
    case RewriteStrategy::TableBounds:
      return compact && shape.byTable && !facts.boundsMissed;
    case RewriteStrategy::CompactSlices:
      return compact;
  }
  return false;
}

// The one place the threads of a rewrite are decided: every thread the world has for a
// strategy that splits the word (unforced, only a large word takes one), else one.
RewritePlan planRewrite(const RewriteFacts& facts) {
  const RewriteStrategy strategy = facts.forced && rewriteApplies(*facts.forced, facts) ? *facts.forced : choose(facts);
  return {strategy, onOneThread(strategy) ? 1u : std::max(1u, facts.threads)};
}

bool keepsWordCompact(const RewriteShape& shape, bool slices, bool lineage,
                      const std::optional<RewriteStrategy>& forced) {
  if (!shape.compact || lineage) return false;
  return forced ? rewritesCompactWords(*forced) : slices;
}

bool writesWordsWithoutIds(const RewriteShape& shape, bool wordsWithoutIds,
                           const std::optional<RewriteStrategy>& forced) {
  // Of the compact strategies a table's word may take (its choices are fixed, so neither
  // OneForOne nor Parts), only CompactSerial writes ids.
  return wordsWithoutIds && shape.byTable && forced != RewriteStrategy::CompactSerial;
}

}  // namespace ontogen
