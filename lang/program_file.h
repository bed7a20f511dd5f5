#pragma once
// Reading a program file: a cell-language file as it is, a cpfg (.l, with its view file
// .v) or L-Py (.lpy) file converted (lang/convert/convert.h). The file is held to the
// source size limit and, before it is converted or checked, to what checking it would
// take of the memory limit, which the caller supplies as a check; so is the text a
// conversion writes. Nothing here prints: the converter's diagnostics go to the sink,
// and why there is no text comes back in the result.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lang/convert/lsystem_file.h"
#include "model/diagnostics.h"
#include "model/source.h"
#include "lang/source_reader.h"

namespace ontogen {

/// Checking a program takes about 100 bytes of memory a byte of text (a 5 MB axiom took
/// 520 MB), converting one of another tool less (a 10 MB line of a .l took 87 bytes a
/// byte): the memory asked of the check for a text of n bytes is n times this.
inline constexpr uint64_t kCheckBytesPerSourceByte = 128;

/// Why `bytes` of memory for `what` ("checking the 120 bytes of 'tree.l'") would pass
/// the memory limit, or nothing when they fit.
using MemoryCheck = std::function<std::optional<std::string>(const std::string& what, uint64_t bytes)>;

struct ProgramFileDef {
  uint64_t maxSourceBytes = kDefaultMaxSourceBytes;  ///< the file with its view file, bytes
  MemoryCheck memory;                                ///< empty: no memory limit
  /// The most converted text checking can take within the memory limit (the limit over
  /// kCheckBytesPerSourceByte): the converter stops as soon as its text passes it, since
  /// a small file can expand far past memory (C blocks whose assignments double a value).
  uint64_t checkableBytes = UINT64_MAX;
};

/// Why a program file gave no text.
enum class ProgramFileFailure {
  None,
  Unreadable,       ///< not a regular file, past the source limit, or its view file so
  PastMemoryLimit,  ///< checking it (or its conversion) would pass the memory limit
  NotConverted,     ///< the converter could not make out the file (its errors in the sink)
  Untranslatable,   ///< the file holds code of the other tool ontogen cannot express
};

struct ProgramFileText {
  std::optional<std::string> text;  ///< the cell-language text; empty on failure
  std::string name;  ///< for diagnostics: the path, "PATH (converted)" for another tool's file
  bool converted = false;
  ProgramFileFailure failure = ProgramFileFailure::None;
  std::string error;  ///< why there is no text
  /// A file of another tool: the file itself (also when it was not converted: the
  /// converter's diagnostics in the sink point into it, so keep it while they are read),
  /// and for each line of `text` the bytes of it the line was written from
  /// (convert::mapToOriginal shows errors there).
  std::shared_ptr<const SourceFile> original;
  std::vector<convert::SourceRange> lineOrigins;
};

/// Reads the program file at `path`, converting another tool's; the converter's
/// diagnostics (warnings too) go to `sink`.
ProgramFileText readProgramFile(const std::string& path, const ProgramFileDef& def, DiagnosticSink& sink);

/// A diagnostic of the compiler about `text`, at its place in the file it was converted
/// from when it was (convert::mapToOriginal).
Diagnostic inOriginal(const Diagnostic& diagnostic, const ProgramFileText& text);

/// Whether every error in `sink` has no place in the text: errors of the compile options
/// (a --system or --define the program does not have), a bad command line rather than a
/// bad program.
bool onlyOptionErrors(const DiagnosticSink& sink);

}  // namespace ontogen
