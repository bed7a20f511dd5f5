#include "lang/convert/convert.h"

#include <algorithm>
#include <filesystem>

#include "lang/convert/cpfg_reader.h"
#include "lang/convert/foreign_syntax.h"
#include "lang/convert/lpy_reader.h"

namespace ontogen::convert {

std::optional<Dialect> dialectOfPath(std::string_view path) {
  const std::string extension = std::filesystem::path(path).extension().string();
  if (extension == ".l") return Dialect::Cpfg;
  if (extension == ".lpy") return Dialect::LPy;
  return std::nullopt;
}

ConvertResult convertFile(const SourceFile& file, Dialect dialect, std::optional<std::string_view> view,
                          DiagnosticSink& sink, uint64_t maxBytes, const SideFileReader& readSideFile) {
  ConvertResult result;
  try {
    LSystemFile read = dialect == Dialect::Cpfg ? readCpfg(file.text(), file.name(), view, readSideFile, maxBytes)
                                                : readLPy(file.text(), file.name(), maxBytes);
    // In the file's order: the readers find some (the hooks') before others above them.
    std::stable_sort(read.warnings.begin(), read.warnings.end(),
                     [](const ConvertWarning& a, const ConvertWarning& b) { return a.at.begin < b.at.begin; });
    for (const ConvertWarning& warning : read.warnings)
      sink.warning(SourceSpan{&file, warning.at.begin, warning.at.end}, warning.message);
    CellProgram program = writeCellProgram(read, std::filesystem::path(file.name()).filename().string());
    if (program.text.size() > maxBytes) {
      sink.error(SourceSpan{},
                 "the converted text (" + describeBytes(program.text.size()) + ") is larger than the limit of " +
                     describeBytes(maxBytes) + " of source text");
      result.pastLimit = true;
      return result;
    }
    result.program = std::move(program.text);
    result.lineOrigins = std::move(program.lineOrigins);
  } catch (const ConvertError& error) {
    sink.error(SourceSpan{&file, error.begin, error.end}, error.message);
    result.untranslatable = error.untranslatable;
  } catch (const ConvertedTextTooLarge& tooLarge) {
    sink.error(SourceSpan{}, "the converted text is larger than the limit of " + describeBytes(tooLarge.limit) +
                                 " of source text (the converter stopped where it passed it)");
    result.pastLimit = true;
  }
  return result;
}

Diagnostic mapToOriginal(const Diagnostic& diagnostic, const SourceFile& original,
                         const std::vector<SourceRange>& lineOrigins) {
  if (!diagnostic.span.valid()) return diagnostic;
  const int line = diagnostic.span.line();
  if (line < 1 || static_cast<size_t>(line) > lineOrigins.size()) return diagnostic;
  const SourceRange origin = lineOrigins[static_cast<size_t>(line) - 1];
  if (!origin.known()) return diagnostic;
  const std::string_view full = diagnostic.span.file->lineText(line);
  const size_t indent = std::min(full.find_first_not_of(' '), full.size());
  const int column = diagnostic.span.column() - static_cast<int>(indent);
  // The converted line quoted around the column the compiler names, at most 80 bytes.
  constexpr size_t kQuoted = 80;
  std::string_view quoted = full.substr(indent);
  std::string before, after;
  if (quoted.size() > kQuoted) {
    const size_t from = column > static_cast<int>(kQuoted / 2) ? static_cast<size_t>(column) - kQuoted / 2 : 0;
    if (from > 0) before = "…";
    if (from + kQuoted < quoted.size()) after = "…";
    quoted = quoted.substr(std::min(from, quoted.size()), kQuoted);
  }
  Diagnostic mapped = diagnostic;
  mapped.span = SourceSpan{&original, origin.begin, origin.end};
  mapped.message += " (in the converted line '" + before + std::string(quoted) + after + "', column " +
                    std::to_string(column) + ")";
  return mapped;
}

}  // namespace ontogen::convert
