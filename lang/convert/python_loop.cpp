#include "lang/convert/python_loop.h"

#include <cmath>

#include "lang/convert/foreign_text.h"
#include "lang/convert/written_number.h"

namespace ontogen::convert {

namespace {

using chars::isNameChar;
using chars::isSpace;

[[noreturn]] void refuse(const ForeignSyntax& syntax, uint32_t begin, uint32_t end, const std::string& what) {
  syntax.fail(begin, end,
              what +
                  ": the converter writes out a loop `for NAME in range(...)` over numbers written in the file, "
                  "turn by turn (a name could be changed by a hook or --define after the loop is written out)");
}

}  // namespace

LoopTurns readRangeLoop(const ForeignSyntax& syntax, std::string_view text, const PythonStatement& loop) {
  const PythonBranch& header = loop.branches.front();
  const uint32_t b = header.testBegin, e = header.testEnd;
  LoopTurns turns;
  uint32_t at = b;
  while (at < e && isNameChar(text[at])) ++at;
  uint32_t in = at;
  while (in < e && isSpace(text[in])) ++in;
  if (at == b || !chars::isLetter(text[b]) || !startsWithKeyword(text, in, e, "in"))
    refuse(syntax, loop.begin, e, "a 'for' over other than one name");
  turns.name = std::string(text.substr(b, at - b));
  uint32_t call = in + 2;
  while (call < e && isSpace(text[call])) ++call;
  uint32_t open = call;
  while (open < e && isNameChar(text[open])) ++open;
  const std::string_view function = text.substr(call, open - call);
  while (open < e && isSpace(text[open])) ++open;
  if ((function != "range" && function != "xrange") || open >= e || text[open] != '(' ||
      syntax.find(open, e, ")") != e - 1)
    refuse(syntax, call, e, "a 'for' over other than range(...)");
  std::vector<long long> bounds;
  const uint32_t close = e - 1;
  for (uint32_t from = open + 1; from <= close;) {
    const uint32_t comma = syntax.find(from, close, ",");
    uint32_t x = from, y = comma;
    syntax.trim(x, y);
    if (x == y) refuse(syntax, open, e, "range() with an empty argument");
    const std::optional<double> value = writtenNumber(syntax.expression(x, y));
    if (!value) refuse(syntax, x, y, "a range over a value that is no written number");
    if (*value != std::floor(*value) || std::fabs(*value) > 1e9)
      refuse(syntax, x, y, "a range over a number that is not whole (Python refuses it)");
    bounds.push_back(static_cast<long long>(*value));
    from = comma + 1;
  }
  if (bounds.empty() || bounds.size() > 3) refuse(syntax, open, e, "range() of other than one to three numbers");
  const long long start = bounds.size() == 1 ? 0 : bounds[0];
  const long long stop = bounds.size() == 1 ? bounds[0] : bounds[1];
  const long long step = bounds.size() == 3 ? bounds[2] : 1;
  if (step == 0) refuse(syntax, open, e, "range() with a step of 0 (Python refuses it)");
  for (long long v = start; step > 0 ? v < stop : v > stop; v += step) {
    if (turns.values.size() >= kMaxLoopTurns)
      refuse(syntax, call, e, "a range of more than " + std::to_string(kMaxLoopTurns) + " turns");
    turns.values.push_back(std::to_string(v));
  }
  return turns;
}

}  // namespace ontogen::convert
