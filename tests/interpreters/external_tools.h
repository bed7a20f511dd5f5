#pragma once
// Running the independent programs the output tests check files with (assimp, the glTF
// validator, ffprobe) and reading their reports.

#include <sys/wait.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <utility>

namespace ontogen::testing_support {

/// Runs a shell command and returns its exit status and standard output.
inline std::pair<int, std::string> runCommand(const std::string& command) {
  std::string output;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return {-1, output};
  char buffer[4096];
  std::size_t read = 0;
  while ((read = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, read);
  int status = ::pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

/// The number after "\nfield:" in assimp's report, or -1.
inline long reported(const std::string& output, const std::string& field) {
  std::size_t at = output.find("\n" + field + ":");
  if (at == std::string::npos) return -1;
  std::istringstream in(output.substr(at + field.size() + 2));
  long value = -1;
  in >> value;
  return value;
}

}  // namespace ontogen::testing_support
