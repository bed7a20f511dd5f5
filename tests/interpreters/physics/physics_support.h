#pragma once
// Growing a program and solving its rods through the physics set, for the physics tests.

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <optional>
#include <string>

#include "core/world.h"
#include "interpreters/interpret.h"
#include "interpreters/physics/physics_set.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"
#include "tests/core/test_support.h"

namespace ontogen::testing_support {

inline std::shared_ptr<const Program> compileWithDefines(const std::string& text, const std::string& name,
                                                         const std::map<std::string, double>& defines) {
  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  for (const auto& [key, value] : defines) options.defines.push_back({key, value});
  std::shared_ptr<const Program> program = compileSource(name, text, sink, options);
  EXPECT_NE(program, nullptr) << formatDiagnostics(sink);
  return program;
}

/// A program grown to `at` (else its #until) and interpreted by a physics set of its own.
struct Solved {
  std::shared_ptr<const Program> program;
  std::unique_ptr<PhysicsSet> set;
  const PhysicsFrame& frame() const { return set->frame(); }
};

inline Solved solveProgram(std::shared_ptr<const Program> program, std::optional<double> at = {}) {
  Solved solved;
  solved.program = program;
  solved.set = std::make_unique<PhysicsSet>();
  if (!program) return solved;
  World world(program);
  world.advanceTo(at.value_or(program->until), program->dt);
  solved.set->beginFrame(FrameTarget{".", "test", 0, 1, world.time()});
  interpretWord(world, *solved.set);
  return solved;
}

inline Solved solveText(const std::string& text, std::optional<double> at = {}) {
  return solveProgram(compileOrFail(text), at);
}

inline Solved solveModel(const std::string& model, const std::map<std::string, double>& defines = {},
                         std::optional<double> at = {}) {
  return solveProgram(compileWithDefines(readModel(model), "models/" + model, defines), at);
}

}  // namespace ontogen::testing_support
