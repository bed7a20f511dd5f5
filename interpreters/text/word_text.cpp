#include "interpreters/text/word_text.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/parents.h"
#include "core/salts.h"

namespace ontogen {

namespace {

// %.*g, as printf writes it, without -0.
void appendShort(std::string& text, double value, int precision) {
  // Only a program that allows non-finite state has any (core/finite_state.h); NaN's sign
  // means nothing, so it is `nan` alone.
  if (std::isnan(value)) {
    text += "nan";
    return;
  }
  if (value == 0) {
    text += '0';
    return;
  }
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::general, precision);
  text.append(buffer, result.ptr);
}

// The shortest form that reads back exactly; null for infinities and NaN.
void appendExact(std::string& text, double value) {
  if (!std::isfinite(value)) {
    text += "null";
    return;
  }
  if (value == 0) {
    text += '0';
    return;
  }
  char buffer[40];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  text.append(buffer, result.ptr);
}

void appendString(std::string& text, std::string_view value) {
  text += '"';
  for (unsigned char c : value) {
    switch (c) {
      case '"': text += "\\\""; break;
      case '\\': text += "\\\\"; break;
      case '\n': text += "\\n"; break;
      case '\t': text += "\\t"; break;
      default:
        if (c < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
          text += escaped;
        } else {
          text += static_cast<char>(c);
        }
    }
  }
  text += '"';
}

void appendArray(std::string& text, std::span<const double> values) {
  text += '[';
  for (size_t i = 0; i < values.size(); ++i) {
    if (i) text += ", ";
    appendExact(text, values[i]);
  }
  text += ']';
}

}  // namespace

void BufferedOutput::flush() {
  if (text_.empty()) return;
  out_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
  text_.clear();
}

void WordTextWriter::cell(const WordCellView& cell) {
  std::string& text = out_.text();
  if (depth_ > 0 || !first_) text += ' ';
  first_ = false;
  if (cell.timed) text += '(';
  text += cell.label;
  if (!cell.developed.empty()) {
    text += '(';
    for (size_t i = 0; i < cell.developed.size(); ++i) {
      if (i) text += ", ";
      appendShort(text, cell.developed[i], precision_);
    }
    text += ')';
  }
  if (cell.timed) {
    text += ", ";
    appendShort(text, cell.age, precision_);
    text += ')';
  }
  out_.wrote();
}

void WordTextWriter::enterPool() {
  out_.text() += " {";
  ++depth_;
}

void WordTextWriter::leavePool() {
  out_.text() += " }";
  --depth_;
}

std::string formatWord(const std::vector<WordCell>& word, int precision) {
  std::ostringstream text;
  {
    BufferedOutput out(text);
    WordTextWriter writer(out, precision);
    visitWord(word, writer);
  }
  return text.str();
}

std::string formatExact(double value) {
  std::string text;
  appendExact(text, value);
  return text;
}

void WordJsonWriter::begin() { out_.text() += "{\"times\": ["; }

void WordJsonWriter::beginTime(double t, bool first) {
  std::string& text = out_.text();
  text += first ? "\n  " : ",\n  ";
  text += "{\"t\": ";
  appendExact(text, t);
  text += ", \"cells\": ";
  openList();
}

void WordJsonWriter::endTime() {
  closeList();
  out_.text() += '}';
  out_.wrote();
}

void WordJsonWriter::end() {
  out_.text() += "\n]}\n";
  out_.flush();
}

void WordJsonWriter::openList() {
  out_.text() += '[';
  cellsInList_.push_back(0);
}

// The list's closing bracket on a line of its own, at the indentation of what holds it.
void WordJsonWriter::closeList() {
  std::string& text = out_.text();
  if (cellsInList_.back() > 0) {
    text += '\n';
    text.append(2 * cellsInList_.size(), ' ');
  }
  text += ']';
  cellsInList_.pop_back();
}

void WordJsonWriter::cell(const WordCellView& cell) {
  std::string& text = out_.text();
  text += cellsInList_.back()++ ? ",\n" : "\n";
  text.append(2 * cellsInList_.size() + 2, ' ');
  text += "{\"label\": ";
  appendString(text, cell.label);
  text += ", \"params\": ";
  appendArray(text, cell.params);
  text += ", \"developed\": ";
  appendArray(text, cell.developed);
  text += ", \"age\": ";
  appendExact(text, cell.age);
  text += ", \"id\": ";
  appendExact(text, idValue(cell.id));
  text += ", \"parent\": ";
  if (cell.parent == kNoParent)
    text += "-1";
  else
    appendExact(text, idValue(cell.parent));
  if (!cell.position.empty()) {
    text += ", \"position\": ";
    appendArray(text, cell.position);
  }
  if (cell.system)
    text += ", \"pool\": ";
  else
    text += '}';
  out_.wrote();
}

void WordJsonWriter::enterPool() { openList(); }

void WordJsonWriter::leavePool() {
  closeList();
  out_.text() += '}';
}

void writeWordJson(std::ostream& out, const std::vector<WordAtTime>& words) {
  BufferedOutput buffered(out);
  WordJsonWriter writer(buffered);
  writer.begin();
  for (const WordAtTime& word : words) {
    writer.beginTime(word.time, &word == words.data());
    visitWord(word.cells, writer);
    writer.endTime();
  }
  writer.end();
}

}  // namespace ontogen
