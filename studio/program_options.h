#pragma once
// How the studio reads and grows its program: the settings of `ontogen run` it shares
// (file, root system, seed, step, limits, threads, source size), given by the command
// that starts the studio. The studio library knows nothing of the command line.

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/limits.h"
#include "core/world.h"
#include "lang/convert/lsystem_file.h"
#include "model/diagnostics.h"
#include "model/program.h"
#include "lang/source_reader.h"

namespace ontogen::studio {

/// A program's text as read for the studio.
struct StudioSource {
  std::optional<std::string> text;  ///< empty when it cannot be read
  std::string name;                 ///< names the text in diagnostics
  std::string error;                ///< why there is no text
  /// A file of another tool (cpfg, L-Py) converted when read: the file itself, and for
  /// each line of `text` the bytes of it the line was written from, so that diagnostics
  /// are shown at the file's own lines (convert::mapToOriginal). Null: not converted.
  std::shared_ptr<const SourceFile> original;
  std::vector<convert::SourceRange> lineOrigins;
};

/// Reads the program file at path, at most maxBytes of it (with its imports), within
/// `limits`: the interactive limits of the growth it is read for (StudioModel), which
/// may refuse a file whose checking or conversion would pass their memory.
using StudioReader =
    std::function<StudioSource(const std::string& path, uint64_t maxBytes, const WorldLimits& limits)>;

struct StudioProgramOptions {
  std::string file;                       ///< the program file
  std::string system;                     ///< root system; empty: the first
  std::map<std::string, double> defines;  ///< define values to start from (`--define`)
  std::optional<uint64_t> seed;           ///< empty: the program's #seed
  std::optional<double> step;             ///< empty: the program's #dt
  WorldLimits limits;  ///< the command line's; the studio's interactive limits are at most these
  unsigned threads = 0;                              ///< 0: all cores
  int maxErrors = kDefaultMaxErrors;                 ///< errors reported before the compiler stops; 0: all
  uint64_t maxSourceBytes = kDefaultMaxSourceBytes;  ///< of the program and its imports
  /// Reads the file; empty: read as a cell-language file (lang/source_reader.h). The
  /// command gives one that converts cpfg and L-Py files too, held to the limits given.
  StudioReader read;
};

/// The program file's text, read as options say within `limits` (the interactive ones).
StudioSource readStudioSource(const StudioProgramOptions& options, const WorldLimits& limits);

/// The world a run of program grows with these options.
WorldDef worldDefOf(const StudioProgramOptions& options, const Program& program);

}  // namespace ontogen::studio
