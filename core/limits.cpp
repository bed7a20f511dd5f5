#include "core/limits.h"

#include <string>

namespace ontogen {

namespace {
std::string mebibytes(uint64_t bytes) { return std::to_string(bytes >> 20); }
}  // namespace

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

void checkGridMemory(uint64_t sites, uint64_t bytesPerSite, const WorldLimits& limits) {
  if (sites * bytesPerSite * 2 > limits.maxMemoryBytes) [[unlikely]]
    throw LimitError("the grid's " + std::to_string(sites) + " sites need more than the memory limit of " +
                     mebibytes(limits.maxMemoryBytes) + " MiB; raise it with --max-memory MIB");
}

void checkEventLimit(uint64_t events, double when, const WorldLimits& limits) {
  if (events > limits.maxEventsPerStep) [[unlikely]]
    throw LimitError("more than " + std::to_string(limits.maxEventsPerStep) +
                     " terminal-age events in one step (near t = " + std::to_string(when) +
                     "); a lifetime much shorter than the step? Use a smaller --step, or raise --max-events N");
}

}  // namespace ontogen
