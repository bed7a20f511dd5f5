#pragma once
// Running the ontogen executable from a command-line test (through ontogen_process.h),
// and the files such a test reads and writes (tests/test_files.h).

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/apps/ontogen_process.h"
#include "tests/test_files.h"

namespace ontogen::test {

namespace fs = std::filesystem;

/// How a run ended: its exit code (-1: killed by a signal, or could not start), stdout
/// and stderr.
using CliResult = OntogenRun;

/// Runs `ontogen ARGS` through the shell (so ARGS may quote and redirect), within
/// `timeoutSeconds` (exit 124 past it), by the command-line tests' one spawner.
inline CliResult runOntogen(const std::string& args, int timeoutSeconds = 60) {
  return runOntogenShell(args, "timeout " + std::to_string(timeoutSeconds) + " ");
}

inline std::string modelPath(const std::string& name) {
  return std::string(ONTOGEN_SOURCE_DIR) + "/models/" + name;
}

}  // namespace ontogen::test
