#include "core/limits.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

namespace ontogen {

namespace {
std::string mebibytes(uint64_t bytes) { return std::to_string(bytes >> 20); }

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

// The memory of the machine, 0 when it does not say.
uint64_t physicalMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long pageSize = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || pageSize <= 0) return 0;
  return static_cast<uint64_t>(pages) * static_cast<uint64_t>(pageSize);
}

// The memory limit of this process's control group (cgroup v2), 0 for none: a container
// may have far less than the machine.
uint64_t controlGroupMemoryBytes() {
  std::ifstream in("/sys/fs/cgroup/memory.max");
  uint64_t bytes = 0;
  if (!(in >> bytes)) return 0;  // "max", or no cgroup v2
  return bytes;
}
}  // namespace

uint64_t defaultMemoryLimitBytes() {
  static const uint64_t limit = [] {
    uint64_t memory = physicalMemoryBytes();
    if (const uint64_t group = controlGroupMemoryBytes(); group > 0 && (memory == 0 || group < memory)) memory = group;
    return memory == 0 ? uint64_t{8} << 30 : std::max<uint64_t>(memory / 2, uint64_t{1} << 20);
  }();
  return limit;
}

void checkCellLimit(uint64_t cells, const WorldLimits& limits) {
  if (cells > limits.maxCells) [[unlikely]]
    throw LimitError("the model grew past " + std::to_string(limits.maxCells) +
                     " cells, the cell limit; raise it with --max-cells N");
}

void checkTotalCellLimit(uint64_t cells, const WorldLimits& limits) {
  if (cells > limits.maxCells) [[unlikely]]
    throw LimitError("the model grew past " + std::to_string(limits.maxCells) +
                     " cells in all its systems, the cell limit; raise it with --max-cells N");
}

void checkSeedCellLimit(uint64_t cells, const WorldLimits& limits) {
  if (cells > limits.maxCells) [[unlikely]]
    throw LimitError("the pool starts with " + std::to_string(cells) + " cells, past the cell limit of " +
                     std::to_string(limits.maxCells) + "; raise it with --max-cells N");
}

void checkMemoryLimit(uint64_t bytes, const WorldLimits& limits) {
  if (bytes > limits.maxMemoryBytes) [[unlikely]]
    throw LimitError("the model's pools passed " + mebibytes(limits.maxMemoryBytes) +
                     " MiB, the memory limit; raise it with --max-memory MIB");
}

void checkOutsideMemory(const std::string& what, uint64_t bytes, uint64_t held, const WorldLimits& limits) {
  if (bytes > limits.maxMemoryBytes || held > limits.maxMemoryBytes - bytes) [[unlikely]]
    throw LimitError(what + " needs about " + std::to_string((bytes + (1 << 20) - 1) >> 20) + " MiB" +
                     ((held >> 20) > 0 ? " besides the " + mebibytes(held) + " MiB held" : "") +
                     ", past the memory limit of " + mebibytes(limits.maxMemoryBytes) +
                     " MiB; raise it with --max-memory MIB");
}

void checkGridMemory(uint64_t sites, uint64_t bytesPerSite, const WorldLimits& limits, uint64_t held) {
  const uint64_t limit = limits.maxMemoryBytes;
  // Twice: the grid is double buffered. Compared by division so that no product overflows.
  if (held > limit || sites > (limit - held) / (2 * bytesPerSite)) [[unlikely]]
    throw LimitError("the grid's " + std::to_string(sites) + " sites need more than the memory limit of " +
                     mebibytes(limit) + " MiB; raise it with --max-memory MIB");
}

void checkEventLimit(uint64_t events, double when, const WorldLimits& limits) {
  if (events > limits.maxEventsPerStep) [[unlikely]]
    throw LimitError("more than " + std::to_string(limits.maxEventsPerStep) +
                     " terminal-age events in one step (near t = " + std::to_string(when) +
                     "); a lifetime much shorter than the step? Use a smaller --step, or raise --max-events N");
}

void checkStepLimit(uint64_t steps, double more, double dt, double target, const WorldLimits& limits) {
  // `more` may be huge or infinite (a denormal step): compare as doubles.
  if (!(static_cast<double>(steps) + more <= static_cast<double>(limits.maxSteps))) [[unlikely]]
    throw LimitError("reaching t = " + number(target) + " in steps of " + number(dt) + " s takes " +
                     number(static_cast<double>(steps) + more) + " steps, past the step limit of " +
                     std::to_string(limits.maxSteps) + "; use a larger --step, or raise it with --max-steps N");
}

void checkTimeAdvances(double time, double next, double dt) {
  if (!(next > time)) [[unlikely]]
    throw LimitError("a step of " + number(dt) + " s no longer moves the time on at t = " + number(time) +
                     " (it is below the precision of the time there); use a larger --step");
}

}  // namespace ontogen
