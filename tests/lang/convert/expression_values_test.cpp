// Expressions of cpfg and L-Py converted and evaluated by the cell language's compiler:
// the value each has is the one cpfg's evaluator (vlab's cpfg/generate.c) or Python
// computes, stated beside each case.

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "model/expression_batch.h"
#include "lang/expression_compiler.h"
#include "lang/parser.h"
#include "tests/lang/convert/convert_test_support.h"

namespace ontogen::convert {
namespace {

using test::convertText;

// The successor's argument of `A(x, y) --> B(expr)` as converted; "" on error.
std::string converted(Dialect dialect, const std::string& expr, std::string* error = nullptr) {
  const std::string text = dialect == Dialect::Cpfg ? "Lsystem: 1\nAxiom: A(1, 2)\nA(x, y) --> B(" + expr + ")\n"
                                                    : "Axiom: A(1, 2)\nA(x, y) --> B(" + expr + ")\n";
  auto c = convertText(dialect, dialect == Dialect::Cpfg ? "a.l" : "a.lpy", text);
  if (error) *error = std::to_string(c.line) + ":" + std::to_string(c.column) + ": " + c.error;
  const size_t at = c.program.find("-> B(");
  if (at == std::string::npos) return "";
  const size_t close = c.program.rfind(')', c.program.find('\n', at));
  return c.program.substr(at + 5, close - at - 5);
}

// The value of a cell-language expression of x and y.
double value(const std::string& expr, double x, double y) {
  SourceFile file("e", "#define R " + expr + "\n");
  DiagnosticSink sink;
  ast::Program tree = parse(file, sink);
  EXPECT_FALSE(sink.hasErrors()) << expr << "\n" << formatDiagnostics(sink);
  if (sink.hasErrors()) return -999;
  NameLookup names;
  names.slot = [](std::string_view name) { return name == "x" ? 0 : name == "y" ? 1 : -1; };
  names.constant = [](std::string_view name) -> std::optional<double> {
    if (const BuiltinConstant* c = findConstant(name)) return c->value;
    return std::nullopt;
  };
  CompiledExpression compiled = compileExpression(*tree.defines[0].value, names, sink);
  EXPECT_FALSE(sink.hasErrors()) << expr << "\n" << formatDiagnostics(sink);
  double frame[2] = {x, y};
  RandomStream random(1);
  EvalContext context{frame, EvalEnvironment{&random, 1}, nullptr};
  return compiled.evaluate(context);
}

struct Case {
  const char* expr;
  double x, y;
  double expected;
};

void expectValues(Dialect dialect, std::initializer_list<Case> cases) {
  for (const Case& k : cases) {
    std::string error;
    const std::string text = converted(dialect, k.expr, &error);
    ASSERT_NE(text, "") << k.expr << ": " << error;
    EXPECT_EQ(value(text, k.x, k.y), k.expected) << k.expr << " with x = " << k.x << ", y = " << k.y << " as " << text;
  }
}

// Python's `or` and `and` give an operand (python3 -c 'x, y = 0, 3; print(x or y)'),
// the cell language's || and && give 0 or 1.
TEST(ExpressionValues, PythonsOrAndAndGiveAnOperand) {
  expectValues(Dialect::LPy, {
                                 {"x or y", 0, 3, 3},
                                 {"x or y", 2, 3, 2},
                                 {"x and y", 2, 3, 3},
                                 {"x and y", 0, 3, 0},
                                 {"x > 1 or y", 0, 5, 5},
                                 {"x > 1 or y", 2, 5, 1},  // True
                                 {"(x or y) * 2", 0, 4, 8},
                                 {"x or y or 7", 0, 0, 7},
                                 {"x and y or 9", 2, 0, 9},
                                 {"x and y or 9", 2, 3, 3},
                                 {"x and y > 1", 5, 3, 1},
                                 {"x and y > 1", 0, 3, 0},
                                 {"not (x or y)", 0, 0, 1},
                                 {"max(x or 4, 1)", 0, 0, 4},
                                 {"x < 1 or y < 1", 2, 0, 1},
                             });
  // Where every operand is 0 or 1, or only the truth is read, they stay || and &&.
  EXPECT_EQ(converted(Dialect::LPy, "x > 1 or not y"), "x > 1 || !(y)");
  auto condition = convertText(Dialect::LPy, "a.lpy", "Axiom: A(1, 2)\nA(x, y) : x and (y or x) --> B\n");
  ASSERT_EQ(condition.error, "");
  EXPECT_NE(condition.program.find("A(x, y) : x && (y || x) -> B"), std::string::npos) << condition.program;
  // An operand that draws is written once where it is chosen, refused where it would be
  // written twice.
  EXPECT_EQ(converted(Dialect::LPy, "x and random()"), "if(x, uniform(), 0)");
  std::string error;
  EXPECT_EQ(converted(Dialect::LPy, "random() or x", &error), "");
  EXPECT_NE(error.find("2:24: Python's 'or' of a left operand that draws a random number"), std::string::npos) << error;
}

// cpfg divides by 1 where the divisor is 0 ("Warning: division by 0.", generate.c) and
// reads `<>` as `!=` (lsys_input.l).
TEST(ExpressionValues, CpfgsDivisionByZeroAndNotEqual) {
  expectValues(Dialect::Cpfg, {
                                  {"x / y", 6, 0, 6},
                                  {"x / y", 6, 3, 2},
                                  {"x / (y - 3) + 1", 6, 3, 7},
                                  {"x / 0", 5, 0, 5},
                                  {"x <> y", 1, 2, 1},
                                  {"x <> y", 2, 2, 0},
                                  {"x<>y ? 3 : 4", 2, 2, 4},
                              });
  EXPECT_EQ(converted(Dialect::Cpfg, "x / 2"), "x / 2");
  std::string error;
  EXPECT_EQ(converted(Dialect::Cpfg, "x / ran(1)", &error), "");
  EXPECT_NE(error.find("3:17: cpfg's '/' of a divisor that draws a random number"), std::string::npos) << error;
  // Python 2's `<>` is `!=` as well.
  expectValues(Dialect::LPy, {{"x <> y", 1, 2, 1}, {"x <> y", 2, 2, 0}});
}

}  // namespace
}  // namespace ontogen::convert
