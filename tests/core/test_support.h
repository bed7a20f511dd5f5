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

inline std::string readModel(const std::string& name) {
  std::ifstream in(std::string(ONTOGEN_SOURCE_DIR) + "/models/" + name, std::ios::binary);
  EXPECT_TRUE(in.good()) << name;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline std::shared_ptr<const Program> compileModel(const std::string& name) {
  return compileOrFail(readModel(name), "models/" + name);
}

}  // namespace ontogen::testing_support
