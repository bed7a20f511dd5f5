#include "lang/convert/convert.h"

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

ConvertResult convertFile(const SourceFile& file, Dialect dialect, std::string_view view, DiagnosticSink& sink) {
  ConvertResult result;
  try {
    const LSystemFile read =
        dialect == Dialect::Cpfg ? readCpfg(file.text(), file.name(), view) : readLPy(file.text(), file.name());
    result.program = writeCellProgram(read, std::filesystem::path(file.name()).filename().string());
  } catch (const ConvertError& error) {
    sink.error(SourceSpan{&file, error.begin, error.end}, error.message);
    result.untranslatable = error.untranslatable;
  }
  return result;
}

}  // namespace ontogen::convert
