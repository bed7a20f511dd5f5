#pragma once
// One table's worth of variants, run to completion across threads and ranks: what
// `ontogen sweep` runs once and `ontogen evolve` once a generation. Rank 0 keeps the
// journal (interpreters/sweep/sweep_table.h), appending each row as it arrives, and at
// the end writes DIR/results.csv, DIR/results.json, DIR/gallery.png and DIR/gallery.json
// (interpreters/sweep/contact_sheet.h); every rank runs
// its share of the variants not yet in the journal (the k-th of them on rank k mod K),
// on its worker threads. When `stop` says so, no further variant starts: the running
// ones finish and the table of what finished is written. Nothing here prints: progress
// goes to a callback, and why a batch failed comes back in its result.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "batch/cluster.h"
#include "interpreters/sweep/contact_sheet.h"
#include "interpreters/sweep/sweep_table.h"

namespace ontogen {

/// How far a batch has come, as rank 0 sees it after each row.
struct BatchProgress {
  uint64_t done = 0;          ///< rows in the table, from the journal or run now
  uint64_t total = 0;         ///< variants of the batch
  uint64_t failed = 0;        ///< rows with an error
  double secondsLeft = 0;     ///< estimated from the rows run now (seconds)
};

struct BatchDef {
  std::filesystem::path dir;          ///< the folder of the table (made if missing)
  /// The journal's first line: a JSON object of the settings that make the rows. Its
  /// "measures" and "columns" may differ when a journal is resumed (its rows then run
  /// again, measured anew); any other difference refuses the journal.
  std::string header;
  std::vector<std::string> columns;   ///< between `variant` and `error`
  uint64_t count = 0;                 ///< variants 0 .. count - 1
  bool resume = false;                ///< continue the journal in dir (else dir must hold none)
  unsigned workers = 1;               ///< threads on each rank
  /// Runs variant i (on any rank, on a worker thread) and writes its own files; must
  /// not throw.
  std::function<SweepRow(uint64_t)> run;
  /// The values a row of variant i begins with (its defines or genes, its seed): a row of
  /// the journal that says otherwise is not trusted but run again. Empty: not checked.
  std::function<std::vector<std::string>(uint64_t)> leading;
  /// The thumbnail of variant i (for the gallery), whether or not it exists.
  std::function<std::filesystem::path(uint64_t)> thumbnail;
  ContactSheetDef sheet{};
  /// The first this many columns label each tile of the gallery, `NAME=VALUE` apart by
  /// spaces (the values as the table holds them, as the program's text writes them).
  size_t labelColumns = 0;
  /// Asked between rows on the thread that called runBatch: true starts no further
  /// variant (Ctrl-C). Empty: never.
  std::function<bool()> stop;
  /// Called on rank 0, on the thread that called runBatch, after each row; empty: none.
  std::function<void(const BatchProgress&)> progress;
};

/// How a batch ended.
enum class BatchStatus {
  Done,         ///< every variant has its row
  Refused,      ///< the folder holds another batch, or one when not resuming (a usage error)
  OutputError,  ///< the folder, the journal or the table could not be written
  Stopped,      ///< `stop` said so: the table holds what finished
};

struct BatchResult {
  BatchStatus status = BatchStatus::Done;
  std::string message;   ///< why, unless Done or Stopped (on rank 0)
  SweepTable table;      ///< every row finished (all of them unless stopped), on every rank
  uint64_t failed = 0;   ///< rows with an error
};

/// The gallery's tile of `row`: its thumbnail (if written), whether it failed, its label
/// (the first `labelColumns` columns) and its scale (written beside the thumbnail).
ContactTile galleryTile(const std::filesystem::path& thumbnail, const SweepTable& table, const SweepRow& row,
                        size_t labelColumns);

/// Runs the batch; every rank calls it with the same definition.
BatchResult runBatch(const BatchDef& def, Cluster& cluster);

}  // namespace ontogen
