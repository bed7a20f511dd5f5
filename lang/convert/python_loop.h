#pragma once
// L-Py's `for NAME in range(...)` in a production body, over numbers written in the file:
// the converter writes the loop out turn by turn, its variable a local holding each value
// in turn, so the loop's statements become the productions' calculations. Any other loop
// (over a parameter, a list, a name a hook or --define may change) is a located error.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "lang/convert/foreign_syntax.h"
#include "lang/convert/python_block.h"

namespace ontogen::convert {

/// Turns of loops one body may take in all, over every way through its tests: each turn
/// writes its statements out once more, and loops within loops multiply (a body of 256
/// turns already writes a word longer than any model's production).
inline constexpr size_t kMaxLoopTurns = 256;

/// A loop's variable and the values it takes, as cell-language numbers.
struct LoopTurns {
  std::string name;
  std::vector<std::string> values;
};

/// The turns of the `for` statement `loop` (PythonStatement::isFor). Throws ConvertError
/// at a loop over anything but range() (or Python 2's xrange()) of one to three written
/// whole numbers, a step of 0, or more than kMaxLoopTurns turns.
LoopTurns readRangeLoop(const ForeignSyntax& syntax, std::string_view text, const PythonStatement& loop);

}  // namespace ontogen::convert
