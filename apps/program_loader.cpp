#include "apps/program_loader.h"

#include <algorithm>
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

// Errors with no place in the text come from the compile options, here --system and
// --define: a bad command line rather than a bad program.
bool onlyOptionErrors(const DiagnosticSink& sink) {
  return std::all_of(sink.diagnostics().begin(), sink.diagnostics().end(),
                     [](const Diagnostic& d) { return d.severity != Severity::Error || !d.span.valid(); });
}

// A view file holds a few settings: no more than this is read of one.
constexpr uint64_t kMaxViewBytes = uint64_t{1} << 20;

// Checking a program takes about 100 bytes of memory a byte of text (a 5 MB axiom takes
// 520 MB), converting one of another tool less (a 10 MB line of a .l took 87 bytes a
// byte): a text that could not be checked within the memory limit is refused before it
// is converted or checked.
constexpr uint64_t kCheckBytesPerSourceByte = 128;

// Prints why `result` has no text, and keeps it.
ProgramText failed(ProgramText result, int exitCode, std::string error) {
  std::cerr << "ontogen: error: " << error << "\n";
  result.exitCode = exitCode;
  result.error = std::move(error);
  return result;
}

// Whether checking `bytes` of text (`what`: "the N bytes of 'PATH'") fits the memory limit.
std::optional<std::string> checkingPastMemoryLimit(const std::string& what, uint64_t bytes, const WorldLimits& limits) {
  try {
    checkOutsideMemory("checking " + what, bytes * kCheckBytesPerSourceByte, 0, limits);
  } catch (const LimitError& limit) {
    return limit.what();
  }
  return std::nullopt;
}

std::optional<std::string> pastMemoryLimit(const std::string& path, uint64_t bytes, const WorldLimits& limits) {
  return checkingPastMemoryLimit("the " + std::to_string(bytes) + " bytes of '" + path + "'", bytes, limits);
}

// The most text that checking can take within the memory limit.
uint64_t checkableBytes(const WorldLimits& limits) {
  return limits.maxMemoryBytes / kCheckBytesPerSourceByte;
}

}  // namespace

ProgramText readProgramText(const std::string& path, uint64_t maxBytes, const WorldLimits& limits) {
  ProgramText result;
  result.name = path;
  SourceText read = readSourceFile(path, maxBytes);
  if (!read.text) return failed(std::move(result), kExitUsage, "cannot read '" + path + "': " + read.error);
  std::optional<std::string>& text = read.text;
  const std::optional<convert::Dialect> dialect = convert::dialectOfPath(path);
  if (!dialect) {
    if (auto past = pastMemoryLimit(path, text->size(), limits)) return failed(std::move(result), kExitModelError, *past);
    result.text = std::move(text);
    return result;
  }
  // cpfg keeps the turn angle in the view file beside the L-system, named alike. It is
  // read as a program is, a regular file up to a limit: a FIFO or a device named .v
  // must neither block nor fill memory.
  std::string view;
  if (*dialect == convert::Dialect::Cpfg) {
    const std::filesystem::path viewPath = std::filesystem::path(path).replace_extension(".v");
    std::error_code missing;
    if (std::filesystem::exists(std::filesystem::symlink_status(viewPath, missing))) {
      // The view file counts with the file toward the source limit.
      SourceText viewText = readSourceFile(viewPath, std::min(kMaxViewBytes, maxBytes - text->size()));
      if (!viewText.text)
        return failed(std::move(result), kExitUsage,
                      "cannot read the view file '" + viewPath.string() + "': " + viewText.error);
      view = std::move(*viewText.text);
    }
  }
  // Converting takes memory as checking does: a file that could not be checked within the
  // limit is refused before it is converted (a 10 MB line took 36 s and 866 MB first).
  if (auto past = pastMemoryLimit(path, text->size() + view.size(), limits))
    return failed(std::move(result), kExitModelError, *past);
  auto source = std::make_shared<const SourceFile>(path, std::move(*text));
  DiagnosticSink sink;
  // The converter stops as soon as its text passes what could be checked: a small file
  // can expand far past memory (C blocks whose assignments double a value).
  const uint64_t checkable = checkableBytes(limits);
  convert::ConvertResult converted = convert::convertFile(*source, *dialect, view, sink, std::min(maxBytes, checkable));
  if (converted.pastLimit && checkable < maxBytes) {
    // The memory limit stopped it, named as it is for a .cell of that size.
    for (const Diagnostic& diagnostic : sink.diagnostics())
      if (diagnostic.severity != Severity::Error) std::cerr << formatDiagnostic(diagnostic);
    const std::string what =
        "the text converted from '" + path + "' (more than " + std::to_string(checkable) + " bytes)";
    // One byte more than `checkable` is past the limit by its definition.
    return failed(std::move(result), kExitModelError, *checkingPastMemoryLimit(what, checkable + 1, limits));
  }
  std::cerr << formatDiagnostics(sink);
  if (!converted.program) {
    std::cerr << "ontogen: " << path << " cannot be converted from " << convert::dialectName(*dialect) << "\n";
    result.exitCode = converted.untranslatable ? kExitUntranslatable : kExitProgramError;
    result.error = "it cannot be converted from " + std::string(convert::dialectName(*dialect));
    return result;
  }
  if (auto past = pastMemoryLimit(path + " (converted)", converted.program->size(), limits))
    return failed(std::move(result), kExitModelError, *past);
  result.text = std::move(converted.program);
  result.name = path + " (converted)";
  result.converted = true;
  result.original = std::move(source);
  result.lineOrigins = std::move(converted.lineOrigins);
  return result;
}

studio::StudioReader studioReader(const WorldLimits& limits) {
  return [limits](const std::string& path, uint64_t maxBytes) {
    ProgramText read = readProgramText(path, maxBytes, limits);  // says why on stderr too
    return studio::StudioSource{std::move(read.text), read.name, std::move(read.error), std::move(read.original),
                                std::move(read.lineOrigins)};
  };
}

Diagnostic inOriginal(const Diagnostic& diagnostic, const ProgramText& text) {
  if (!text.converted || !text.original || !diagnostic.span.valid() || diagnostic.span.file->name() != text.name)
    return diagnostic;
  return convert::mapToOriginal(diagnostic, *text.original, text.lineOrigins);
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
