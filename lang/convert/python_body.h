#pragma once
// L-Py's productions written as Python function bodies,
//
//   A(x) :
//     y = x * 2
//     if y > 3:
//       nproduce F(y)
//       produce B(y)
//     elif random() < 0.3: produce C
//     else: produce D
//
// read as cell-language productions: every way through the `if`/`elif`/`else` tree that
// ends in `produce` (or has `nproduce`d something) becomes one production, whose
// condition is the conjunction of the tests taken and whose successors are what the way
// `nproduce`d followed by what it `produce`d. Local assignments are substituted into what
// follows them; a loop `for i in range(3):` over written numbers is written out turn by
// turn (python_loop.h). A test of a uniform draw against a value, `random() < p`, is not a
// condition but a choice: the ways it splits become stochastic productions weighted p and
// 1 - p, and a way of such a choice that produces nothing keeps the module (L-Py leaves it
// unchanged). `n = randint(a, b)` over written numbers or constants (lpy_constants.h) is
// a choice too: one way per number, each weighted 1/(b - a + 1); so is one draw
// `r = random()` tested against rising thresholds, `if r <= p1: ... elif r <= p2: ...`.
// Any other Python is an error at its place.

#include <cstdint>
#include <string>
#include <vector>

#include "lang/convert/foreign_syntax.h"
#include "lang/convert/lsystem_file.h"
#include "lang/convert/python_block.h"

namespace ontogen::convert {

/// Most productions one body becomes; more is a located error (a body of many tests in a
/// row multiplies its ways, and no model writes a tenth as many).
inline constexpr size_t kMaxBodyProductions = 256;
/// Most numbers `n = randint(a, b)` in a body chooses among: one production per number
/// (and per way after it), within kMaxBodyProductions with room for other tests.
inline constexpr size_t kMaxRandintChoices = 64;
/// Most ways through one body's tests the converter follows, those that give no
/// production among them (a way that neither produces nor chooses gives none).
inline constexpr size_t kMaxBodyWays = 16 * kMaxBodyProductions;

/// The productions `head` (its contexts and predecessor read, no successors) becomes with
/// the body `lines`. A way that produces nothing and chooses nothing gives no production
/// (L-Py then tries the next one). Throws ConvertError at the construct it cannot read.
std::vector<Statement> translatePythonBody(const ForeignSyntax& syntax, std::string_view text,
                                           const Statement& head, const std::vector<BodyLine>& lines);

/// The value of L-Py's helper function of several lines (`def f(x):` and a body of
/// assignments to locals and parameters, if/elif/else, loops over ranges of written
/// numbers and `return EXPR`, docstrings, `pass`, `print`; `parameters` its parameters)
/// as one cell-language expression of its parameters: each way's returned value, joined
/// by `if(test, yes, no)`. Throws ConvertError at other Python, at a way that returns no
/// value, at a local holding a random draw read twice.
std::string translatePythonFunction(const ForeignSyntax& syntax, std::string_view text,
                                    const std::vector<std::string>& parameters, const std::vector<BodyLine>& lines);

}  // namespace ontogen::convert
