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
  // One caret column per character (UTF-8 continuation bytes take none); tabs are kept
  // so the caret lines up under the same columns.
  auto isContinuation = [](char c) { return (static_cast<unsigned char>(c) & 0xC0) == 0x80; };
  std::string caret;
  size_t start = std::min<size_t>(text.size(), column - 1);
  for (size_t i = 0; i < start; ++i)
    if (!isContinuation(text[i])) caret += text[i] == '\t' ? '\t' : ' ';
  caret += '^';
  size_t end = std::min<size_t>(text.size(), start + (d.span.end - d.span.begin));
  bool first = true;
  for (size_t i = start; i < end; ++i) {
    if (isContinuation(text[i])) continue;
    if (!first) caret += '~';
    first = false;
  }
  out += caret + "\n";
  return out;
}

std::string formatDiagnostics(const DiagnosticSink& sink) {
  std::string out;
  for (const auto& d : sink.diagnostics()) out += formatDiagnostic(d);
  return out;
}

}  // namespace ontogen
