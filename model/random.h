#pragma once
// Counter-based random numbers. A stream is made from a key (the run's seed mixed with
// a cell's id and the instant of the event), so the numbers a cell draws do not depend
// on the order in which cells are visited, the number of threads or the step size.

#include <bit>
#include <cstdint>

#include "pools/mix_key.h"

namespace ontogen {

/// A small deterministic generator (SplitMix64 over a counter).
class RandomStream {
 public:
  explicit RandomStream(uint64_t key = 0) : state_(key) {}

  uint64_t next();
  /// Uniform in [0, 1), 53 random bits.
  double uniform();
  /// Standard normal N(0, 1) by Box-Muller; keeps no spare so each call is self-contained.
  double gaussian();

 private:
  uint64_t state_;
};

}  // namespace ontogen
