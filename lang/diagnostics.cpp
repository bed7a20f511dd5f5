#include "lang/diagnostics.h"

#include <algorithm>

namespace ontogen {

void DiagnosticSink::report(Severity severity, SourceSpan span, std::string message) {
  if (severity == Severity::Error) ++errors_;
  diagnostics_.push_back({severity, span, std::move(message)});
}

void DiagnosticSink::clear() {
  diagnostics_.clear();
  errors_ = 0;
}

static const char* severityName(Severity severity) {
  switch (severity) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Note: return "note";
  }
  return "error";
}

std::string formatDiagnostic(const Diagnostic& d) {
  std::string out;
  if (!d.span.valid()) {
    out += "ontogen: ";
    out += severityName(d.severity);
    out += ": " + d.message + "\n";
    return out;
  }
  const SourceFile& file = *d.span.file;
  int line = d.span.line();
  int column = d.span.column();
  out += file.name() + ":" + std::to_string(line) + ":" + std::to_string(column) + ": ";
  out += severityName(d.severity);
  out += ": " + d.message + "\n";
  std::string_view text = file.lineText(line);
  out.append(text);
  out += "\n";
  // Tabs in the prefix are kept so the caret lines up under the same columns.
  std::string caret;
  for (int i = 0; i < column - 1 && i < static_cast<int>(text.size()); ++i)
    caret += text[i] == '\t' ? '\t' : ' ';
  caret += '^';
  int lineEnd = column - 1 + static_cast<int>(text.size() - std::min<size_t>(text.size(), column - 1));
  int width = static_cast<int>(d.span.end) - static_cast<int>(d.span.begin);
  int room = lineEnd - column;
  for (int i = 1; i < std::min(width, room + 1); ++i) caret += '~';
  out += caret + "\n";
  return out;
}

std::string formatDiagnostics(const DiagnosticSink& sink) {
  std::string out;
  for (const auto& d : sink.diagnostics()) out += formatDiagnostic(d);
  return out;
}

}  // namespace ontogen
