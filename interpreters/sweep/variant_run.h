#pragma once
// One variant of a sweep or an evolution: a program text with its values written in,
// compiled, grown through a Run (interpreters/run.h) on one thread with a seed, its
// last frame pictured as a thumbnail, and measured. Nothing a variant does ends the
// sweep: a text that does not compile, a model that fails or passes a limit, a measure
// that is not finite, all become the row's error.

#include <string>
#include <utility>
#include <vector>

#include "interpreters/run.h"
#include "interpreters/sweep/measure.h"
#include "lang/compiler.h"

namespace ontogen {

/// What to run; the caller fills `run` as for any run, but for its program.
struct VariantDef {
  std::string name;        ///< the program's name in diagnostics (the original file's path)
  std::string text;        ///< the variant's program text
  CompileOptions compile;  ///< root system, command sets, source limit (the text holds the values)
  /// The run: seed and limits in run.world (threads 1: a variant is one task), sets and
  /// picture size in run.sets and run.setOptions, the thumbnail's folder and name in
  /// run.out and run.stem. run.program and run.world.environment are set from the text.
  RunDef run;
  std::vector<Measure> measures;
  /// Quantities the measures may name besides the run's (a sweep's define values).
  std::vector<std::pair<std::string, double>> values;
};

struct VariantResult {
  std::vector<double> measures;  ///< one per measure; NaN where it has no finite value
  std::string error;             ///< the first error, on one line; empty when none
  /// The thumbnail's scale: pixels per model unit at the centre of the last frame's
  /// model, as the picture's camera frames it; 0 when nothing was drawn.
  double pixelsPerUnit = 0;
};

/// The one-line form of a run's diagnostic for a table: "file:line:col: message" where
/// it has a place, else the message; line breaks become spaces.
std::string oneLine(const RunDiagnostic& diagnostic);

/// Runs the variant. Never throws for what the program does; the result says what failed.
VariantResult runVariant(VariantDef def);

}  // namespace ontogen
