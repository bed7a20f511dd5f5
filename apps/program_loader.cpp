#include "apps/program_loader.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <cerrno>
#include <cstring>

#include "apps/commands.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"

namespace ontogen::app {

std::optional<LoadedProgram> loadProgram(const std::string& path, const std::string& rootSystem) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::cerr << "ontogen: error: cannot read '" << path << "': " << std::strerror(errno) << "\n";
    return std::nullopt;
  }
  std::ostringstream text;
  text << in.rdbuf();
  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  options.rootSystem = rootSystem;
  std::unique_ptr<Program> program = compileSource(path, text.str(), sink, options);
  std::cerr << formatDiagnostics(sink);
  if (!program) {
    int errors = sink.errorCount();
    std::cerr << errors << " error" << (errors == 1 ? "" : "s") << " in " << path << "\n";
    return std::nullopt;
  }
  return LoadedProgram{std::move(program), std::filesystem::path(path).stem().string()};
}

int developReporting(const std::function<void()>& develop) {
  try {
    develop();
  } catch (const LimitError& error) {
    std::cerr << "ontogen: error: " << error.what() << "\n";
    return kExitModelError;
  } catch (const ModelError& error) {
    std::cerr << error.what();
    return kExitModelError;
  }
  return kExitOk;
}

}  // namespace ontogen::app
