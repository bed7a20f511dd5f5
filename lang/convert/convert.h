#pragma once
// `ontogen convert`: another L-system tool's file as a cell-language program. The tool
// is known by the file's extension; its reader (cpfg_reader.h, lpy_reader.h) fills an
// LSystemFile (lsystem_file.h), which is written as one lsystem block. A construct the
// converter cannot translate (Python or C code, a module with no cell-language
// spelling) is an error at its place in the file.

#include <optional>
#include <string>
#include <string_view>

#include "lang/convert/lsystem_file.h"
#include "lang/diagnostics.h"
#include "lang/source.h"

namespace ontogen::convert {

/// cpfg for `.l`, L-Py for `.lpy`; nothing for other files (the cell language's own).
std::optional<Dialect> dialectOfPath(std::string_view path);

struct ConvertResult {
  std::optional<std::string> program;  ///< the cell-language text; empty on error
  /// The error was a construct ontogen cannot express (code of the other tool), rather
  /// than text the reader could not make out.
  bool untranslatable = false;
};

/// Converts `file`, written for `dialect`; `view` is cpfg's view file (.v), where cpfg
/// keeps the turn angle, or empty. The error, if any, goes to `sink` with its place.
ConvertResult convertFile(const SourceFile& file, Dialect dialect, std::string_view view, DiagnosticSink& sink);

}  // namespace ontogen::convert
