#pragma once
// Python's operators whose meaning the cell language spells otherwise, in an L-Py
// expression already read into cell-language tokens:
//
//   x % y        Python's remainder takes the sign of y; the cell language's `%` is C's
//                fmod, with the sign of x.  It becomes fmod(fmod(x, y) + y, y).
//   x // y       floor division: floor(x / y).
//   a < b < c    a chain of comparisons: (a < b && b < c).  The cell language would read
//                (a < b) < c.
//
// Everything else keeps the meaning the tokens have in order, since the two languages
// agree on the other operators' precedences (docs/LANGUAGE.md 3.9).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ontogen::convert {

class ForeignSyntax;

/// One token of an expression as the converter wrote it, with the bytes of the file it
/// came from.
struct ExpressionToken {
  std::string text;
  uint32_t begin = 0;
  uint32_t end = 0;
  bool glued = false;  ///< written against the token before it: the '(' of a call
};

/// The expression `tokens` spell, rewritten where one of the operators above occurs;
/// nullopt when none does (the tokens mean in the cell language what they meant in
/// Python). An operand written more than once by the rewrite that draws a random number
/// is a located error (each copy would draw anew). Throws ConvertError through `syntax`.
std::optional<std::string> pythonOperators(const ForeignSyntax& syntax, const std::vector<ExpressionToken>& tokens);

}  // namespace ontogen::convert
