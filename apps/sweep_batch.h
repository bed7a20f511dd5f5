#pragma once
// One table's worth of variants, run to completion across threads and ranks: what
// `ontogen sweep` runs once and `ontogen evolve` once a generation. Rank 0 keeps the
// journal (interpreters/sweep/sweep_table.h), appending each row as it arrives, and at
// the end writes DIR/results.csv, DIR/results.json and DIR/gallery.png; every rank runs
// its share of the variants not yet in the journal (the k-th of them on rank k mod K),
// on its worker threads. Ctrl-C (SIGINT) starts no further variant, waits for the
// running ones and writes the table of what finished; a second Ctrl-C ends at once.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "apps/cluster.h"
#include "interpreters/sweep/contact_sheet.h"
#include "interpreters/sweep/sweep_table.h"

namespace ontogen::app {

struct BatchDef {
  std::filesystem::path dir;          ///< the folder of the table (made if missing)
  std::string header;                 ///< the journal's first line: the settings that make the rows
  std::vector<std::string> columns;   ///< between `variant` and `error`
  uint64_t count = 0;                 ///< variants 0 .. count - 1
  bool resume = false;                ///< continue the journal in dir (else dir must hold none)
  unsigned workers = 1;               ///< threads on each rank
  std::string label = "sweep";        ///< the progress bar's
  std::optional<bool> progress;       ///< draw the bar on rank 0; empty: when stderr is a terminal
  /// Runs variant i (on any rank, on a worker thread) and writes its own files; must
  /// not throw.
  std::function<SweepRow(uint64_t)> run;
  /// The thumbnail of variant i (for the gallery), whether or not it exists.
  std::function<std::filesystem::path(uint64_t)> thumbnail;
  ContactSheetDef sheet{};
};

struct BatchResult {
  int exitCode = 0;      ///< kExitOk, or why the batch stopped (usage, output, interrupted)
  SweepTable table;      ///< every row finished (all of them unless interrupted), on every rank
  uint64_t failed = 0;   ///< rows with an error
};

/// Runs the batch; every rank calls it with the same definition.
BatchResult runBatch(const BatchDef& def, Cluster& cluster);

/// Ctrl-C while a batch runs: set by the handler, read between variants.
bool batchInterrupted();

}  // namespace ontogen::app
