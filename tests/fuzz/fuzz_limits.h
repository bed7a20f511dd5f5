#pragma once
// What the fuzz targets give a program: small limits, so that no input can make a
// target hang or run out of memory, only stop at a limit as `ontogen` would.

#include <cstdint>

#include "core/limits.h"

namespace ontogen::fuzz {

/// The name the input is compiled under. Its folder does not exist, so a relative
/// `import` finds no file (an error, as for a user), and absolute ones read what they
/// name, through the same checks as the executable (regular files, the size limit).
inline constexpr const char* kProgramName = "/nonexistent-ontogen-fuzz/fuzz.cell";

/// Source text with imports, bytes: 1 MiB, far above what libFuzzer makes (-max_len) and
/// far below what would take the sanitizers' memory.
inline constexpr uint64_t kMaxSourceBytes = uint64_t{1} << 20;

/// Growth limits of the grow target: a few thousand cells and a few steps are enough to
/// run every rule kind, and keep one input well under the time limit under the sanitizers.
inline WorldLimits growLimits() {
  WorldLimits limits;
  limits.maxCells = 4096;
  limits.maxMemoryBytes = uint64_t{64} << 20;  // 64 MiB
  limits.maxEventsPerStep = 20'000;
  limits.maxSteps = 16;
  return limits;
}

/// Steps the grow target develops.
inline constexpr int kGrowSteps = 8;

}  // namespace ontogen::fuzz
