#pragma once
// What `ontogen sweep` and `ontogen evolve` share: reading the program and its genes,
// the measures checked against the sets that will run, the run every variant makes,
// and one variant's files (its program with its values written in, its thumbnail).

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/cluster.h"
#include "apps/commands.h"
#include "interpreters/sweep/measure.h"
#include "interpreters/sweep/sweep_table.h"
#include "interpreters/sweep/variant_run.h"
#include "lang/variation.h"

namespace ontogen::app {

/// A sweep or an evolution ready to run: the program's text and genes, the measures,
/// and the definition every variant's run starts from.
struct SweepSetup {
  std::string path;                        ///< the program file as given
  std::string stem;                        ///< its name without folder and extension
  std::unique_ptr<VariationSpace> space;   ///< the genes of the program's text
  std::vector<Measure> measures;
  std::vector<std::string> sets;           ///< the interpretation sets every variant runs
  CompileOptions compile;                  ///< root system, command sets, source limit
  RunDef run;                              ///< seed, limits, sets, picture; program, out and stem unset
  uint64_t programSeed = 1;                ///< the program's #seed (or 1)
  std::string rerunFlags;                  ///< --until, --step, --frames as given, for a variant's note
  unsigned workers = 1;                    ///< threads on this machine
  int digits = 4;                          ///< of a variant's number in its file names
};

/// Reads and checks the program (without --define, which sweep and evolve read their own
/// way), its genes (`variation`), the measures (which may also name `extraNames`), the
/// sets and the run; prints why not and returns the exit code when it cannot.
int prepareSweep(const SweepCommonOptions& options, VariationOptions variation,
                 const std::vector<std::string>& extraNames, SweepSetup& setup);

/// A variant's file name without extension: "v0007" (digits as the setup says).
std::string variantStem(const SweepSetup& setup, uint64_t index);

/// Runs variant `index` of text `text` with `seed` into `dir` (DIR/programs/<stem>.cell,
/// DIR/thumbnails/<stem>.png) and returns its row: `leading` values first (the defines or
/// genes), then the seed, then the measures. `values` are extra quantities the measures
/// may name. Never throws: what fails is the row's error.
SweepRow runSweepVariant(const SweepSetup& setup, const std::filesystem::path& dir, uint64_t index,
                         const std::string& text, uint64_t seed, std::vector<std::string> leading,
                         std::vector<std::pair<std::string, double>> values, const std::string& note);

/// FNV-1a, 64 bits, in hexadecimal: names a program's text in a journal's header.
std::string textDigest(const std::string& text);

/// Joins the MPI job when an MPI launcher started this process (apps/cluster.h); prints
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

}  // namespace ontogen::app
