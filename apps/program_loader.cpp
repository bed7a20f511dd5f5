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

}  // namespace

ProgramText readProgramText(const std::string& path, uint64_t maxBytes) {
  ProgramText result;
  result.name = path;
  SourceText read = readSourceFile(path, maxBytes);
  if (!read.text) {
    std::cerr << "ontogen: error: cannot read '" << path << "': " << read.error << "\n";
    result.exitCode = kExitUsage;
    return result;
  }
  std::optional<std::string>& text = read.text;
  const std::optional<convert::Dialect> dialect = convert::dialectOfPath(path);
  if (!dialect) {
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
      SourceText viewText = readSourceFile(viewPath, kMaxViewBytes);
      if (!viewText.text) {
        std::cerr << "ontogen: error: cannot read the view file '" << viewPath.string() << "': " << viewText.error
                  << "\n";
        result.exitCode = kExitUsage;
        return result;
      }
      view = std::move(*viewText.text);
    }
  }
  auto source = std::make_shared<const SourceFile>(path, std::move(*text));
  DiagnosticSink sink;
  convert::ConvertResult converted = convert::convertFile(*source, *dialect, view, sink, maxBytes);
  std::cerr << formatDiagnostics(sink);
  if (!converted.program) {
    std::cerr << "ontogen: " << path << " cannot be converted from " << convert::dialectName(*dialect) << "\n";
    result.exitCode = converted.untranslatable ? kExitUntranslatable : kExitProgramError;
    return result;
  }
  result.text = std::move(converted.program);
  result.name = path + " (converted)";
  result.converted = true;
  result.original = std::move(source);
  result.lineOrigins = std::move(converted.lineOrigins);
  return result;
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
  ProgramText text = readProgramText(path, common.maxSourceBytes);
  if (!text.text) {
    loaded.exitCode = text.exitCode;
    return loaded;
  }
  // Checking a program takes about 100 bytes of memory a byte of text (a 5 MB axiom
  // takes 520 MB): a text that could not be checked within the memory limit is stopped
  // before it is.
  constexpr uint64_t kCheckBytesPerSourceByte = 128;
  try {
    checkOutsideMemory("checking the " + std::to_string(text.text->size()) + " bytes of '" + path + "'",
                       text.text->size() * kCheckBytesPerSourceByte, 0, common.limits);
  } catch (const LimitError& limit) {
    std::cerr << "ontogen: error: " << limit.what() << "\n";
    loaded.exitCode = kExitModelError;
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
