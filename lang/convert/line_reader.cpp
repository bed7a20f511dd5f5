#include "lang/convert/line_reader.h"

#include <cctype>

namespace ontogen::convert {

std::vector<Line> splitLines(std::string_view text) {
  std::vector<Line> lines;
  uint32_t begin = 0;
  for (uint32_t at = 0; at <= text.size(); ++at) {
    if (at == text.size() || text[at] == '\n') {
      uint32_t end = at;
      if (end > begin && text[end - 1] == '\r') --end;
      if (at < text.size() || begin < at) lines.push_back({begin, end});
      begin = at + 1;
    }
  }
  return lines;
}

uint32_t firstNonSpace(std::string_view text, Line line) {
  uint32_t at = line.begin;
  while (at < line.end && std::isspace(static_cast<unsigned char>(text[at]))) ++at;
  return at;
}

std::optional<uint32_t> afterKeyword(std::string_view text, Line line, std::string_view keyword) {
  const uint32_t at = firstNonSpace(text, line);
  if (line.end - at < keyword.size()) return std::nullopt;
  for (size_t i = 0; i < keyword.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(text[at + i])) != std::tolower(static_cast<unsigned char>(keyword[i])))
      return std::nullopt;
  const uint32_t after = at + static_cast<uint32_t>(keyword.size());
  if (std::isalpha(static_cast<unsigned char>(keyword.back())) && after < line.end &&
      (std::isalnum(static_cast<unsigned char>(text[after])) || text[after] == '_'))
    return std::nullopt;
  return after;
}

std::optional<uint32_t> afterLabel(std::string_view text, Line line, std::string_view keyword) {
  std::optional<uint32_t> after = afterKeyword(text, line, keyword);
  if (!after) return std::nullopt;
  uint32_t at = *after;
  while (at < line.end && (text[at] == ' ' || text[at] == '\t')) ++at;
  if (at >= line.end || text[at] != ':') return std::nullopt;
  return at + 1;
}

}  // namespace ontogen::convert
