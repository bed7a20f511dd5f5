#pragma once
// `ontogen sweep` and `ontogen evolve` on the terminal, over the batch library (batch/):
// the program read and checked with its diagnostics printed, the MPI job joined, the
// progress bar, Ctrl-C, and a batch's end as a message and an exit code.

#include <cstdint>
#include <memory>
#include <streambuf>
#include <string>

#include "apps/commands.h"
#include "apps/progress_bar.h"
#include "batch/batch_run.h"
#include "batch/cluster.h"
#include "batch/sweep_setup.h"

namespace ontogen::app {

/// Reads and checks the program (without --define, which sweep and evolve read their
/// own way) and turns the options into the library's settings; prints why not and
/// returns the exit code when it cannot.
int readSweepSettings(const SweepCommonOptions& options, SweepSettings& settings);

/// Makes the setup from the settings; prints why not and returns the exit code when it
/// cannot.
int prepareSweepReporting(const SweepSettings& settings, SweepSetup& setup);

/// Joins the MPI job when an MPI launcher started this process (batch/cluster.h); prints
/// why not and returns null when it cannot.
std::unique_ptr<Cluster> joinCluster();

/// Keeps std::cerr quiet on every rank but the first (each rank would print the same
/// diagnostics), for as long as it lives.
class QuietFollowers {
 public:
  explicit QuietFollowers(bool leader);
  ~QuietFollowers();
  QuietFollowers(const QuietFollowers&) = delete;
  QuietFollowers& operator=(const QuietFollowers&) = delete;

 private:
  std::streambuf* saved_ = nullptr;
};

/// Ctrl-C (SIGINT) while it lives asks the batch to stop: no further variant starts, the
/// running ones finish and the table of what finished is written. The handler then gives
/// the signal back to the one before it (which removes temporaries and ends the
/// process), so a second Ctrl-C ends at once.
class BatchInterrupt {
 public:
  BatchInterrupt();
  ~BatchInterrupt();
  BatchInterrupt(const BatchInterrupt&) = delete;
  BatchInterrupt& operator=(const BatchInterrupt&) = delete;
  /// Whether Ctrl-C came (BatchDef::stop).
  static bool requested();
};

/// A batch's progress on a bar (rank 0 only), labelled `label`.
class BatchProgressBar {
 public:
  BatchProgressBar(std::string label, std::optional<bool> show, bool leader);
  /// For BatchDef::progress.
  std::function<void(const BatchProgress&)> callback();
  /// Ends the bar's line, prints why the batch failed and gives its exit code.
  int finish(const BatchResult& result);

 private:
  ProgressBar bar_;
  bool leader_;
};

}  // namespace ontogen::app
