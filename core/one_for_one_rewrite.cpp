// The OneForOne strategy (core/rewrite_plan.h): a compact word whose modules each write
// one, its slices written in place in one pass.

#include <stdexcept>

#include "core/compact_rewrite_range.h"

namespace ontogen {

namespace {
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
  detail::knowTheBirth(next, slices, expectedBirth);
  std::vector<CompactCounts> counted(sliceCount);
  std::vector<double> earliest(sliceCount, kForever);
  auto never = [](const CompactCounts&) { return false; };
  detail::forEachIndex(sliceCount, threads, [&](size_t s) {
    CompactWord::Slice& out = slices[s];
    CompactEvaluation evaluation{seed, nullptr, {}};  // no state: nothing is evaluated
    double soonest = kForever;                        // on the thread's stack: `earliest` shares a cache line
    SliceOut written{out};
    counted[s] = detail::withLabelsOf(word, [&](const auto& labels) {
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

}  // namespace ontogen
