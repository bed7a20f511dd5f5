#pragma once
// The statements of a block of Python as the converter reads L-Py's production bodies
// and hooks: logical lines by indentation, `if` / `elif` / `else` with their tests and
// bodies (on the line of the test or indented below it), and every other line a simple
// statement, which the reader of a body or a hook tells apart by what it may say.

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "lang/convert/foreign_syntax.h"

namespace ontogen::convert {

/// One logical line of a body: bytes [begin, end) of the file (a line continued inside
/// parentheses spans several), and its indentation in columns.
struct BodyLine {
  uint32_t begin = 0;
  uint32_t end = 0;
  int indent = 0;
};

/// The logical lines of [begin, end) of `text`: blank lines dropped, lines joined while
/// parentheses are open.
std::vector<BodyLine> logicalLines(std::string_view text, uint32_t begin, uint32_t end);

struct PythonStatement;

/// One way of an `if`: its test [testBegin, testEnd) (empty for `else`) and its body.
struct PythonBranch {
  uint32_t testBegin = 0;
  uint32_t testEnd = 0;
  std::vector<PythonStatement> body;
};

/// A statement [begin, end), its spaces trimmed: an `if` (branches not empty), a `for`
/// (one branch, whose "test" is what follows `for`: `i in range(3)`) or a simple
/// statement (no branches). An `if` written on the line of a test is a simple
/// statement, which the readers refuse; so is another compound statement (`while`,
/// `with` ...), whose indented block is passed over.
struct PythonStatement {
  uint32_t begin = 0;
  uint32_t end = 0;
  std::vector<PythonBranch> branches;
  bool loop = false;  ///< a `for`
  bool isIf() const { return !branches.empty() && !loop; }
  bool isFor() const { return loop; }
};

/// The statements of `lines` (all of them, the first line's indentation being the
/// block's). Throws ConvertError (through `syntax`) at a line indented where no block
/// opens, an `elif`/`else` without its `if`, a test without ':' or without a body.
std::vector<PythonStatement> readPythonBlock(const ForeignSyntax& syntax, std::string_view text,
                                             const std::vector<BodyLine>& lines);

/// A simple statement `NAME = VALUE` or `NAME op= VALUE` (op one of + - * /).
struct PythonAssignment {
  std::string name;
  char op = '=';            ///< '=', or the operator of an augmented assignment
  uint32_t valueBegin = 0;  ///< the value is [valueBegin, the statement's end), untrimmed
};

/// The assignment the statement [begin, end) of `text` is, or nullopt.
std::optional<PythonAssignment> readAssignment(std::string_view text, uint32_t begin, uint32_t end);

/// The names `statements` assign (or loop over) on any of their ways: Python's locals of a body, which
/// hide the file's globals of the same name wherever the body reads them.
std::set<std::string, std::less<>> assignedNames(std::string_view text, const std::vector<PythonStatement>& statements);

/// Whether [begin, end) of `text` starts with the keyword `word` (followed by no name
/// character).
bool startsWithKeyword(std::string_view text, uint32_t begin, uint32_t end, std::string_view word);

}  // namespace ontogen::convert
