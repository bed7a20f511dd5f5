#pragma once
// Helpers shared by the core tests: compiling a program text or a model file.

#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "interpreters/set_registry.h"
#include "lang/compiler.h"

namespace ontogen::testing_support {

inline std::shared_ptr<const Program> compileOrFail(const std::string& text, const std::string& name = "test.cell") {
  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  std::shared_ptr<const Program> program = compileSource(name, text, sink, options);
  EXPECT_NE(program, nullptr) << formatDiagnostics(sink);
  return program;
}

// The benchmarks' Thue-Morse and parametric L-systems (bench/derivation_bench.cpp):
// |w_n| = 2^n for both.
inline constexpr const char* kThueMorse = R"(lsystem thueMorse {
  axiom a
  a -> a b
  b -> b a
})";

inline constexpr const char* kParametric = R"(lsystem parametric {
  axiom A(1)
  A(x) -> A(x + 1) B(x * 0.5)
  B(y) -> B(y + 1) B(y * 0.5)
})";

inline std::string readModel(const std::string& name) {
  std::ifstream in(std::filesystem::path(ONTOGEN_SOURCE_DIR) / "models" / name, std::ios::binary);
  EXPECT_TRUE(in.good()) << name;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::shared_ptr<const Program> compileModel(const std::string& name) {
  return compileOrFail(readModel(name), "models/" + name);
}

}  // namespace ontogen::testing_support
