#include "lang/parser.h"

#include <gtest/gtest.h>

namespace ontogen {
namespace {

struct Parsed {
  std::unique_ptr<SourceFile> file;
  DiagnosticSink sink;
  ast::Program program;
};

std::unique_ptr<Parsed> parseText(const std::string& text) {
  auto result = std::make_unique<Parsed>();
  result->file = std::make_unique<SourceFile>("test.cell", text);
  result->program = parse(*result->file, result->sink);
  return result;
}

TEST(Parser, CellWithContextPredicateAndActions) {
  auto p = parseText(
      "#define kmin 0.1\n"
      "cell A(x = 1) {\n"
      "  rules {\n"
      "    A(y) me A(z) : y > kmin && z > kmin : x = (y + z) / 2;\n"
      "    age > 3 && x > 0.5 : -> me B(x / 2);\n"
      "  }\n"
      "  interpret geometry { !(x) F(1 + age) }\n"
      "  interpret music { note(60 + 12 * x, 0.25) }\n"
      "}\n"
      "system filament { pool linear; axiom A(1) A(0) A(0.5) }\n");
  ASSERT_FALSE(p->sink.hasErrors()) << formatDiagnostics(p->sink);
  ASSERT_EQ(p->program.cells.size(), 1u);
  const auto& cell = p->program.cells[0];
  ASSERT_EQ(cell.rules.size(), 2u);
  EXPECT_TRUE(cell.rules[0].hasContext);
  EXPECT_EQ(cell.rules[0].left.size(), 1u);
  EXPECT_EQ(cell.rules[0].right.size(), 1u);
  EXPECT_NE(cell.rules[0].predicate, nullptr);
  EXPECT_EQ(cell.rules[0].calculations.size(), 1u);
  EXPECT_FALSE(cell.rules[0].hasAction);
  EXPECT_FALSE(cell.rules[1].hasContext);
  EXPECT_TRUE(cell.rules[1].hasAction);
  ASSERT_EQ(cell.rules[1].successors.size(), 2u);
  EXPECT_TRUE(cell.rules[1].successors[0].isMe);
  EXPECT_EQ(cell.interpretations.size(), 2u);
  EXPECT_EQ(p->program.systems[0].axiom.size(), 3u);
}

TEST(Parser, LSystemStatementsEndAtLinesUnlessIndented) {
  auto p = parseText(
      "lsystem piston {\n"
      "  axiom (piston, 0)\n"
      "  p1: (piston, 0.04) -> (mov(50), 0) !(10)\n"
      "        cC(60, true) f(50)\n"
      "  p2: (mov(x), 4) -> (mov(x), 0)\n"
      "  g mov(tau, beta) = 1 - cos(2 * pi * tau / beta)\n"
      "}\n");
  ASSERT_FALSE(p->sink.hasErrors()) << formatDiagnostics(p->sink);
  const auto& system = p->program.systems[0];
  ASSERT_EQ(system.productions.size(), 2u);
  EXPECT_EQ(system.productions[0].name, "p1");
  EXPECT_EQ(system.productions[0].successors.size(), 4u);
  EXPECT_NE(system.productions[0].successors[0].age, nullptr);
  EXPECT_EQ(system.productions[1].predecessor.label, "mov");
  ASSERT_EQ(system.functions.size(), 1u);
  EXPECT_EQ(system.functions[0].params.size(), 2u);
}

TEST(Parser, LabelIsTriedBeforeCondition) {
  auto p = parseText(
      "lsystem a {\n"
      "  axiom A(1)\n"
      "  A(x) : x > 5 -> B\n"
      "  A : time > 5 -> C\n"
      "  q: A(x) -> D\n"
      "}\n");
  ASSERT_FALSE(p->sink.hasErrors()) << formatDiagnostics(p->sink);
  const auto& productions = p->program.systems[0].productions;
  ASSERT_EQ(productions.size(), 3u);
  EXPECT_NE(productions[0].predicate, nullptr);
  EXPECT_EQ(productions[1].name, "");
  EXPECT_NE(productions[1].predicate, nullptr);
  EXPECT_EQ(productions[2].name, "q");
}

TEST(Parser, ContextAndStochasticProductions) {
  auto p = parseText(
      "lsystem a {\n"
      "  axiom A\n"
      "  B C < S > G [ H ] M -> X\n"
      "  A -> B : 0.25\n"
      "}\n");
  ASSERT_FALSE(p->sink.hasErrors()) << formatDiagnostics(p->sink);
  const auto& productions = p->program.systems[0].productions;
  EXPECT_EQ(productions[0].left.size(), 2u);
  EXPECT_EQ(productions[0].right.size(), 5u);
  EXPECT_NE(productions[1].probability, nullptr);
}

TEST(Parser, ArgumentsMustTouchTheLabel) {
  auto p = parseText("lsystem a {\n  axiom F (G, 1) F(2)\n}\n");
  ASSERT_FALSE(p->sink.hasErrors()) << formatDiagnostics(p->sink);
  const auto& axiom = p->program.systems[0].axiom;
  ASSERT_EQ(axiom.size(), 3u);
  EXPECT_FALSE(axiom[0].hasArgs);
  EXPECT_NE(axiom[1].age, nullptr);
  EXPECT_TRUE(axiom[2].hasArgs);
}

TEST(Parser, PowerBindsTighterThanUnaryMinusAndIsRightAssociative) {
  auto p = parseText("#define A -2^2\n#define B 2^3^2\nlsystem a { axiom X }\n");
  ASSERT_FALSE(p->sink.hasErrors());
  const auto& a = *p->program.defines[0].value;
  EXPECT_EQ(a.kind, ast::Expr::Kind::Unary);
  const auto& b = *p->program.defines[1].value;
  ASSERT_EQ(b.kind, ast::Expr::Kind::Binary);
  EXPECT_EQ(b.args[1]->kind, ast::Expr::Kind::Binary);  // 2^(3^2)
}

TEST(Parser, RecoversAndReportsEveryBadStatement) {
  auto p = parseText(
      "lsystem a {\n"
      "  axiom A\n"
      "  A -> B(\n"
      "  B -> C\n"
      "  C D -> E\n"
      "}\n");
  EXPECT_EQ(p->sink.errorCount(), 2) << formatDiagnostics(p->sink);
  EXPECT_EQ(p->program.systems[0].productions.size(), 1u);
}

// Inputs 100,000 levels deep end in one located error, not in a stack overflow.
std::string repeat(std::string_view piece, int times) {
  std::string text;
  for (int i = 0; i < times; ++i) text += piece;
  return text;
}

void expectOneDepthError(const std::string& text, const std::string& message) {
  auto p = parseText(text);
  ASSERT_EQ(p->sink.errorCount(), 1) << formatDiagnostics(p->sink).substr(0, 2000);
  const Diagnostic& error = p->sink.diagnostics().front();
  EXPECT_NE(error.message.find(message), std::string::npos) << error.message;
  EXPECT_EQ(error.span.line(), 1);
}

TEST(Parser, DeepParenthesesEndInOneError) {
  expectOneDepthError("#define K " + repeat("(", 100000) + "1" + repeat(")", 100000) + "\nlsystem a { axiom X }\n",
                      "expression nested too deeply (more than 200 levels)");
}

TEST(Parser, DeepPowersAndSignsEndInOneError) {
  expectOneDepthError("#define K " + repeat("2^", 100000) + "2\nlsystem a { axiom X }\n",
                      "expression nested too deeply (more than 200 levels)");
  expectOneDepthError("#define K " + repeat("-", 100000) + "2\nlsystem a { axiom X }\n",
                      "expression nested too deeply (more than 200 levels)");
}

TEST(Parser, LongChainsOfOperatorsEndInOneError) {
  // Left-associative chains recurse in the compiler, not in the parser.
  expectOneDepthError("#define K 1" + repeat(" + 1", 100000) + "\nlsystem a { axiom X }\n",
                      "expression too deep: more than 1000 operators inside each other");
  auto ok = parseText("#define K 1" + repeat(" + 1", 999) + "\nlsystem a { axiom X }\n");
  EXPECT_FALSE(ok->sink.hasErrors()) << formatDiagnostics(ok->sink).substr(0, 500);
}

TEST(Parser, DeepContextsEndInOneError) {
  expectOneDepthError("cell A { rules { " + repeat("(", 100000) + "me" + repeat(")", 100000) + " : -> A; } }\n",
                      "context nested too deeply (more than 200 levels)");
}

TEST(Parser, DeepBracketsAreModulesNotNesting) {
  auto p = parseText("lsystem a {\n  axiom " + repeat("[", 100000) + "F" + repeat("]", 100000) + "\n}\n");
  ASSERT_FALSE(p->sink.hasErrors());
  EXPECT_EQ(p->program.systems[0].axiom.size(), 200001u);
}

TEST(Parser, AProductionEndsAtTheLineAfterIt) {
  // `A > B` has no arrow; the next line is a production of its own.
  auto p = parseText("lsystem a {\n  axiom A B\n  A > B\n  B -> C\n}\n");
  ASSERT_EQ(p->sink.errorCount(), 1) << formatDiagnostics(p->sink);
  EXPECT_EQ(p->sink.diagnostics()[0].span.line(), 3);
  ASSERT_EQ(p->program.systems[0].productions.size(), 1u);
  EXPECT_EQ(p->program.systems[0].productions[0].predecessor.label, "B");
}

TEST(Parser, BacktrackingFromALabelRestoresTheParentheses) {
  auto p = parseText("lsystem a {\n  A : (time) == 1 -> B\n  axiom A\n}\n");
  ASSERT_FALSE(p->sink.hasErrors()) << formatDiagnostics(p->sink);
  const auto& system = p->program.systems[0];
  ASSERT_EQ(system.productions.size(), 1u);
  EXPECT_TRUE(system.productions[0].name.empty());
  EXPECT_NE(system.productions[0].predicate, nullptr);
  ASSERT_EQ(system.axiom.size(), 1u);
}

}  // namespace
}  // namespace ontogen
