#pragma once
// What the batch library's tests share: the chain they sweep and evolve, a folder of
// their own for each test, a file read whole (tests/test_files.h).

#include <filesystem>
#include <string>

#include "tests/test_files.h"

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
inline std::filesystem::path scratch(const std::string& name) { return scratchDir(name, "batch_test"); }

}  // namespace ontogen::test
