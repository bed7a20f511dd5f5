#pragma once
// A sweep: a program run once for every combination of values of some of its #defines
// and of seeds, each variant measured, into one table (docs/SWEEPS.md). Variant i is the
// i-th of the product, the first define outermost and the seed innermost. What
// `ontogen sweep` runs after reading its command line, and what a host program calls.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "batch/batch_run.h"
#include "batch/cluster.h"
#include "batch/sweep_setup.h"

namespace ontogen {

/// Variants of one sweep: the journal and the tables hold every row in memory, about
/// 200 bytes each; ten million is 2 GB.
inline constexpr uint64_t kMaxSweepVariants = 10'000'000;

/// One #define of the program and the values it takes.
struct SweptDefine {
  std::string name;
  std::vector<double> values;
  std::vector<std::string> written;  ///< the values as the table writes them (formatValue)
};

struct SweepDef {
  /// The program and what every variant runs; `extraNames` is filled in from `defines`.
  SweepSettings settings;
  std::vector<SweptDefine> defines;          ///< each a #define of the program whose value is a number
  std::pair<uint64_t, uint64_t> seeds{1, 1};  ///< first and last seed, inclusive
  std::filesystem::path out;                  ///< the sweep's folder
  bool resume = false;                        ///< continue the journal in `out`
  std::string sizeText;                       ///< the thumbnails' size as given ("128x128"), for the journal's header
  std::function<bool()> stop;                 ///< BatchDef::stop
  std::function<void(const BatchProgress&)> progress;  ///< BatchDef::progress
};

struct SweepResult {
  BatchResult batch;      ///< how it ended, the table (its rows in variant order)
  uint64_t count = 0;     ///< variants of the sweep
  std::string stem;       ///< the program's, for messages
};

/// Checks the definition (a usage error is BatchStatus::Refused with its message) and
/// runs the sweep; every rank calls it with the same definition.
SweepResult runSweep(SweepDef def, Cluster& cluster);

/// Runs a sweep on this machine alone.
SweepResult runSweep(SweepDef def);

}  // namespace ontogen
