#pragma once
// Reading and compiling a program for the commands of the ontogen executable; the only
// place (with the commands) that writes to the terminal.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/limits.h"
#include "model/program.h"
#include "lang/program_file.h"
#include "studio/program_options.h"

namespace ontogen::app {

/// Exit codes of the ontogen executable (documented in README.md).
enum ExitCode {
  kExitOk = 0,
  kExitProgramError = 1,  ///< the program has errors (diagnostics printed)
  kExitUsage = 2,         ///< bad command line
  kExitModelError = 3,    ///< the model failed or passed a limit while it ran
  kExitOutputError = 4,   ///< an output could not be written
  kExitMidiError = 5,     ///< live MIDI: no MIDI system runs, or no such port
  kExitUntranslatable = 6,  ///< convert: the cpfg or L-Py file holds code ontogen cannot translate
  kExitInternalError = 70, ///< a fault of ontogen itself (an exception nothing else caught; sysexits' EX_SOFTWARE)
  kExitInterrupted = 130, ///< stopped by Ctrl-C (SIGINT) during live playback, notes stopped
};

struct LoadedProgram {
  std::shared_ptr<const Program> program;  ///< null when the program could not be loaded
  std::string stem;  ///< file name without directory and extension: names outputs
  /// Why loading failed: kExitProgramError for errors in the text, kExitUsage for a
  /// --system or --define the program does not have, a malformed --define, or a FILE
  /// that is no regular file or passes the source size limit.
  int exitCode = kExitOk;
};

struct CommonOptions;

/// A program file's text (lang/program_file.h) with the exit code of why there is none:
/// kExitUsage (not a readable file, past the source size limit), kExitModelError (past
/// the memory limit), kExitProgramError or kExitUntranslatable (not converted).
struct ProgramText : ProgramFileText {
  int exitCode = kExitOk;
};

/// Reads the program file at `path`, converting another tool's, held to the source limit
/// `maxBytes` and the memory limit of `limits`; prints the converter's diagnostics and
/// why there is no text to stderr.
ProgramText readProgramText(const std::string& path, uint64_t maxBytes = kDefaultMaxSourceBytes,
                            const WorldLimits& limits = WorldLimits{});

/// The studio's reader of its program file (studio/program_options.h): readProgramText
/// held to the limits of each read, the studio's interactive ones.
studio::StudioReader studioReader();

/// Reads and compiles the program file of `options` with its --system and --define. On
/// failure prints the diagnostics (or the I/O error) to stderr and returns no program.
LoadedProgram loadProgram(const CommonOptions& options);

}  // namespace ontogen::app
