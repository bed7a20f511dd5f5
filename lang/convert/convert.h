#pragma once
// `ontogen convert`: another L-system tool's file as a cell-language program. The tool
// is known by the file's extension; its reader (cpfg_reader.h, lpy_reader.h) fills an
// LSystemFile (lsystem_file.h), which is written as one lsystem block. A construct the
// converter cannot translate (Python or C code, a module with no cell-language
// spelling) is an error at its place in the file.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lang/convert/lsystem_file.h"
#include "model/diagnostics.h"
#include "model/source.h"
#include "lang/source_reader.h"

namespace ontogen::convert {

/// cpfg for `.l`, L-Py for `.lpy`; nothing for other files (the cell language's own).
std::optional<Dialect> dialectOfPath(std::string_view path);

struct ConvertResult {
  std::optional<std::string> program;  ///< the cell-language text; empty on error
  /// For each line of `program` (index: line − 1), the bytes of the file it was written
  /// from: errors in the converted text are shown at the file's own line.
  std::vector<SourceRange> lineOrigins;
  /// The error was a construct ontogen cannot express (code of the other tool), rather
  /// than text the reader could not make out.
  bool untranslatable = false;
  /// The text grew past the limit `maxBytes`: the converter stopped there.
  bool pastLimit = false;
};

/// Converts `file`, written for `dialect`; `view` is the text of cpfg's view file (.v),
/// where cpfg keeps the turn angle and names its functions (read by `readSideFile`), or
/// nothing when there is none (its turns then warn: see readCpfg). The
/// error, if any, and the warnings go to `sink` with their places. A program longer than
/// `maxBytes` is an error: the source limit holds for the converted text too, and the
/// converter stops as soon as its text passes it (an expansion of a small file can be far
/// larger than memory).
ConvertResult convertFile(const SourceFile& file, Dialect dialect, std::optional<std::string_view> view,
                          DiagnosticSink& sink,
                          uint64_t maxBytes = kDefaultMaxSourceBytes, const SideFileReader& readSideFile = {});

/// A diagnostic of the compiler in converted text, at the place of the file it was
/// converted from (`original`), with the converted line quoted; one at a line that came
/// from no place of the file is returned as it is.
Diagnostic mapToOriginal(const Diagnostic& diagnostic, const SourceFile& original,
                         const std::vector<SourceRange>& lineOrigins);

}  // namespace ontogen::convert
