#pragma once
// Running the ontogen executable from a command-line test (through ontogen_process.h),
// and the files such a test reads and writes.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tests/apps/ontogen_process.h"

namespace ontogen::test {

namespace fs = std::filesystem;

/// How a run ended: its exit code (-1: killed by a signal, or could not start), stdout
/// and stderr.
using CliResult = OntogenRun;

/// An empty folder of its own for a test, under the build tree.
inline fs::path scratchDir(const std::string& name) {
  fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "cli_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline std::string readWholeFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Runs `ontogen ARGS` through the shell (so ARGS may quote and redirect), within
/// `timeoutSeconds` (exit 124 past it), by the command-line tests' one spawner.
inline CliResult runOntogen(const std::string& args, int timeoutSeconds = 60) {
  return runOntogenShell(args, "timeout " + std::to_string(timeoutSeconds) + " ");
}

inline std::string modelPath(const std::string& name) {
  return std::string(ONTOGEN_SOURCE_DIR) + "/models/" + name;
}

inline fs::path writeFile(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

}  // namespace ontogen::test
