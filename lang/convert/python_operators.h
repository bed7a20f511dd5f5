#pragma once
// Operators whose meaning the cell language spells otherwise, in an expression already
// read into cell-language tokens. Python's (L-Py):
//
//   x % y        Python's remainder takes the sign of y; the cell language's `%` is C's
//                fmod, with the sign of x.  It becomes fmod(fmod(x, y) + y, y).
//   x // y       floor division: floor(x / y).
//   a < b < c    a chain of comparisons: (a < b && b < c).  The cell language would read
//                (a < b) < c.
//   a or b       a if a is true, else b: if(a, a, b) (if(a, 1, b) where a is a comparison);
//   a and b      b if a is true, else a (0): if(a, b, 0). Written || and && where every
//                operand is 0 or 1, or where only the truth of the whole is read.
//
// cpfg's (its lsys_input.y and generate.c):
//
//   x % y        C's remainder of the operands cast to int: fmod(trunc(x), trunc(y)).
//   -a ^ b       unary minus and ! bind tighter than ^: (-a) ^ b (the cell language reads
//                -(a ^ b)).
//   a ^ b ^ c    ^ is left-associative: (a ^ b) ^ c (the cell language's is right-).
//   x / y        cpfg divides by 1 where y is 0: x / if(y == 0, 1, y) (unless y is a
//                number other than 0).
//
// Everything else keeps the meaning the tokens have in order, since the languages agree
// on the other operators' precedences (docs/LANGUAGE.md 3.11). So a cpfg macro's tokens
// put in where its name stands read as C's textual replacement does.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lang/convert/lsystem_file.h"

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

/// The expression `tokens` spell, rewritten where one of the operators above occurs in
/// `dialect`; nullopt when none does (the tokens mean in the cell language what they
/// meant in the file). An operand written more than once by the rewrite that draws a
/// random number is a located error (each copy would draw anew). `truth`: only the
/// truth of the value is read (a condition), where Python's `or` and `and` are the cell
/// language's || and &&. Throws ConvertError through `syntax`.
std::optional<std::string> foreignOperators(const ForeignSyntax& syntax, const std::vector<ExpressionToken>& tokens,
                                            Dialect dialect, bool truth);

}  // namespace ontogen::convert
