#include "lang/program_file.h"

#include <algorithm>
#include <filesystem>

#include "lang/convert/convert.h"
#include "lang/convert/cpfg_view_file.h"

namespace ontogen {

namespace {

// A view file holds a few settings: no more than this is read of one.
constexpr uint64_t kMaxViewBytes = uint64_t{1} << 20;

ProgramFileText failed(ProgramFileText result, ProgramFileFailure failure, std::string error) {
  result.failure = failure;
  result.error = std::move(error);
  return result;
}

// Why checking `bytes` of text read from `path` would not fit the memory limit.
std::optional<std::string> pastMemoryLimit(const ProgramFileDef& def, const std::string& path, uint64_t bytes) {
  if (!def.memory) return std::nullopt;
  return def.memory("checking the " + std::to_string(bytes) + " bytes of '" + path + "'",
                    bytes * kCheckBytesPerSourceByte);
}

bool pathExists(const std::filesystem::path& path) {
  std::error_code missing;
  return std::filesystem::exists(std::filesystem::symlink_status(path, missing));
}

// The view file cpfg would read with the L-system at `path`, if there is one.
std::optional<std::filesystem::path> viewPathOf(const std::string& path) {
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (pathExists(folder / "specifications")) {
    SourceText specifications = readSourceFile(folder / "specifications", kMaxViewBytes);
    if (specifications.text)
      if (auto name = convert::viewFileInSpecifications(*specifications.text,
                                                        std::filesystem::path(path).filename().string()))
        if (pathExists(folder / *name)) return folder / *name;
  }
  std::filesystem::path sameName = std::filesystem::path(path).replace_extension(".v");
  if (pathExists(sameName)) return sameName;
  return std::nullopt;
}

}  // namespace

ProgramFileText readProgramFile(const std::string& path, const ProgramFileDef& def, DiagnosticSink& sink) {
  ProgramFileText result;
  result.name = path;
  const uint64_t maxBytes = def.maxSourceBytes;
  SourceText read = readSourceFile(path, maxBytes);
  if (!read.text)
    return failed(std::move(result), ProgramFileFailure::Unreadable, "cannot read '" + path + "': " + read.error);
  std::optional<std::string>& text = read.text;
  const std::optional<convert::Dialect> dialect = convert::dialectOfPath(path);
  if (!dialect) {
    if (auto past = pastMemoryLimit(def, path, text->size()))
      return failed(std::move(result), ProgramFileFailure::PastMemoryLimit, *past);
    result.text = std::move(text);
    return result;
  }
  // cpfg keeps the turn angle in its view file, the one its command in the folder's
  // `specifications` names, else the one named as the L-system (cpfg_view_file.h). It is
  // read as a program is, a regular file up to a limit: a FIFO or a device named .v must
  // neither block nor fill memory.
  std::optional<std::string> view;
  if (*dialect == convert::Dialect::Cpfg) {
    if (auto viewPath = viewPathOf(path)) {
      // The view file counts with the file toward the source limit.
      SourceText viewText = readSourceFile(*viewPath, std::min(kMaxViewBytes, maxBytes - text->size()));
      if (!viewText.text)
        return failed(std::move(result), ProgramFileFailure::Unreadable,
                      "cannot read the view file '" + viewPath->string() + "': " + viewText.error);
      view = std::move(*viewText.text);
    }
  }
  // Converting takes memory as checking does: a file that could not be checked within the
  // limit is refused before it is converted (a 10 MB line took 36 s and 866 MB first).
  if (auto past = pastMemoryLimit(def, path, text->size() + (view ? view->size() : 0)))
    return failed(std::move(result), ProgramFileFailure::PastMemoryLimit, *past);
  auto source = std::make_shared<const SourceFile>(path, std::move(*text));
  result.original = source;  // the converter's diagnostics point into it, also when it fails
  // The function files the view file names (cpfg's func), beside the file, read as the
  // view file is.
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  auto readSideFile = [&folder](const std::string& name) -> std::optional<std::string> {
    SourceText side = readSourceFile(folder / name, kMaxViewBytes);
    return side.text;
  };
  const uint64_t checkable = def.checkableBytes;
  DiagnosticSink converterSink;
  convert::ConvertResult converted =
      convert::convertFile(*source, *dialect, view, converterSink, std::min(maxBytes, checkable), readSideFile);
  if (converted.pastLimit && checkable < maxBytes && def.memory) {
    // The memory limit stopped it: named as it is for a .cell of that size, in place of
    // the converter's error about the source limit; its warnings are kept.
    for (const Diagnostic& diagnostic : converterSink.diagnostics())
      if (diagnostic.severity != Severity::Error) sink.report(diagnostic.severity, diagnostic.span, diagnostic.message);
    const std::string what =
        "checking the text converted from '" + path + "' (more than " + std::to_string(checkable) + " bytes)";
    // One byte more than `checkable` is past the limit by its definition.
    if (auto past = def.memory(what, (checkable + 1) * kCheckBytesPerSourceByte))
      return failed(std::move(result), ProgramFileFailure::PastMemoryLimit, *past);
  }
  for (const Diagnostic& diagnostic : converterSink.diagnostics())
    sink.report(diagnostic.severity, diagnostic.span, diagnostic.message);
  if (!converted.program)
    return failed(std::move(result),
                  converted.untranslatable ? ProgramFileFailure::Untranslatable : ProgramFileFailure::NotConverted,
                  "it cannot be converted from " + std::string(convert::dialectName(*dialect)));
  if (auto past = pastMemoryLimit(def, path + " (converted)", converted.program->size()))
    return failed(std::move(result), ProgramFileFailure::PastMemoryLimit, *past);
  result.text = std::move(converted.program);
  result.name = path + " (converted)";
  result.converted = true;
  result.lineOrigins = std::move(converted.lineOrigins);
  return result;
}

Diagnostic inOriginal(const Diagnostic& diagnostic, const ProgramFileText& text) {
  if (!text.converted || !text.original || !diagnostic.span.valid() || diagnostic.span.file->name() != text.name)
    return diagnostic;
  return convert::mapToOriginal(diagnostic, *text.original, text.lineOrigins);
}

bool onlyOptionErrors(const DiagnosticSink& sink) {
  return std::all_of(sink.diagnostics().begin(), sink.diagnostics().end(),
                     [](const Diagnostic& d) { return d.severity != Severity::Error || !d.span.valid(); });
}

}  // namespace ontogen
