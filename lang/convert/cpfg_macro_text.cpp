#include "lang/convert/cpfg_macro_text.h"

#include <cctype>
#include <climits>

namespace ontogen::convert {

namespace {

bool isNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.'; }

// The level of cpfg's binary operator at the start of `text` (its yacc grammar, lowest
// first), and its length; 0 for none.
int binaryLevel(std::string_view text, size_t& length) {
  static constexpr struct {
    std::string_view op;
    int level;
  } kOperators[] = {{"||", 1}, {"&&", 2}, {"==", 3}, {"!=", 3}, {"<=", 4}, {">=", 4}, {"<", 4}, {">", 4},
                    {"+", 5},  {"-", 5},  {"*", 6},  {"/", 6},  {"%", 6},  {"^", 7}};
  for (const auto& [op, level] : kOperators)
    if (text.substr(0, op.size()) == op) {
      length = op.size();
      return level;
    }
  length = 0;
  return 0;
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  return text;
}

}  // namespace

bool replacementReadsAsParenthesised(std::string_view value, std::string_view before, std::string_view after,
                                     const std::function<bool(std::string_view name)>& isCompound) {
  // The loosest binary operator outside parentheses (INT_MAX: none); an operator is
  // binary where an operand ends before it.
  int loosest = INT_MAX;
  int depth = 0;
  bool operandBefore = false;
  for (size_t at = 0; at < value.size();) {
    const char c = value[at];
    if (std::isspace(static_cast<unsigned char>(c))) {
      ++at;
      continue;
    }
    if (isNameChar(c)) {
      size_t stop = at;
      while (stop < value.size() && isNameChar(value[stop])) ++stop;
      if (isCompound && isCompound(value.substr(at, stop - at))) return false;
      at = stop;
      operandBefore = true;
      continue;
    }
    if (c == '(' || c == ')') {
      depth += c == '(' ? 1 : -1;
      operandBefore = c == ')';
      ++at;
      continue;
    }
    if (c == '?' || c == ':') return false;
    size_t length = 0;
    const int level = binaryLevel(value.substr(at), length);
    if (depth == 0 && operandBefore && level > 0 && level < loosest) loosest = level;
    at += length > 0 ? length : 1;
    operandBefore = false;
  }
  if (loosest == INT_MAX) return true;  // a single operand with its unary operators
  // Before the call: the start of the expression, '(' or ',', or a binary operator of a
  // looser level (a unary one would take the value's first operand alone).
  before = trimmed(before);
  if (!before.empty() && before.back() != '(' && before.back() != ',') {
    size_t length = 0;
    int level = 0;
    for (size_t take = 2; take >= 1 && level == 0; --take)
      if (before.size() >= take) {
        level = binaryLevel(before.substr(before.size() - take), length);
        if (length != take) level = 0;
      }
    const std::string_view operand = trimmed(before.substr(0, before.size() - length));
    const bool binary = level > 0 && !operand.empty() && (isNameChar(operand.back()) || operand.back() == ')');
    if (!binary || level >= loosest) return false;
  }
  // After it: the end, ')' or ',', or a binary operator of the value's level or looser.
  after = trimmed(after);
  if (!after.empty() && after.front() != ')' && after.front() != ',') {
    size_t length = 0;
    const int level = binaryLevel(after, length);
    if (level == 0 || level > loosest) return false;
  }
  return true;
}

}  // namespace ontogen::convert
