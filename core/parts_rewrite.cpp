// The Parts strategy (core/rewrite_plan.h): a compact word whose choices vary, each
// thread writing a part of its own, copied into the word after.

#include <atomic>

#include "core/compact_rewrite_range.h"

namespace ontogen {

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
    detail::SerialOut serial{out, word};
    double soonest = kForever;
    CompactEvaluation evaluation{seed, nullptr, {}};  // no state: nothing is evaluated
    counted[p] = detail::withLabelsOf(word, [&](const auto& labels) {
      return withValues_
                 ? rewriteRangeWithValues(word, begin, end, horizon, group, labels, serial, stop, soonest, evaluation)
                 : rewriteRange<false>(word, begin, end, horizon, group, labels, serial, stop, soonest, evaluation);
    });
    earliest[p] = soonest;
  };
  detail::forEachIndex(partCount, threads, writePart);

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
  detail::forEachIndex(partCount, threads, [&](size_t p) { next.copyPart(places[p], word.birthCount()); });
  next.endParts(places);
  next.finish();
  for (size_t p = 0; p < partCount; ++p) earliestDeath_ = std::min(earliestDeath_, earliest[p]);
  lastGrowth_ = Growth::of(word, next);
  return counts;
}

}  // namespace ontogen
