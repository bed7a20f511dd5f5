// The compiler's options and what a compiled program tells its caller: values given to
// #defines from outside the text (CompileOptions::defines) and the list Program::defines.

#include "lang/compiler.h"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <limits>
#include <sstream>

namespace ontogen {
namespace {

struct Compiled {
  DiagnosticSink sink;
  std::unique_ptr<Program> program;
};

std::unique_ptr<Compiled> compileText(const std::string& text, std::vector<DefineOverride> defines = {}) {
  auto result = std::make_unique<Compiled>();
  CompileOptions options;
  options.defines = std::move(defines);
  result->program = compileSource("test.cell", text, result->sink, options);
  return result;
}

const char* const kModel =
    "#define N 3\n"
    "#define TWICE N * 2\n"
    "#define LIFE 2\n"
    "cell A(x = TWICE) { lifetime LIFE; }\n"
    "system s {\n"
    "  #define W 4\n"
    "  pool grid(W, N);\n"
    "  at(0, 0) A(N + 0.5);\n"
    "}\n";

TEST(CompilerDefines, ListsEveryDefineWithItsValueInOrder) {
  auto c = compileText(kModel);
  ASSERT_NE(c->program, nullptr) << formatDiagnostics(c->sink);
  const auto& defines = c->program->defines;
  ASSERT_EQ(defines.size(), 4u);
  EXPECT_EQ(defines[0].name, "N");
  EXPECT_EQ(defines[0].value, 3);
  EXPECT_EQ(defines[0].system, -1);
  EXPECT_FALSE(defines[0].overridden);
  EXPECT_EQ(defines[0].span.line(), 1);
  EXPECT_EQ(defines[1].name, "TWICE");
  EXPECT_EQ(defines[1].value, 6);
  EXPECT_EQ(defines[2].name, "LIFE");
  EXPECT_EQ(defines[3].name, "W");
  EXPECT_EQ(defines[3].value, 4);
  EXPECT_EQ(defines[3].system, 0);
}

TEST(CompilerDefines, AValueFromOutsideActsAsIfTheTextSaidIt) {
  auto c = compileText(kModel, {{"N", 5}, {"LIFE", 0.25}, {"W", 7}});
  ASSERT_NE(c->program, nullptr) << formatDiagnostics(c->sink);
  const Program& program = *c->program;
  // A constant after it, a default, a lifetime, a grid size and a placement's value.
  EXPECT_EQ(program.defines[0].value, 5);
  EXPECT_TRUE(program.defines[0].overridden);
  EXPECT_EQ(program.defines[1].value, 10);
  EXPECT_FALSE(program.defines[1].overridden);
  const MasterCell& a = program.masters[program.findMaster("A")];
  EXPECT_EQ(a.defaults, std::vector<double>{10});
  EXPECT_EQ(a.lifetime, 0.25);
  const SystemDefinition& s = program.systems[0];
  EXPECT_EQ(s.grid.size[0], 7u);
  EXPECT_EQ(s.grid.size[1], 5u);
  ASSERT_EQ(s.placements.size(), 1u);
  ASSERT_EQ(s.placements[0].values.size(), 1u);
  ASSERT_TRUE(s.placements[0].values[0].isConstant());
  EXPECT_EQ(s.placements[0].values[0].constantValue(), 5.5);
}

TEST(CompilerDefines, NegativeAndRealValues) {
  auto c = compileText(kModel, {{"TWICE", -2.5}});
  ASSERT_NE(c->program, nullptr) << formatDiagnostics(c->sink);
  EXPECT_EQ(c->program->masters[c->program->findMaster("A")].defaults, std::vector<double>{-2.5});
}

TEST(CompilerDefines, TheLastValueOfANameWins) {
  auto c = compileText(kModel, {{"N", 5}, {"N", 8}});
  ASSERT_NE(c->program, nullptr) << formatDiagnostics(c->sink);
  EXPECT_EQ(c->program->defines[0].value, 8);
}

TEST(CompilerDefines, EveryBlockDefiningTheNameTakesTheValue) {
  auto c = compileText(
      "#define K 1\n"
      "cell A(x = K) { }\n"
      "lsystem l { #define K 2\n axiom B(K)\n }\n"
      "system s { pool linear; axiom A; }\n",
      {{"K", 9}});
  ASSERT_NE(c->program, nullptr) << formatDiagnostics(c->sink);
  ASSERT_EQ(c->program->defines.size(), 2u);
  EXPECT_EQ(c->program->defines[0].value, 9);
  EXPECT_EQ(c->program->defines[1].value, 9);
  EXPECT_EQ(c->program->defines[1].system, 0);
  EXPECT_EQ(c->program->systems[0].axiom[0].values, std::vector<double>{9});
  EXPECT_EQ(c->program->masters[c->program->findMaster("A")].defaults, std::vector<double>{9});
}

TEST(CompilerDefines, ReplacedTextIsNotEvaluated) {
  // The text's value would be an error; the value from outside stands in its place.
  auto c = compileText("#define K nosuchname\nsystem s { pool linear; axiom A(K); }\ncell A(x = 0) { }\n", {{"K", 2}});
  ASSERT_NE(c->program, nullptr) << formatDiagnostics(c->sink);
  EXPECT_EQ(c->program->systems[0].axiom[0].values, std::vector<double>{2});
}

TEST(CompilerDefines, AnUnknownNameIsAnErrorListingTheDefinedOnes) {
  auto c = compileText(kModel, {{"SEGMENTS", 3}});
  EXPECT_EQ(c->program, nullptr);
  ASSERT_EQ(c->sink.errorCount(), 1);
  const Diagnostic& error = c->sink.diagnostics()[0];
  EXPECT_FALSE(error.span.valid());
  EXPECT_EQ(error.message, "cannot set 'SEGMENTS': the program has no #define SEGMENTS (it defines N, TWICE, LIFE, W)");
}

TEST(CompilerDefines, AnUnknownNameInAProgramWithoutDefines) {
  auto c = compileText("cell A { }\nsystem s { pool linear; axiom A; }\n", {{"K", 1}});
  EXPECT_EQ(c->program, nullptr);
  ASSERT_EQ(c->sink.errorCount(), 1);
  EXPECT_EQ(c->sink.diagnostics()[0].message, "cannot set 'K': the program has no #define K (it has no #define)");
}

TEST(CompilerDefines, AValueMustBeFinite) {
  auto c = compileText(kModel, {{"N", std::numeric_limits<double>::quiet_NaN()}});
  EXPECT_EQ(c->program, nullptr);
  ASSERT_EQ(c->sink.errorCount(), 1);
  EXPECT_EQ(c->sink.diagnostics()[0].message, "cannot set 'N' to NaN: a value for a #define must be a finite number");
  auto infinite = compileText(kModel, {{"N", -std::numeric_limits<double>::infinity()}});
  ASSERT_EQ(infinite->sink.errorCount(), 1);
  EXPECT_EQ(infinite->sink.diagnostics()[0].message,
            "cannot set 'N' to -inf: a value for a #define must be a finite number");
}

TEST(CompilerDefines, ImportedDefinesCanBeSet) {
  const std::string main = std::string(ONTOGEN_SOURCE_DIR) + "/tests/programs/import_library.cell";
  DiagnosticSink sink;
  CompileOptions options;
  options.defines = {{"base", 4}};
  std::ifstream in(main);
  std::ostringstream text;
  text << in.rdbuf();
  auto program = compileSource(main, text.str(), sink, options);
  ASSERT_NE(program, nullptr) << formatDiagnostics(sink);
  // More's step_size, then shapes' base, then the program's own twice = base * 2.
  ASSERT_EQ(program->defines.size(), 3u);
  EXPECT_EQ(program->defines[0].name, "step_size");
  EXPECT_EQ(program->defines[1].name, "base");
  EXPECT_TRUE(program->defines[1].overridden);
  EXPECT_EQ(program->defines[2].name, "twice");
  EXPECT_EQ(program->defines[2].value, 8);
}

}  // namespace
}  // namespace ontogen

namespace ontogen {
namespace {

// Past the error limit the sink drops errors without counting them as kept; an
// expression with an unknown function must still not be compiled (found by fuzz_grow).
TEST(CompilerErrorLimit, AnExpressionWithAnErrorPastTheLimitIsNotCompiled) {
  DiagnosticSink sink(1);
  const auto program = compileSource("limit.cell",
                                     "lsystem a {\n  axiom A(1)\n  A(x) -> A(nosuch(x))\n  B(x) -> B(other(x))\n}\n", sink);
  EXPECT_EQ(program, nullptr);
  EXPECT_EQ(sink.errorCount(), 1);
  EXPECT_EQ(sink.errorsReported(), 2);
}

}  // namespace
}  // namespace ontogen

namespace ontogen {
namespace {

// Labels are looked up through an index, not by a walk over every master: 100,000
// productions took minutes when each lookup walked them all (200,000: over a quarter of
// an hour), and take about a second now. The bound is loose for slow machines and the
// sanitizers, and far below the quadratic time.
TEST(CompilerScale, ManyProductionsCompileInLinearTime) {
  constexpr int kProductions = 100'000;
  std::string text = "lsystem big {\n  axiom A0\n";
  for (int i = 0; i < kProductions; ++i)
    text += "  A" + std::to_string(i) + " -> A" + std::to_string((i + 1) % kProductions) + "\n";
  text += "}\n";
  DiagnosticSink sink;
  const auto start = std::chrono::steady_clock::now();
  const auto program = compileSource("big.cell", text, sink);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_NE(program, nullptr) << formatDiagnostics(sink);
  EXPECT_GE(program->masters.size(), static_cast<size_t>(kProductions));
  EXPECT_LT(seconds, 60.0);
}

}  // namespace
}  // namespace ontogen
