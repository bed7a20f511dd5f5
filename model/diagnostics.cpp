#include "model/diagnostics.h"

#include <algorithm>

#include "model/utf8.h"

namespace ontogen {

void DiagnosticSink::report(Severity severity, SourceSpan span, std::string message) {
  if (severity == Severity::Error) ++errorsReported_;
  if (limitReached()) {
    ++dropped_;
    return;
  }
  if (repeatsFrom_ != kNoRepeats)
    for (size_t i = repeatsFrom_; i < diagnostics_.size(); ++i) {
      const Diagnostic& kept = diagnostics_[i];
      if (kept.severity == severity && kept.span.file == span.file && kept.span.begin == span.begin &&
          kept.span.end == span.end && kept.message == message)
        return;
    }
  if (severity == Severity::Error) ++errors_;
  diagnostics_.push_back({severity, span, std::move(message)});
  if (consumer_) consumer_(diagnostics_.back());
}

void DiagnosticSink::clear() {
  diagnostics_.clear();
  errors_ = 0;
  errorsReported_ = 0;
  dropped_ = 0;
}

const char* severityName(Severity severity) {
  switch (severity) {
    case Severity::Error: return "error";
    case Severity::Warning: return "warning";
    case Severity::Note: return "note";
  }
  return "error";
}

namespace {

// One column of an echoed line: a character as written, or '?' for a byte that is no
// valid UTF-8 or a control character (a terminal would act on it).
struct Column {
  size_t begin = 0;  ///< byte offset in the line
  std::string_view shown;
};

std::vector<Column> columnsOf(std::string_view text) {
  std::vector<Column> columns;
  for (size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const size_t length = utf8SequenceLength(text, i);
    const bool control = (c < 0x20 && c != '\t') || c == 0x7F;
    if (length == 0 || control) {
      columns.push_back({i, "?"});
      ++i;
    } else {
      columns.push_back({i, text.substr(i, length)});
      i += length;
    }
  }
  return columns;
}

// The first column whose character starts at or after `byte`.
size_t columnAt(const std::vector<Column>& columns, size_t byte) {
  return std::lower_bound(columns.begin(), columns.end(), byte,
                          [](const Column& column, size_t at) { return column.begin < at; }) -
         columns.begin();
}

}  // namespace

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
  const std::vector<Column> columns = columnsOf(text);
  const size_t startByte = std::min<size_t>(text.size(), column - 1);
  const size_t endByte = std::min<size_t>(text.size(), startByte + (d.span.end - d.span.begin));
  const size_t start = columnAt(columns, startByte);
  const size_t end = std::max(start + 1, columnAt(columns, endByte));
  // A long line shows a window around the caret, so that a diagnostic stays a few
  // lines whatever the line's length.
  const size_t width = kEchoColumns, n = columns.size();
  const size_t first = n <= width ? 0 : std::min(start > width / 2 ? start - width / 2 : 0, n - width);
  const size_t last = std::min(n, first + width);
  std::string echo = first > 0 ? "…" : "";
  std::string caret = first > 0 ? " " : "";
  for (size_t k = first; k < last; ++k) echo += columns[k].shown;
  if (last < n) echo += "…";
  // Tabs are kept so the caret lines up under the same columns.
  for (size_t k = first; k < start && k < last; ++k) caret += columns[k].shown == "\t" ? '\t' : ' ';
  caret += '^';
  for (size_t k = start + 1; k < end && k < last; ++k) caret += '~';
  out += echo + "\n" + caret + "\n";
  return out;
}

std::string formatDiagnostics(const DiagnosticSink& sink) {
  std::string out;
  for (const auto& d : sink.diagnostics()) out += formatDiagnostic(d);
  return out;
}

}  // namespace ontogen
