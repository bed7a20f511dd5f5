#pragma once
// The growth limits' checks, one message each: a model that passes a limit stops with a
// LimitError naming the limit and the flag that raises it, never an out-of-memory kill
// and never a run that goes on for ever. Pools check them as they make cells, within a
// step, counting what the rest of the world holds too (StepContext::held).

#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace ontogen {

/// The memory limit a world gets when none is given: half the memory this process may
/// use (memoryAvailableBytes()), so a runaway model stops before the machine swaps or the
/// kernel kills it, leaving the other half to the outputs, the system and other programs.
/// 8 GiB when nothing says.
uint64_t defaultMemoryLimitBytes();

/// What bounds the memory of this process, each 0 when it sets no bound.
struct MemoryBounds {
  uint64_t physical = 0;       ///< the machine's RAM (bytes)
  uint64_t controlGroupV2 = 0;  ///< memory.max of the process's cgroup v2 and its ancestors
  uint64_t controlGroupV1 = 0;  ///< memory.limit_in_bytes of its cgroup v1 memory group and its ancestors
  uint64_t addressSpace = 0;   ///< RLIMIT_AS (soft)
};

/// The bounds as this machine gives them. `root` stands for `/` (tests give a folder of
/// fake /proc/self/cgroup and /sys/fs/cgroup files); RLIMIT_AS is read from the process.
MemoryBounds readMemoryBounds(const std::string& root = "/");
/// The cgroup v2 limit below `root`: the least memory.max of the process's group (from
/// `root`/proc/self/cgroup, line `0::/path`) and its ancestors under
/// `root`/sys/fs/cgroup, 0 when all say `max` or there is none.
uint64_t readControlGroupV2Bytes(const std::string& root);
/// The cgroup v1 limit below `root`: the least memory.limit_in_bytes of the memory
/// controller's group (line `N:memory:/path`) and its ancestors under
/// `root`/sys/fs/cgroup/memory. 0 when there is none, or it is v1's "unlimited" (a page
/// count near 2^63, 9223372036854771712 with 4 KiB pages).
uint64_t readControlGroupV1Bytes(const std::string& root);
/// The least of the bounds that are set (0 when none is).
uint64_t memoryAvailableBytes(const MemoryBounds& bounds);
/// Half of memoryAvailableBytes (at least 1 MiB), or 8 GiB when no bound is set.
uint64_t defaultMemoryLimitBytes(const MemoryBounds& bounds);

/// Growth limits of a world (and of all its nested systems together).
struct WorldLimits {
  /// Most cells in one pool, and in all pools together. 100 M cells take about 5 GB with
  /// double buffering.
  uint64_t maxCells = 100'000'000;
  /// Most bytes the pools and the outputs a run holds may take (defaultMemoryLimitBytes()).
  uint64_t maxMemoryBytes = defaultMemoryLimitBytes();
  /// Most terminal events in one step: a lifetime far shorter than the step would
  /// otherwise spin for ever renewing one cell.
  uint64_t maxEventsPerStep = 200'000'000;
  /// Most steps of one world: a step far too small for the time to reach (#dt 1e-320,
  /// --step 1e-12, #until 1e308) would otherwise run for ever without a word. 100 M steps
  /// of a one-cell model take about 6 s, of a thousand-cell one hours; real runs take
  /// thousands.
  uint64_t maxSteps = 100'000'000;
  /// Cooperative cancellation: when another thread sets it, growth stops with
  /// GrowthCancelled at the next step and as pools make cells within a step (the world is
  /// then left part-way through a step: read its statistics, do not grow it on). Owned by
  /// the caller and outliving the growth; null: never cancelled.
  const std::atomic<bool>* cancel = nullptr;
};

/// A limit was passed; the message names the limit and how to raise it.
struct LimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Growth was cancelled through WorldLimits::cancel: a stop asked for, not a failure.
struct GrowthCancelled : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Throws GrowthCancelled when limits.cancel is set.
inline void checkCancelled(const WorldLimits& limits) {
  if (limits.cancel && limits.cancel->load(std::memory_order_relaxed)) [[unlikely]]
    throw GrowthCancelled("the growth was cancelled");
}
/// Throws when `cells` cells in one pool pass the cell limit.
void checkCellLimit(uint64_t cells, const WorldLimits& limits);
/// Throws when `cells` cells in all the systems of a world pass the cell limit.
void checkTotalCellLimit(uint64_t cells, const WorldLimits& limits);
/// Throws when a model starts (seeds a pool) with more cells than the limit allows.
void checkSeedCellLimit(uint64_t cells, const WorldLimits& limits);
/// Throws when the pools (and what the run holds besides) take more than the memory limit.
void checkMemoryLimit(uint64_t bytes, const WorldLimits& limits);
/// Throws when something that is not a pool (`what`: "a 8192x8192 picture") would need
/// `bytes` more, on top of `held` bytes already held, past the memory limit.
void checkOutsideMemory(const std::string& what, uint64_t bytes, uint64_t held, const WorldLimits& limits);
/// Throws when a pool of `sites` grid sites of `bytesPerSite` bytes each (at the peak of a
/// step) could not be held within the memory limit, with `held` bytes held elsewhere.
void checkGridMemory(uint64_t sites, uint64_t bytesPerSite, const WorldLimits& limits, uint64_t held = 0);
/// Throws when a step has had more than the allowed terminal events; `when` is the time
/// of the last one (seconds).
void checkEventLimit(uint64_t events, double when, const WorldLimits& limits);
/// Throws when `steps` steps would pass the step limit: `steps` already taken, `more` to
/// come (seconds `dt` each, to reach `target`).
void checkStepLimit(uint64_t steps, double more, double dt, double target, const WorldLimits& limits);
/// Throws when a step of `dt` from `time` no longer moves the time on (`next` ≤ `time`):
/// the step is below the precision of the time.
void checkTimeAdvances(double time, double next, double dt);

}  // namespace ontogen
