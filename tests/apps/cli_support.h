#pragma once
// Running the ontogen executable from a test: its exit code, stdout and stderr.

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace ontogen::test {

namespace fs = std::filesystem;

struct CliResult {
  int exitCode = -1;  ///< -1: killed by a signal (an abort), or could not start
  std::string out;
  std::string err;
};

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

/// Runs `ontogen ARGS` through the shell (so ARGS may quote), within `timeoutSeconds`.
inline CliResult runOntogen(const std::string& args, int timeoutSeconds = 60) {
  // One file per process: ctest runs tests in parallel processes.
  fs::path errFile = fs::path(ONTOGEN_BINARY_DIR) / "cli_test" / ("stderr_" + std::to_string(getpid()) + ".txt");
  fs::create_directories(errFile.parent_path());
  std::string command = "timeout " + std::to_string(timeoutSeconds) + " " + std::string(ONTOGEN_EXECUTABLE) + " " +
                        args + " 2>" + errFile.string();
  CliResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.out.append(buffer.data(), n);
  int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.err = readWholeFile(errFile);
  return result;
}

inline std::string modelPath(const std::string& name) {
  return std::string(ONTOGEN_SOURCE_DIR) + "/models/" + name;
}

inline fs::path writeFile(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

}  // namespace ontogen::test
