#include "interpreters/text/word_text.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "core/parents.h"
#include "core/salts.h"

namespace ontogen {

static std::string formatShort(double value, int precision) {
  if (value == 0) return "0";  // also turns -0 into 0
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
  return buffer;
}

std::string formatWord(const std::vector<WordCell>& word, int precision) {
  std::string text;
  for (const WordCell& cell : word) {
    if (!text.empty()) text += ' ';
    std::string module = cell.label;
    if (!cell.developed.empty()) {
      module += '(';
      for (size_t i = 0; i < cell.developed.size(); ++i) {
        if (i) module += ", ";
        module += formatShort(cell.developed[i], precision);
      }
      module += ')';
    }
    if (cell.timed)
      text += "(" + module + ", " + formatShort(cell.age, precision) + ")";
    else
      text += module;
    if (cell.system) text += cell.pool.empty() ? " { }" : " { " + formatWord(cell.pool, precision) + " }";
  }
  return text;
}

std::string formatExact(double value) {
  if (!std::isfinite(value)) return "null";
  if (value == 0) return "0";
  char buffer[40];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

static void writeString(std::ostream& out, const std::string& text) {
  out << '"';
  for (unsigned char c : text) {
    switch (c) {
      case '"':
        out << "\\\"";
        break;
      case '\\':
        out << "\\\\";
        break;
      case '\n':
        out << "\\n";
        break;
      case '\t':
        out << "\\t";
        break;
      default:
        if (c < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof escaped, "\\u%04x", c);
          out << escaped;
        } else {
          out << static_cast<char>(c);
        }
    }
  }
  out << '"';
}

static void writeArray(std::ostream& out, const std::vector<double>& values) {
  out << '[';
  for (size_t i = 0; i < values.size(); ++i) out << (i ? ", " : "") << formatExact(values[i]);
  out << ']';
}

static void writeCells(std::ostream& out, const std::vector<WordCell>& cells, const std::string& indent) {
  out << '[';
  for (size_t c = 0; c < cells.size(); ++c) {
    out << (c ? ",\n" : "\n") << indent << "{\"label\": ";
    writeString(out, cells[c].label);
    out << ", \"params\": ";
    writeArray(out, cells[c].params);
    out << ", \"developed\": ";
    writeArray(out, cells[c].developed);
    out << ", \"age\": " << formatExact(cells[c].age);
    out << ", \"id\": " << formatExact(idValue(cells[c].id)) << ", \"parent\": "
        << (cells[c].parent == kNoParent ? std::string("-1") : formatExact(idValue(cells[c].parent)));
    if (!cells[c].position.empty()) {
      out << ", \"position\": ";
      writeArray(out, cells[c].position);
    }
    if (cells[c].system) {
      out << ", \"pool\": ";
      writeCells(out, cells[c].pool, indent + "  ");
    }
    out << "}";
  }
  if (!cells.empty()) out << "\n" << indent.substr(2);
  out << ']';
}

void writeWordJson(std::ostream& out, const std::vector<WordAtTime>& words) {
  out << "{\"times\": [";
  for (size_t w = 0; w < words.size(); ++w) {
    out << (w ? ",\n  " : "\n  ") << "{\"t\": " << formatExact(words[w].time) << ", \"cells\": ";
    writeCells(out, words[w].cells, "    ");
    out << "}";
  }
  out << "\n]}\n";
}

}  // namespace ontogen
