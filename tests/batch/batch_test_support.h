#pragma once
// What the batch library's tests share: the chain they sweep and evolve, a folder of
// their own for each test, a file read whole.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace ontogen::test {

// A chain of 3 segments, LEN (1 + S + S^2) tall, the height growing with LEN and S; A
// counts the apices (always 1).
inline const std::string kChain =
    "lsystem chain {\n"
    "  #define LEN 1\n"
    "  #define S 0.5\n"
    "  #until 3\n"
    "  axiom A(1)\n"
    "  A(s) -> F(LEN * s) A(s * S)\n"
    "}\n";

// An empty folder for one test, under the build's batch_test/.
inline std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(ONTOGEN_BINARY_DIR) / "batch_test" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string readAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace ontogen::test
