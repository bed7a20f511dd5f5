#include "apps/program_loader.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string_view>

#include "apps/commands.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"
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
  DefineOverride define{text.substr(0, equals), 0};
  std::string_view value = std::string_view(text).substr(equals + 1);
  // from_chars takes no '+'; "+5" is as clear as "5".
  std::string_view digits = value.starts_with('+') ? value.substr(1) : value;
  auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), define.value);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() || !std::isfinite(define.value)) {
    std::cerr << "ontogen: error: --define " << text << ": '" << value
              << "' is not a number (VALUE is a number such as 100, -2.5 or 1e-3)\n";
    return std::nullopt;
  }
  return define;
}

// Errors with no place in the text come from the compile options, here --system and
// --define: a bad command line rather than a bad program.
bool onlyOptionErrors(const DiagnosticSink& sink) {
  return std::all_of(sink.diagnostics().begin(), sink.diagnostics().end(),
                     [](const Diagnostic& d) { return d.severity != Severity::Error || !d.span.valid(); });
}

std::optional<std::string> readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

ProgramText readProgramText(const std::string& path) {
  ProgramText result;
  result.name = path;
  std::optional<std::string> text = readFile(path);
  if (!text) {
    std::cerr << "ontogen: error: cannot read '" << path << "': " << std::strerror(errno) << "\n";
    result.exitCode = kExitProgramError;
    return result;
  }
  const std::optional<convert::Dialect> dialect = convert::dialectOfPath(path);
  if (!dialect) {
    result.text = std::move(text);
    return result;
  }
  // cpfg keeps the turn angle in the view file beside the L-system, named alike.
  std::string view;
  if (*dialect == convert::Dialect::Cpfg)
    view = readFile(std::filesystem::path(path).replace_extension(".v").string()).value_or("");
  auto source = std::make_shared<const SourceFile>(path, std::move(*text));
  DiagnosticSink sink;
  convert::ConvertResult converted = convert::convertFile(*source, *dialect, view, sink);
  std::cerr << formatDiagnostics(sink);
  if (!converted.program) {
    std::cerr << "ontogen: " << path << " cannot be converted from " << convert::dialectName(*dialect) << "\n";
    result.exitCode = converted.untranslatable ? kExitUntranslatable : kExitProgramError;
    return result;
  }
  result.text = std::move(converted.program);
  result.name = path + " (converted)";
  result.converted = true;
  return result;
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
  ProgramText text = readProgramText(path);
  if (!text.text) {
    loaded.exitCode = text.exitCode;
    return loaded;
  }
  DiagnosticSink sink;
  options.commandSets = commandSets();
  options.rootSystem = common.system;
  std::unique_ptr<Program> program = compileSource(text.name, std::move(*text.text), sink, options);
  std::cerr << formatDiagnostics(sink);
  if (!program) {
    if (onlyOptionErrors(sink)) {
      loaded.exitCode = kExitUsage;
      return loaded;
    }
    int errors = sink.errorCount();
    std::cerr << errors << " error" << (errors == 1 ? "" : "s") << " in " << path << "\n";
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
