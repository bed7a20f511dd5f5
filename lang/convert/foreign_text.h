#pragma once
// The characters of cpfg's and L-Py's text as the converter's readers tell them apart.

#include <cctype>
#include <string>
#include <string_view>

namespace ontogen::convert::chars {

inline bool isLetter(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
inline bool isNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}
inline bool isSpace(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}
/// The one-character symbols the cell language takes as labels (docs/LANGUAGE.md 2).
inline bool isCellSymbol(char c) {
  return std::string_view("+-^&/\\|!<>[]$~@%").find(c) != std::string_view::npos;
}
/// Whether `text` is one Python string literal on its line, 'a', "a" (a prefix u, r or
/// b allowed): as a statement Python evaluates it and drops it.
inline bool isStringLiteral(std::string_view text) {
  while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
  if (!text.empty() && std::string_view("urbURB").find(text.front()) != std::string_view::npos) text.remove_prefix(1);
  if (text.size() < 2 || (text.front() != '\'' && text.front() != '"') || text.back() != text.front()) return false;
  const char quote = text.front();
  for (size_t k = 1; k + 1 < text.size(); ++k) {
    if (text[k] == '\\') ++k;
    else if (text[k] == quote) return false;
  }
  return true;
}
/// Text quoted for a message: 'text'.
inline std::string shown(std::string_view text) {
  return "'" + std::string(text) + "'";
}

}  // namespace ontogen::convert::chars
