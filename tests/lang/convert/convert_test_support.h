#pragma once
// Converting a text of another tool's notation in a test: the program, or the error's
// line, column and message. A cpfg text without a view file is converted as one whose
// view file could not be found.

#include <optional>
#include <string>
#include <vector>

#include "lang/convert/convert.h"

namespace ontogen::convert::test {

struct Converted {
  std::string program;  ///< empty on error
  int line = 0;
  int column = 0;
  std::string error;
  bool untranslatable = false;
  std::vector<std::string> warnings;  ///< "line:column: message"
};

inline Converted convertText(Dialect dialect, const std::string& name, const std::string& text,
                             const std::optional<std::string>& view = std::nullopt) {
  SourceFile file(name, text);
  DiagnosticSink sink;
  ConvertResult result = convertFile(file, dialect, view, sink);
  Converted converted;
  converted.program = result.program.value_or("");
  converted.untranslatable = result.untranslatable;
  for (const Diagnostic& d : sink.diagnostics()) {
    if (d.severity == Severity::Warning) {
      converted.warnings.push_back(std::to_string(d.span.line()) + ":" + std::to_string(d.span.column()) + ": " +
                                   d.message);
      continue;
    }
    if (!converted.error.empty()) continue;
    converted.line = d.span.line();
    converted.column = d.span.column();
    converted.error = d.message;
  }
  return converted;
}

}  // namespace ontogen::convert::test
