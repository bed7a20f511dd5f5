#pragma once
// Diagnostics are values handed to a sink the caller supplies; the libraries never
// print. formatDiagnostic renders one the way clang does: location, message, the
// source line and a caret under the span. A sink keeps a bounded number of errors (an
// error limit, as compilers have) and may hand each one on as it arrives, so a file of
// garbage neither floods the terminal nor fills memory.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "model/source.h"

namespace ontogen {

enum class Severity { Error, Warning, Note };

/// "error", "warning" or "note": the word formatDiagnostic prints before the message.
const char* severityName(Severity severity);

struct Diagnostic {
  Severity severity = Severity::Error;
  SourceSpan span;  ///< may be invalid for errors that belong to no source text
  std::string message;
};

/// Errors a sink keeps before it stops, by default: enough to fix a file by, few enough
/// to read; the number clang and GCC stop at.
inline constexpr int kDefaultMaxErrors = 20;

/// Collects diagnostics; counts errors so stages can stop before writing anything.
class DiagnosticSink {
 public:
  /// `maxErrors` errors are kept; 0 keeps every one.
  explicit DiagnosticSink(int maxErrors = kDefaultMaxErrors) : maxErrors_(maxErrors) {}

  /// Keeps a diagnostic, unless the error limit was reached: then it is dropped (and
  /// counted), whatever its severity. The lexer and parser stop reading at the limit.
  void report(Severity severity, SourceSpan span, std::string message);
  void error(SourceSpan span, std::string message) { report(Severity::Error, span, std::move(message)); }
  void warning(SourceSpan span, std::string message) { report(Severity::Warning, span, std::move(message)); }
  void note(SourceSpan span, std::string message) { report(Severity::Note, span, std::move(message)); }

  /// Between these, a diagnostic identical to one kept since beginRepeats (severity,
  /// place and message) is dropped: for text the compiler compiles several times over,
  /// as the alternatives of a context. Not nested.
  void beginRepeats() { repeatsFrom_ = diagnostics_.size(); }
  void endRepeats() { repeatsFrom_ = kNoRepeats; }

  /// Errors kept (at most the limit).
  int errorCount() const { return errors_; }
  bool hasErrors() const { return errors_ > 0; }
  /// Errors reported, kept or dropped past the limit: what a caller compares before and
  /// after a step to learn whether the step failed (errorCount() stops at the limit).
  int errorsReported() const { return errorsReported_; }
  /// The error limit was reached: later diagnostics are dropped.
  bool limitReached() const { return maxErrors_ > 0 && errors_ >= maxErrors_; }
  int maxErrors() const { return maxErrors_; }
  /// Diagnostics reported after the limit and dropped.
  int droppedCount() const { return dropped_; }
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  void clear();
  /// Keeps a source file alive as long as the sink, so diagnostics can always show it.
  void retain(std::shared_ptr<const SourceFile> file) { files_.push_back(std::move(file)); }
  /// Hands every kept diagnostic to `consumer` as soon as it is reported (a terminal
  /// sees errors while a long file is still being checked); they are kept as well.
  void streamTo(std::function<void(const Diagnostic&)> consumer) { consumer_ = std::move(consumer); }

 private:
  std::vector<Diagnostic> diagnostics_;
  std::vector<std::shared_ptr<const SourceFile>> files_;
  std::function<void(const Diagnostic&)> consumer_;
  int maxErrors_ = kDefaultMaxErrors;
  int errors_ = 0;
  int errorsReported_ = 0;
  int dropped_ = 0;
  static constexpr size_t kNoRepeats = SIZE_MAX;
  size_t repeatsFrom_ = kNoRepeats;
};

/// Columns of a source line a diagnostic echoes: a longer line is shown as a window of
/// this many characters around the caret, with '…' where it was cut.
inline constexpr int kEchoColumns = 80;

/// "file:line:col: error: message\n<source line>\n    ^~~~\n"
std::string formatDiagnostic(const Diagnostic& diagnostic);
/// All diagnostics of a sink, formatted, in the order reported.
std::string formatDiagnostics(const DiagnosticSink& sink);

}  // namespace ontogen
