// cpfg's modules and lists as the converter reads them (lang/convert/foreign_syntax.cpp,
// cpfg_reader.cpp): the '@' modules ontogen's turtle has not, '=' in a right context,
// digits and brackets in ignore: and consider: lists.

#include <gtest/gtest.h>

#include "tests/lang/convert/convert_test_support.h"

namespace ontogen::convert {
namespace {

using test::convertText;

std::string body(const std::string& program) {
  const size_t open = program.find("{\n"), close = program.rfind("}");
  return program.substr(open + 2, close - open - 2);
}

// cpfg's textures, elasticities, twist, contours, cylinder sides, scale and bounded
// circles (its blackbox.c) stay modules of a name, each with a warning at its first place.
TEST(CpfgVocabulary, AtModulesTheTurtleHasNotStayModulesOfAName) {
  auto c = convertText(Dialect::Cpfg, "a.l",
                       "Axiom: @Tx(2)F@Ts(1,0.5)@Ti(1)@Td(1)@Tp@Tf@#(3)@!(8)@D(2)@Di(2)@Dd(2)@bo(1)@bc(1)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  axiom Texture(2) F SetElasticity(1, 0.5) IncElasticity(1) DecElasticity(1) PreventTwist AcceptTwist "
            "SetContour(3) CylinderSides(8) SetScale(2) MultScale(2) DivScale(2) BoundedDisc(1) BoundedCircle3D(1)\n");
  ASSERT_EQ(c.warnings.size(), 13u);
  EXPECT_EQ(c.warnings[0],
            "1:8: cpfg's module '@Tx' has no counterpart in ontogen's turtle: it stays a module named 'Texture', so "
            "the word is cpfg's, but it draws nothing");
  EXPECT_EQ(c.warnings[6].substr(0, 38), "1:43: cpfg's module '@#' has no counte");
  auto unknown = convertText(Dialect::Cpfg, "a.l", "Axiom: F@Tq(1)\n");
  EXPECT_EQ(unknown.column, 9);
  EXPECT_NE(unknown.error.find("cpfg's module '@Tq' is none ontogen can translate"), std::string::npos)
      << unknown.error;
}

// cpfg's '=' before ']' in a right context skips the rest of the branch, as the cell
// language's ']' does there; cpfg's ']' alone (the branch ends right there) and '='
// elsewhere have no counterpart, refused at the context.
TEST(CpfgVocabulary, EqualsBeforeABracketSkipsTheRestOfTheBranch) {
  auto c = convertText(Dialect::Cpfg, "a.l", "Axiom: A[B]C\nA > [B=][=]C --> X\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  axiom A [ B ] C\n  A > [ B ] [ ] C -> X\n");
  auto bracket = convertText(Dialect::Cpfg, "a.l", "Axiom: A\nA > [B]C --> X\n");
  EXPECT_EQ(bracket.line, 2);
  EXPECT_EQ(bracket.column, 3);
  EXPECT_NE(bracket.error.find("cpfg's ']' in a right context matches where the branch ends"), std::string::npos)
      << bracket.error;
  auto equals = convertText(Dialect::Cpfg, "a.l", "Axiom: A\nA > B=C --> X\n");
  EXPECT_EQ(equals.column, 3);
  EXPECT_NE(equals.error.find("cpfg's '=' in a right context stands before ']'"), std::string::npos) << equals.error;
  auto successor = convertText(Dialect::Cpfg, "a.l", "Axiom: A\nA --> B=\n");
  EXPECT_EQ(successor.column, 8);
  EXPECT_NE(successor.error.find("cpfg's '=' (in a right context before ']'"), std::string::npos) << successor.error;
  auto left = convertText(Dialect::Cpfg, "a.l", "Axiom: A\nB= < A --> X\n");
  EXPECT_EQ(left.column, 1);
  EXPECT_NE(left.error.find("cpfg's '=' in a left context"), std::string::npos) << left.error;
}

// Digits name modules under #letters only: an ignore: list's digits, where no module is
// a digit, name modules the word never holds and are left out. With a digit module the
// block has #letters and keeps them.
TEST(CpfgVocabulary, DigitsNoModuleIsAreLeftOutOfIgnoreLists) {
  auto c = convertText(Dialect::Cpfg, "a.l", "ignore: +0-12\nAxiom: A\nA --> B\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  axiom A\n  ignore: + -\n  A -> B\n");
  auto letters = convertText(Dialect::Cpfg, "a.l", "ignore: +0\nAxiom: A\nA --> 0\n");
  ASSERT_EQ(letters.error, "");
  EXPECT_EQ(body(letters.program), "  #letters\n  axiom A\n  ignore: + 0\n  A -> 0\n");
  // A list of digits alone stays (an empty list would mean otherwise): the compiler's
  // error then names the line.
  auto only = convertText(Dialect::Cpfg, "a.l", "consider: 0\nAxiom: A\n");
  ASSERT_EQ(only.error, "");
  EXPECT_EQ(body(only.program), "  axiom A\n  consider: 0\n");
}

// cpfg reads brackets that a consider: list names, as the cell language always does.
TEST(CpfgVocabulary, BracketsOfAConsiderListAreLeftOut) {
  auto c = convertText(Dialect::Cpfg, "a.l", "Consider: SL[]\nAxiom: S\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  axiom S\n  consider: S L\n");
}

// cpfg's reader passes over spaces between a module and its parameters (vlab's
// Lychnis writes `\ (90)`), also before a tab-continued line.
TEST(CpfgVocabulary, SpacesBeforeParametersKeepThemOnTheirModule) {
  auto c = convertText(Dialect::Cpfg, "a.l", "Axiom: A (1)\nA(t) --> F [\\ (90) B(t)] /\n\t(45)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  axiom A(1)\n  A(t) -> F [ \\(90) B(t) ] /(45)\n");
}

// cpfg reads its file through the C preprocessor: a macro whose value is a module
// string stands for its modules where its name is a whole C token (not within xGROUND),
// and a line that ends in a backslash goes on on the next.
TEST(CpfgVocabulary, AMacroOfModulesIsItsModulesWhereItsNameStands) {
  auto c = convertText(Dialect::Cpfg, "a.l",
                       "#define GROUND [,(6)f(2)\\\n+F]\nAxiom: GROUND A\nA --> AB GROUND xGROUND\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  axiom [ color(6) f(2) + F ] A\n  A -> A B [ color(6) f(2) + F ] x G R O U N D\n");
  // A macro with parameters among modules: C would put its value there.
  auto call = convertText(Dialect::Cpfg, "a.l", "#define LEAF(x) x*2\nAxiom: A\nA --> F LEAF(3)\n");
  EXPECT_EQ(call.line, 3);
  EXPECT_EQ(call.column, 9);
  EXPECT_NE(call.error.find("a macro with parameters among modules"), std::string::npos) << call.error;
  // A module of a macro's name, C(x) beside #define C 0.5: C makes it 0.5(x).
  auto named = convertText(Dialect::Cpfg, "a.l", "#define C 0.5\nAxiom: A\nA --> F C(3)\n");
  EXPECT_EQ(named.line, 3);
  EXPECT_EQ(named.column, 9);
  EXPECT_NE(named.error.find("the macro 'C' before parameters"), std::string::npos) << named.error;
}

}  // namespace
}  // namespace ontogen::convert

namespace ontogen::convert {
namespace {

// cpfg's ?E is answered by an environmental program (cpfg -e): wherever it stands (a
// word, a predecessor of several modules, a consider: list) it is refused at its place.
TEST(CpfgVocabulary, TheEnvironmentsQueryIsRefusedAtItsPlace) {
  struct Case {
    const char* text;
    int line, column;
  };
  const Case cases[] = {
      {"Lsystem: 1\nAxiom: |+(30)?E(0)\nendlsystem\n", 2, 14},
      {"Lsystem: 1\nAxiom: fA\nf?E(x) : x==1 --> ;FA\nendlsystem\n", 3, 2},
      {"Lsystem: 1\nconsider: ?E[]\nAxiom: A\nendlsystem\n", 2, 11},
  };
  for (const Case& c : cases) {
    auto converted = test::convertText(Dialect::Cpfg, "a.l", c.text);
    EXPECT_EQ(converted.program, "") << c.text;
    EXPECT_TRUE(converted.untranslatable) << c.text;
    EXPECT_EQ(converted.line, c.line) << c.text << converted.error;
    EXPECT_EQ(converted.column, c.column) << c.text << converted.error;
    EXPECT_EQ(converted.error.rfind("cpfg's ?E, the query an environmental program answers (cpfg -e FILE)", 0), 0u)
        << converted.error;
  }
}

// cpfg's random numbers of the beta and binomial distributions have no counterpart
// among the cell language's draws: refused at the call, where they reached the compiler
// as unknown functions.
TEST(CpfgVocabulary, BetaAndBinomialDrawsAreRefusedAtTheCall) {
  auto beta = test::convertText(Dialect::Cpfg, "a.l", "Lsystem: 1\nAxiom: A(2)\nA(n) --> B(n*bran(5,16))\nendlsystem\n");
  EXPECT_TRUE(beta.untranslatable);
  EXPECT_EQ(beta.line, 3);
  EXPECT_EQ(beta.column, 14);
  EXPECT_EQ(beta.error.rfind("cpfg's bran(a, b), a random number of the beta distribution", 0), 0u) << beta.error;
  auto binomial = test::convertText(Dialect::Cpfg, "a.l", "Lsystem: 1\nAxiom: A(biran(4, 0.5))\nendlsystem\n");
  EXPECT_EQ(binomial.line, 2);
  EXPECT_EQ(binomial.column, 10);
  EXPECT_NE(binomial.error.find("binomial"), std::string::npos) << binomial.error;
}

}  // namespace
}  // namespace ontogen::convert
