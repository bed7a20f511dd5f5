#include "lang/expression_compiler.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>

#include "model/expression_batch.h"
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

namespace ontogen {
namespace {

// A batch gives, lane for lane, the bits of one evaluation per cell: arithmetic,
// comparisons, powers, remainders, built-ins, infinities and denormals alike (a NaN for a
// NaN).
TEST(ExpressionBatch, EachLaneIsTheOneCellEvaluation) {
  const char* expressions[] = {
      "x * y + 1",         "-x / (y - 0.5)",     "x ^ y - 2 ^ -x",          "x % (y + 0.25)",
      "(x < y) + (x >= y) * 3 - (x == y)", "sin(x) * cos(y) + sqrt(abs(x))", "min(x, y) - max(x, 2 * y) + exp(-x)",
      "!x + !!y",          "x / 0 + y",          "1e308 * x * 10 - y",
  };
  const double values[] = {0.0, -0.0, 1.5, -2.25, 3e-310, 7.0, -1e300, std::nan(""), INFINITY, 0.5};
  for (const char* text : expressions) {
    auto f = compileText(text);
    ASSERT_FALSE(f->sink.hasErrors()) << text << formatDiagnostics(f->sink);
    ASSERT_TRUE(f->compiled.batchable(2)) << text;
    EXPECT_FALSE(f->compiled.batchable(1)) << text << " reads y, slot 1";
    constexpr int kLanes = CompiledExpression::kBatchLanes;
    double xs[kLanes], ys[kLanes], batch[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      xs[l] = values[l % 10];
      ys[l] = values[(l * 7 + 3) % 10];
    }
    RandomStream random(1);
    EvalContext context{nullptr, EvalEnvironment{&random, 1}, nullptr};
    f->compiled.evaluateBatch(
        kLanes, [&](int lane, int slot) { return slot == 0 ? xs[lane] : ys[lane]; },
        [](int, int) { return 0.0; }, context, batch);
    for (int l = 0; l < kLanes; ++l) {
      double frame[2] = {xs[l], ys[l]};
      context.frame = frame;
      const double one = f->compiled.evaluate(context);
      // A NaN is a NaN: which operand's NaN an instruction passes on (its sign and
      // payload) is the compiler's choice once it vectorises the lanes.
      if (std::isnan(one) && std::isnan(batch[l])) continue;
      EXPECT_EQ(std::bit_cast<uint64_t>(batch[l]), std::bit_cast<uint64_t>(one))
          << text << " at x = " << xs[l] << ", y = " << ys[l] << ": " << batch[l] << " and " << one;
    }
  }
}

// Batch code (three-address, fused pairs) gives, lane for lane, the bits of one
// evaluation per cell, in full batches and partial ones, whatever the operands' shapes:
// a lone slot or constant, chains of products, a result on either side of the next
// operation, built-ins of intermediate results, comparisons and negations.
TEST(ExpressionBatch, BatchCodeGivesEachLaneTheOneCellEvaluation) {
  const char* expressions[] = {
      "x",         "2.5",           "-x",                "x * y * y",            "x - y * 2",
      "2 / x - y", "(x + 1) * (y - 2)", "x * y + x * y", "-(x * y) / (y + x)", "min(x * y, y + 1) - x",
      "x ^ y - 2 ^ -x", "(x < y) + (x >= y) * 3 - (x == y)", "!x + !!y", "x % (y + 0.25) * y",
      "0.2 * (x - 4 * y) - x * y * y + 0.03 * (1 - x)", "(x * y - 1) / y", "2 - 3 / (x + y)",
      "x * y * y * x", "(x - y) * (x + y) - 1", "y / (x - (y + 2) * x)",
  };
  const double values[] = {0.0, -0.0, 1.5, -2.25, 3e-310, 7.0, -1e300, std::nan(""), INFINITY, 0.5, -3.0};
  constexpr int kLanes = BatchCode::kLanes;
  double xs[kLanes], ys[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    xs[l] = values[l % 11];
    ys[l] = values[(l * 7 + 3) % 11];
  }
  const double* slots[] = {xs, ys};
  for (const char* text : expressions) {
    auto f = compileText(text);
    ASSERT_FALSE(f->sink.hasErrors()) << text << formatDiagnostics(f->sink);
    BatchCode code;
    ASSERT_TRUE(code.compile(f->compiled, 2, 0)) << text;
    EXPECT_LE(code.instructionCount(), f->compiled.instructionCount()) << text;
    for (int lanes : {kLanes, 37, 1}) {
      double batch[kLanes];
      EvalContext context{nullptr, EvalEnvironment{nullptr, 1}, nullptr};
      code.evaluate(lanes, slots, nullptr, context, batch);
      for (int l = 0; l < lanes; ++l) {
        double frame[2] = {xs[l], ys[l]};
        context.frame = frame;
        const double one = f->compiled.evaluate(context);
        if (std::isnan(one) && std::isnan(batch[l])) continue;  // which NaN: as evaluateBatch
        EXPECT_EQ(std::bit_cast<uint64_t>(batch[l]), std::bit_cast<uint64_t>(one))
            << text << " (" << lanes << " lanes) at x = " << xs[l] << ", y = " << ys[l] << ": " << batch[l]
            << " and " << one;
      }
    }
  }
}

// An operation whose result only feeds the next is fused with it, up to three in a chain:
// Gray-Scott's rate of u, 9 operations, takes 3 instructions (4 * y into x - . into
// 0.2 * ., x * y into . * y into . - ., 1 - x into 0.03 * . into . + .); code that is
// not batchable, or reads a slot past the frame, does not compile.
TEST(ExpressionBatch, BatchCodeFusesAnOperationIntoTheNext) {
  auto f = compileText("0.2 * (x - 4 * y) - x * y * y + 0.03 * (1 - x)");
  ASSERT_FALSE(f->sink.hasErrors()) << formatDiagnostics(f->sink);
  BatchCode code;
  ASSERT_TRUE(code.compile(f->compiled, 2, 0));
  EXPECT_EQ(code.instructionCount(), 3u);
  EXPECT_FALSE(code.compile(f->compiled, 1, 0)) << "reads y, slot 1";
  EXPECT_TRUE(code.empty());
  auto branch = compileText("if(x < 1, x, y)");
  ASSERT_FALSE(branch->sink.hasErrors()) << formatDiagnostics(branch->sink);
  EXPECT_FALSE(code.compile(branch->compiled, 2, 0));
}

// An expression of one operation on one slot and a constant is recognised
// (pools/value_operation.h), and both ways a rewrite by a table computes it give the bits
// of the interpreter: zeros of either sign, denormals, infinities, overflow (a NaN for a
// NaN, whichever operand's), a constant NaN too.
TEST(ExpressionBatch, OneOperationOnASlotGivesTheInterpretersBits) {
  const char* expressions[] = {"x",       "y",         "2.5",     "x + 1.25", "0.5 + y", "x - 3",    "0.75 - x",
                               "x * 0.5", "-2 * x",    "x / 3",   "6 / y",    "x * 0",   "0 - x",    "x - 0",
                               "x + 0",   "x * -1",    "x * 1e300", "-0.0 + x", "x + -0.0", "x + 0 / 0", "(0 / 0) * y"};
  const double values[] = {0.0, -0.0, 1.5, -2.25, 3e-310, 7.0, -1e300, std::nan(""), INFINITY, -INFINITY, 0.5};
  for (const char* text : expressions) {
    auto f = compileText(text);
    ASSERT_FALSE(f->sink.hasErrors()) << text << formatDiagnostics(f->sink);
    ValueOperation operation;
    ASSERT_TRUE(f->compiled.asValueOperation(2, operation)) << text;
    for (double x : values)
      for (double y : values) {
        double frame[2] = {x, y};
        EvalContext context{frame, EvalEnvironment{nullptr, 1}, nullptr};
        const double one = f->compiled.evaluate(context);
        for (const double value : {operation.apply(frame), operation.applyQuickly(frame)}) {
          if (std::isnan(one) && std::isnan(value)) continue;
          EXPECT_EQ(std::bit_cast<uint64_t>(value), std::bit_cast<uint64_t>(one))
              << text << " at x = " << x << ", y = " << y << ": " << value << " and " << one;
        }
      }
  }
  ValueOperation operation;
  for (const char* text : {"x * y", "-x", "x ^ 2", "x % 2", "x + y", "sin(x)", "x * 2 + 1", "uniform(0, 1)", "x < 1"})
    EXPECT_FALSE(compileText(text)->compiled.asValueOperation(2, operation)) << text;
  EXPECT_FALSE(compileText("y + 1")->compiled.asValueOperation(1, operation)) << "y is slot 1, past the cell's values";
}

TEST(ExpressionBatch, JumpsDrawsAndFunctionsAreNotBatched) {
  for (const char* text : {"x > 0 && y > 0", "x > 0 || y", "uniform(0, 1) * x", "if(x > 1, x, y)"}) {
    auto f = compileText(text);
    ASSERT_FALSE(f->sink.hasErrors()) << text << formatDiagnostics(f->sink);
    EXPECT_FALSE(f->compiled.batchable(2)) << text;
  }
}

}  // namespace
}  // namespace ontogen
