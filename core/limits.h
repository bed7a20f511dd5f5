#pragma once
// The growth limits' checks, one message each: a model that passes a limit stops with a
// LimitError naming the limit and the flag that raises it, never an out-of-memory kill.

#include <cstdint>
#include <stdexcept>

namespace ontogen {

/// Growth limits of a world (and of all its nested systems together).
struct WorldLimits {
  /// Most cells in the root pool. 100 M cells take about 5 GB with double buffering.
  uint64_t maxCells = 100'000'000;
  /// Most bytes the pools may hold. 8 GiB leaves room on a 16 GB machine.
  uint64_t maxMemoryBytes = 8ull << 30;
  /// Most terminal events in one step: a lifetime far shorter than the step would
  /// otherwise spin for ever renewing one cell.
  uint64_t maxEventsPerStep = 200'000'000;
};

/// A limit was passed; the message names the limit and how to raise it.
struct LimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Throws when `cells` cells in one pool pass the cell limit.
void checkCellLimit(uint64_t cells, const WorldLimits& limits);
/// Throws when `cells` cells in all the systems of a world pass the cell limit.
void checkTotalCellLimit(uint64_t cells, const WorldLimits& limits);
/// Throws when a model starts (seeds a pool) with more cells than the limit allows.
void checkSeedCellLimit(uint64_t cells, const WorldLimits& limits);
/// Throws when the pools hold more than the memory limit.
void checkMemoryLimit(uint64_t bytes, const WorldLimits& limits);
/// Throws when a pool of `sites` grid sites could not be held within the memory limit.
void checkGridMemory(uint64_t sites, uint64_t bytesPerSite, const WorldLimits& limits);
/// Throws when a step has had more than the allowed terminal events; `when` is the time
/// of the last one (seconds).
void checkEventLimit(uint64_t events, double when, const WorldLimits& limits);

}  // namespace ontogen
