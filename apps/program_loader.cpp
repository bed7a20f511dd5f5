#include "apps/program_loader.h"

#include <filesystem>
#include <iostream>
#include <optional>
#include <string_view>

#include "apps/cli_values.h"
#include "apps/commands.h"
#include "core/limits.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"
#include "lang/source_reader.h"
#include "lang/convert/convert.h"

namespace ontogen::app {

namespace {

// `NAME=VALUE` with VALUE a number as the language writes one, optionally signed
// (`100`, `-2.5`, `1e-3`); prints why not and returns nothing.
std::optional<DefineOverride> parseDefine(const std::string& text) {
  const size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    std::cerr << "ontogen: error: --define takes NAME=VALUE, as in --define WR=100, not '" << text << "'\n";
    return std::nullopt;
  }
  const std::string_view value = std::string_view(text).substr(equals + 1);
  const std::optional<double> number = parseReal(value);
  if (!number) {
    std::cerr << "ontogen: error: --define " << text << ": '" << value
              << "' is not a number (VALUE is a number such as 100, -2.5 or 1e-3)\n";
    return std::nullopt;
  }
  return DefineOverride{text.substr(0, equals), *number};
}

// The memory limit of `limits` as lang/program_file.h asks it.
MemoryCheck memoryCheckOf(const WorldLimits& limits) {
  return [limits](const std::string& what, uint64_t bytes) -> std::optional<std::string> {
    try {
      checkOutsideMemory(what, bytes, 0, limits);
    } catch (const LimitError& limit) {
      return limit.what();
    }
    return std::nullopt;
  };
}

}  // namespace

ProgramText readProgramText(const std::string& path, uint64_t maxBytes, const WorldLimits& limits) {
  DiagnosticSink sink;
  ProgramText result;
  static_cast<ProgramFileText&>(result) = readProgramFile(
      path, ProgramFileDef{maxBytes, memoryCheckOf(limits), limits.maxMemoryBytes / kCheckBytesPerSourceByte}, sink);
  std::cerr << formatDiagnostics(sink);
  switch (result.failure) {
    case ProgramFileFailure::None: return result;
    case ProgramFileFailure::Unreadable: result.exitCode = kExitUsage; break;
    case ProgramFileFailure::PastMemoryLimit: result.exitCode = kExitModelError; break;
    case ProgramFileFailure::NotConverted:
    case ProgramFileFailure::Untranslatable:
      std::cerr << "ontogen: " << path << " cannot be converted from "
                << convert::dialectName(*convert::dialectOfPath(path)) << "\n";
      result.exitCode =
          result.failure == ProgramFileFailure::Untranslatable ? kExitUntranslatable : kExitProgramError;
      return result;
  }
  std::cerr << "ontogen: error: " << result.error << "\n";
  return result;
}

studio::StudioReader studioReader() {
  return [](const std::string& path, uint64_t maxBytes, const WorldLimits& limits) {
    ProgramText read = readProgramText(path, maxBytes, limits);  // says why on stderr too
    std::shared_ptr<const SourceFile> original = read.converted ? std::move(read.original) : nullptr;
    return studio::StudioSource{std::move(read.text), read.name, std::move(read.error), std::move(original),
                                std::move(read.lineOrigins)};
  };
}

LoadedProgram loadProgram(const CommonOptions& common) {
  LoadedProgram loaded;
  CompileOptions options;
  for (const std::string& text : common.defines) {
    std::optional<DefineOverride> define = parseDefine(text);
    if (!define) {
      loaded.exitCode = kExitUsage;
      return loaded;
    }
    options.defines.push_back(std::move(*define));
  }
  const std::string& path = common.file;
  // The FILE argument names no program to read: a bad command line, like a missing file.
  // Held to the source and memory limits as it is read (and converted).
  ProgramText text = readProgramText(path, common.maxSourceBytes, common.limits);
  if (!text.text) {
    loaded.exitCode = text.exitCode;
    return loaded;
  }
  DiagnosticSink sink(common.maxErrors);
  // Each error reaches the terminal as it is found, not all of them at the end.
  sink.streamTo([&text](const Diagnostic& diagnostic) { std::cerr << formatDiagnostic(inOriginal(diagnostic, text)); });
  options.commandSets = commandSets();
  options.rootSystem = common.system;
  options.maxSourceBytes = common.maxSourceBytes;
  std::unique_ptr<Program> program = compileSource(text.name, std::move(*text.text), sink, options);
  if (!program) {
    if (onlyOptionErrors(sink)) {
      loaded.exitCode = kExitUsage;
      return loaded;
    }
    int errors = sink.errorCount();
    std::cerr << errors << " error" << (errors == 1 ? "" : "s") << " in " << path;
    if (sink.limitReached())
      std::cerr << "; stopped at the error limit (--max-errors N changes it, 0 reports every error)";
    std::cerr << "\n";
    loaded.exitCode = kExitProgramError;
    return loaded;
  }
  loaded.program = std::move(program);
  loaded.stem = std::filesystem::path(path).stem().string();
  return loaded;
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
