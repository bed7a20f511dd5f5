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
/// Text quoted for a message: 'text'.
inline std::string shown(std::string_view text) {
  return "'" + std::string(text) + "'";
}

}  // namespace ontogen::convert::chars
