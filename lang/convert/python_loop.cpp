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
                  ": the converter writes out a loop `for NAME in range(...)` over numbers written in the file "
                  "and its constants set once before the loop, turn by turn (a parameter varies from module to "
                  "module)");
}

}  // namespace

RangeLoop readRangeLoop(const ForeignSyntax& syntax, std::string_view text, const PythonStatement& loop) {
  const PythonBranch& header = loop.branches.front();
  const uint32_t b = header.testBegin, e = header.testEnd;
  RangeLoop result;
  uint32_t at = b;
  while (at < e && isNameChar(text[at])) ++at;
  uint32_t in = at;
  while (in < e && isSpace(text[in])) ++in;
  if (at == b || !chars::isLetter(text[b]) || !startsWithKeyword(text, in, e, "in"))
    refuse(syntax, loop.begin, e, "a 'for' over other than one name");
  result.name = std::string(text.substr(b, at - b));
  uint32_t call = in + 2;
  while (call < e && isSpace(text[call])) ++call;
  uint32_t open = call;
  while (open < e && isNameChar(text[open])) ++open;
  const std::string_view function = text.substr(call, open - call);
  while (open < e && isSpace(text[open])) ++open;
  if ((function != "range" && function != "xrange") || open >= e || text[open] != '(' ||
      syntax.find(open, e, ")") != e - 1)
    refuse(syntax, call, e, "a 'for' over other than range(...)");
  result.callBegin = call;
  result.end = e;
  const uint32_t close = e - 1;
  for (uint32_t from = open + 1; from <= close;) {
    const uint32_t comma = syntax.find(from, close, ",");
    uint32_t x = from, y = comma;
    syntax.trim(x, y);
    if (x == y) refuse(syntax, open, e, "range() with an empty argument");
    result.arguments.emplace_back(x, y);
    from = comma + 1;
  }
  if (result.arguments.empty() || result.arguments.size() > 3)
    refuse(syntax, open, e, "range() of other than one to three numbers");
  return result;
}

std::vector<std::string> loopTurns(const ForeignSyntax& syntax, const RangeLoop& loop,
                                   const std::vector<std::string>& arguments) {
  std::vector<long long> bounds;
  for (size_t k = 0; k < arguments.size(); ++k) {
    const auto [x, y] = loop.arguments[k];
    const std::optional<double> value = syntax.fixedNumber(arguments[k], x, y);
    if (!value) refuse(syntax, x, y, "a range over a value that is no written number");
    if (*value != std::floor(*value)) refuse(syntax, x, y, "a range over a number that is not whole (Python refuses it)");
    // Far beyond any range of kMaxLoopTurns turns a file writes, and within long long.
    if (std::fabs(*value) > 1e15) refuse(syntax, x, y, "a range over a number beyond 1e15");
    bounds.push_back(static_cast<long long>(*value));
  }
  const long long start = bounds.size() == 1 ? 0 : bounds[0];
  const long long stop = bounds.size() == 1 ? bounds[0] : bounds[1];
  const long long step = bounds.size() == 3 ? bounds[2] : 1;
  if (step == 0) refuse(syntax, loop.callBegin, loop.end, "range() with a step of 0 (Python refuses it)");
  std::vector<std::string> values;
  for (long long v = start; step > 0 ? v < stop : v > stop; v += step) {
    if (values.size() >= kMaxLoopTurns)
      refuse(syntax, loop.callBegin, loop.end, "a range of more than " + std::to_string(kMaxLoopTurns) + " turns");
    values.push_back(std::to_string(v));
  }
  return values;
}

}  // namespace ontogen::convert
