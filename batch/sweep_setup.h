#pragma once
// What a sweep and an evolution share: the program's text and genes, the measures
// checked against the sets that will run, the run every variant makes, and one
// variant's files (its program with its values written in, its thumbnail). Nothing
// here prints: what is wrong with the settings comes back as a message.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/limits.h"
#include "interpreters/run.h"
#include "interpreters/sweep/measure.h"
#include "interpreters/sweep/sweep_table.h"
#include "interpreters/sweep/variant_run.h"
#include "lang/compiler.h"
#include "model/program.h"
#include "lang/variation.h"

namespace ontogen {

/// The settings of a sweep or an evolution that are not its variants: the program, what
/// every variant runs and measures, and the thumbnails.
struct SweepSettings {
  std::string path;                       ///< the program file as given (names it in notes and the journal)
  std::string stem;                       ///< its name without folder and extension
  std::string text;                       ///< its cell-language text (a cpfg or L-Py file converted)
  /// The program compiled from `text` with the fixed --define values: its #seed,
  /// #interpret and the defines given a value, which are written into every variant.
  std::shared_ptr<const Program> program;
  VariationOptions variation;             ///< the genes (a sweep: the defaults)
  std::vector<std::string> measures;      ///< `NAME=EXPR`
  std::vector<std::string> extraNames;    ///< further quantities the measures may name (the swept defines)
  std::vector<std::string> sets;          ///< empty: the program's #interpret, else geometry
  std::string system;                     ///< root system; empty: the first
  uint64_t maxSourceBytes = kDefaultMaxSourceBytes;
  WorldLimits limits;
  std::optional<double> until;            ///< seconds; empty: the program's #until
  std::optional<double> step;             ///< seconds; empty: the program's #dt
  std::optional<int> frames;              ///< empty: the program's #fps, else 1
  int width = 128, height = 128;          ///< of the thumbnails, pixels
  std::vector<double> view;               ///< azimuth, elevation in degrees; empty: automatic
  unsigned workers = 0;                   ///< threads on this machine; 0: all cores
};

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

/// Checks the settings and makes the setup: the genes of the text (the fixed defines
/// written in), the measures (which may also name `extraNames`), the sets and the run.
/// Returns why not (a usage error) or an empty string.
std::string prepareSweep(const SweepSettings& settings, SweepSetup& setup);

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

}  // namespace ontogen
