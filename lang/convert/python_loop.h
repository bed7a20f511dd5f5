#pragma once
// L-Py's `for NAME in range(...)` in a production body, over numbers written in the file:
// the converter writes the loop out turn by turn, its variable a local holding each value
// in turn, so the loop's statements become the productions' calculations. The range's
// arguments are read where the loop is reached, with the locals of the way put in, so a
// loop over a local holding a written number, or over an outer loop's variable, is
// written out too. Any other loop (over a parameter, a list, a name a hook or --define
// may change) is a located error.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lang/convert/foreign_syntax.h"
#include "lang/convert/python_block.h"

namespace ontogen::convert {

/// Turns of loops one body may take in all, over every way through its tests: each turn
/// writes its statements out once more, and loops within loops multiply (a body of 256
/// turns already writes a word longer than any model's production).
inline constexpr size_t kMaxLoopTurns = 256;

/// A loop `for NAME in range(ARGUMENTS)` as written.
struct RangeLoop {
  std::string name;
  std::vector<std::pair<uint32_t, uint32_t>> arguments;  ///< bytes [begin, end) of each, one to three
  uint32_t callBegin = 0;  ///< `range(...)`: bytes [callBegin, end)
  uint32_t end = 0;
};

/// The loop the `for` statement `loop` (PythonStatement::isFor) is. Throws ConvertError
/// at a loop over anything but range() (or Python 2's xrange()) of one to three
/// arguments.
RangeLoop readRangeLoop(const ForeignSyntax& syntax, std::string_view text, const PythonStatement& loop);

/// The values the loop's variable takes, as cell-language numbers, given its arguments as
/// cell-language expressions (the way's locals put in). Throws ConvertError at an
/// argument that is no written whole number, a step of 0, or more than kMaxLoopTurns
/// turns.
std::vector<std::string> loopTurns(const ForeignSyntax& syntax, const RangeLoop& loop,
                                   const std::vector<std::string>& arguments);

}  // namespace ontogen::convert
