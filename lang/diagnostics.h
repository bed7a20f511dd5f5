#pragma once
// Diagnostics are values handed to a sink the caller supplies; the libraries never
// print. formatDiagnostic renders one the way clang does: location, message, the
// source line and a caret under the span.

#include <memory>
#include <string>
#include <vector>

#include "lang/source.h"

namespace ontogen {

enum class Severity { Error, Warning, Note };

struct Diagnostic {
  Severity severity = Severity::Error;
  SourceSpan span;  ///< may be invalid for errors that belong to no source text
  std::string message;
};

/// Collects diagnostics; counts errors so stages can stop before writing anything.
class DiagnosticSink {
 public:
  void report(Severity severity, SourceSpan span, std::string message);
  void error(SourceSpan span, std::string message) { report(Severity::Error, span, std::move(message)); }
  void warning(SourceSpan span, std::string message) { report(Severity::Warning, span, std::move(message)); }
  void note(SourceSpan span, std::string message) { report(Severity::Note, span, std::move(message)); }

  int errorCount() const { return errors_; }
  bool hasErrors() const { return errors_ > 0; }
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  void clear();
  /// Keeps a source file alive as long as the sink, so diagnostics can always show it.
  void retain(std::shared_ptr<const SourceFile> file) { files_.push_back(std::move(file)); }

 private:
  std::vector<Diagnostic> diagnostics_;
  std::vector<std::shared_ptr<const SourceFile>> files_;
  int errors_ = 0;
};

/// "file:line:col: error: message\n<source line>\n    ^~~~\n"
std::string formatDiagnostic(const Diagnostic& diagnostic);
/// All diagnostics of a sink, formatted, in the order reported.
std::string formatDiagnostics(const DiagnosticSink& sink);

}  // namespace ontogen
