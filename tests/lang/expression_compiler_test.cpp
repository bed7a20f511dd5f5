#include "lang/expression_compiler.h"

#include <gtest/gtest.h>

#include <cmath>

#include "lang/parser.h"

namespace ontogen {
namespace {

// Compiles `#define R <text>` style expressions with names x (slot 0) and y (slot 1).
struct Fixture {
  std::unique_ptr<SourceFile> file;
  DiagnosticSink sink;
  ast::Program tree;
  CompiledExpression compiled;
};

std::unique_ptr<Fixture> compileText(const std::string& text) {
  auto f = std::make_unique<Fixture>();
  f->file = std::make_unique<SourceFile>("e", "#define R " + text + "\n");
  f->tree = parse(*f->file, f->sink);
  if (f->sink.hasErrors()) return f;
  NameLookup names;
  names.slot = [](std::string_view name) { return name == "x" ? 0 : name == "y" ? 1 : -1; };
  names.constant = [](std::string_view name) -> std::optional<double> {
    if (const BuiltinConstant* c = findConstant(name)) return c->value;
    return std::nullopt;
  };
  f->compiled = compileExpression(*f->tree.defines[0].value, names, f->sink);
  return f;
}

double eval(const std::string& text, double x = 0, double y = 0) {
  auto f = compileText(text);
  EXPECT_FALSE(f->sink.hasErrors()) << formatDiagnostics(f->sink);
  double frame[2] = {x, y};
  RandomStream random(1);
  EvalContext context{frame, EvalEnvironment{&random, 1}, nullptr};
  return f->compiled.evaluate(context);
}

TEST(ExpressionCompiler, CPrecedenceAndAssociativity) {
  EXPECT_DOUBLE_EQ(eval("1 + 2 * 3"), 7);
  EXPECT_DOUBLE_EQ(eval("(1 + 2) * 3"), 9);
  EXPECT_DOUBLE_EQ(eval("10 - 4 - 3"), 3);
  EXPECT_DOUBLE_EQ(eval("2 ^ 3 ^ 2"), 512);
  EXPECT_DOUBLE_EQ(eval("-2 ^ 2"), -4);
  EXPECT_DOUBLE_EQ(eval("2 ^ -1"), 0.5);
  EXPECT_DOUBLE_EQ(eval("7 % 4"), 3);
  EXPECT_DOUBLE_EQ(eval("1 < 2 == 1"), 1);
  EXPECT_DOUBLE_EQ(eval("!0 + !5"), 1);
  EXPECT_DOUBLE_EQ(eval("1 || 0 && 0"), 1);  // && binds tighter than ||
  EXPECT_DOUBLE_EQ(eval("1 | 0 & 0"), 1);    // the papers' & and |
}

TEST(ExpressionCompiler, VariablesAndShortCircuit) {
  EXPECT_DOUBLE_EQ(eval("x * y + 1", 3, 4), 13);
  EXPECT_DOUBLE_EQ(eval("x > 0 && y / x > 1", 0, 5), 0);
  EXPECT_DOUBLE_EQ(eval("x > 0 && y / x > 1", 2, 5), 1);
  EXPECT_DOUBLE_EQ(eval("x < 0 || y > 2", 1, 3), 1);
  EXPECT_DOUBLE_EQ(eval("if(x > 1, y, -y)", 2, 7), 7);
  EXPECT_DOUBLE_EQ(eval("if(x > 1, y, -y)", 0, 7), -7);
  EXPECT_DOUBLE_EQ(eval("(x && y) + (x || y) * 10", 2, 3), 11);  // nested short circuits
}

TEST(ExpressionCompiler, ConstantsAreFolded) {
  auto f = compileText("2 * pi + sqrt(16) + max(1, 5, 3)");
  ASSERT_TRUE(f->compiled.isConstant());
  EXPECT_DOUBLE_EQ(f->compiled.constantValue(), 2 * M_PI + 4 + 5);
  auto g = compileText("x + 2 * 3");
  EXPECT_FALSE(g->compiled.isConstant());
  EXPECT_EQ(g->compiled.instructionCount(), 3u);  // load x, const 6, add
}

TEST(ExpressionCompiler, StochasticCallsAreNotFolded) {
  auto f = compileText("uniform(0, 1)");
  EXPECT_FALSE(f->compiled.isConstant());
  EXPECT_TRUE(f->compiled.isStochastic());
}

TEST(ExpressionCompiler, ErrorsNameTheProblem) {
  auto f = compileText("z + 1");
  ASSERT_EQ(f->sink.errorCount(), 1);
  EXPECT_EQ(f->sink.diagnostics()[0].message, "unknown name 'z'");
  auto g = compileText("frobnicate(1)");
  EXPECT_EQ(g->sink.diagnostics()[0].message, "unknown function 'frobnicate'");
  auto h = compileText("if(1, 2)");
  EXPECT_EQ(h->sink.diagnostics()[0].message, "'if' takes 3 arguments (if(condition, then, else)), given 2");
  auto k = compileText("min(1)");
  EXPECT_NE(k->sink.diagnostics()[0].message.find("'min' takes at least 2 arguments"), std::string::npos);
}

}  // namespace
}  // namespace ontogen
