#pragma once
// Counting what a parallel step makes as it makes it. The chunks of a step (one per
// thread) each report the cells and bytes they made; the meter adds them up and stops
// the step (LimitError, through checkGrowth) once they pass a limit, instead of after the
// step has allocated all of it. A reading is never more than the step's final count, so
// whether a step stops does not depend on the number of threads: it stops exactly when
// its final count, checked after the merge, would.

#include <atomic>
#include <cstdint>

#include "core/development.h"

namespace ontogen {

class GrowthMeter {
 public:
  /// `held`: what the pool holds already during the step (its cells and bytes at the start).
  GrowthMeter(const StepContext& context, WorldHeld held)
      : context_(context), held_(held), interval_(growthCheckInterval(context.limits)) {}

  /// What one chunk has reported so far.
  struct Reported {
    uint64_t cells = 0;
    uint64_t bytes = 0;
    uint64_t calls = 0;  ///< cells developed since the last report
  };
  /// After each cell a chunk develops: the chunk now holds `cells` cells in `bytes`
  /// bytes. Every interval's worth of cells, reports what it made since `reported` and
  /// checks the limits.
  void update(Reported& reported, uint64_t cells, uint64_t bytes) {
    if (++reported.calls < interval_) [[likely]]
      return;
    add(cells - reported.cells, bytes - reported.bytes);
    reported = {cells, bytes, 0};
  }

 private:
  void add(uint64_t cells, uint64_t bytes) {
    const uint64_t madeCells = cells_.fetch_add(cells, std::memory_order_relaxed) + cells;
    const uint64_t madeBytes = bytes_.fetch_add(bytes, std::memory_order_relaxed) + bytes;
    // The cells made replace the pool's; its bytes are held until the step ends.
    checkGrowth(context_, madeCells, held_.bytes + madeBytes);
  }

  const StepContext& context_;
  WorldHeld held_;
  uint64_t interval_;
  std::atomic<uint64_t> cells_{0};
  std::atomic<uint64_t> bytes_{0};
};

}  // namespace ontogen
