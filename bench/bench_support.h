#pragma once
// Helpers shared by the benchmarks: compiling a program text or a model of models/, and
// finding a module's master. Failures come back as messages for state.SkipWithError, so
// a benchmark whose program does not compile reports an error instead of a time.

#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "core/world.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"
#include "lang/program.h"

namespace ontogen::bench {

/// Every benchmark world: seed 1, default limits.
inline const WorldDef kBenchWorld{.seed = 1};

/// A compiled program, or the diagnostics that stopped it.
struct Compiled {
  std::shared_ptr<const Program> program;  ///< null on error
  std::string error;                       ///< the formatted diagnostics when program is null
};

/// Compiles a program text the way `ontogen run` does (interpretation blocks checked).
inline Compiled compileText(const std::string& name, std::string text) {
  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  std::shared_ptr<const Program> program = compileSource(name, std::move(text), sink, options);
  if (!program) return {nullptr, name + " does not compile:\n" + formatDiagnostics(sink)};
  return {std::move(program), {}};
}

/// Compiles models/<name> from the source tree.
inline Compiled compileModel(const std::string& name) {
  const std::string path = std::string(ONTOGEN_SOURCE_DIR) + "/models/" + name;
  std::ifstream in(path, std::ios::binary);
  if (!in) return {nullptr, "cannot read " + path};
  std::ostringstream text;
  text << in.rdbuf();
  return compileText("models/" + name, text.str());
}

/// The master of a module of the root system, by label.
inline std::optional<uint32_t> masterOf(const Program& program, std::string_view label) {
  int index = program.findMaster(label, program.root);
  if (index < 0) return std::nullopt;
  return static_cast<uint32_t>(index);
}

}  // namespace ontogen::bench
