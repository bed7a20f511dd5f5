#pragma once
// The files a test reads and writes: an empty folder of its own under the build tree,
// a file written or read whole.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace ontogen::test {

/// An empty folder of its own for a test, `group/name` under the build tree (a group per
/// test program, so that two programs run side by side never share one).
inline std::filesystem::path scratchDir(const std::string& name, const std::string& group = "cli_test") {
  std::filesystem::path dir = std::filesystem::path(ONTOGEN_BINARY_DIR) / group / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string readWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::filesystem::path writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

}  // namespace ontogen::test
