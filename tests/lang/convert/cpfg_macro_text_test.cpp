// Where C's textual replacement of a cpfg macro reads as its parenthesised value
// (lang/convert/cpfg_macro_text.cpp): each case as C's grammar groups the text.

#include "lang/convert/cpfg_macro_text.h"

#include <gtest/gtest.h>

#include "tests/lang/convert/convert_test_support.h"

namespace ontogen::convert {
namespace {

bool reads(std::string_view value, std::string_view before, std::string_view after) {
  return replacementReadsAsParenthesised(value, before, after, [](std::string_view name) { return name == "D"; });
}

TEST(CpfgMacroText, OperatorsLooserBeforeAndNoTighterAfter) {
  EXPECT_TRUE(reads("3000*func(5,x)*dx", "phi+", ""));         // phi+(3000*...)
  EXPECT_TRUE(reads("3000*func(5,x)*dx", "phi + ", " * l / dx"));  // ((3000*f*dx)*l)/dx either way
  EXPECT_TRUE(reads("a*b", "x < ", " + 1"));
  EXPECT_TRUE(reads("a*b", "(", ")"));
  EXPECT_TRUE(reads("-a", "x^", ""));                          // no binary operator: one operand
  EXPECT_TRUE(reads("f(a+b)", "x*", "*y"));
  EXPECT_FALSE(reads("a*b", "y/", ""));                        // y/a*b is (y/a)*b
  EXPECT_FALSE(reads("a-b", "y-", ""));                        // y-a-b is (y-a)-b
  EXPECT_FALSE(reads("a+b", "", "*2"));                        // a+b*2
  EXPECT_FALSE(reads("a*b", "-", ""));                         // -a*b: the unary minus takes a
  EXPECT_TRUE(reads("a^b", "", "*2"));                         // (a^b)*2: ^ binds tighter
  EXPECT_TRUE(reads("a^b", "", "^2"));                         // (a^b)^2: cpfg's ^ groups from the left
  EXPECT_FALSE(reads("a>b?1:2", "x+", ""));
  EXPECT_FALSE(reads("a*D", "x-", ""));                        // D is a macro of several operands
}

// In a file: the call between + and *, a parenthesised value; one that C would read
// otherwise stays refused at the call.
TEST(CpfgMacroText, ACallIsWrittenWhereTheTextReadsAsItsValue) {
  auto c = test::convertText(Dialect::Cpfg, "a.l",
                             "#define rot(x) 3*x*dx\nLsystem: 1\nAxiom: C(1,2)\n"
                             "C(x,phi) : * {phi = phi + rot(x) * 4;} --> F(phi)\nendlsystem\n");
  ASSERT_EQ(c.error, "");
  EXPECT_NE(c.program.find("  C(x, phi) -> F((phi + (3 * x * dx) * 4))\n"), std::string::npos) << c.program;
  auto refused = test::convertText(Dialect::Cpfg, "a.l",
                                   "#define rot(x) 3*x+1\nLsystem: 1\nAxiom: C(1)\nC(x) --> F(2*rot(x))\nendlsystem\n");
  EXPECT_EQ(refused.line, 4);
  EXPECT_EQ(refused.column, 14);
  EXPECT_NE(refused.error.find("the macro 'rot' is replaced as text by C"), std::string::npos) << refused.error;
}

// derivation length: 0 shows the axiom: with no production or decomposition to rewrite
// it, every step's word is the axiom (#until 1); with one it is refused at the 0.
TEST(CpfgMacroText, DerivationLengthZero) {
  auto alone = test::convertText(Dialect::Cpfg, "a.l",
                                 "Lsystem: 1\nderivation length: 0\nAxiom: C(1)\nhomomorphism\nC(x) --> F(x)\nendlsystem\n");
  ASSERT_EQ(alone.error, "");
  EXPECT_NE(alone.program.find("  #until 1\n"), std::string::npos) << alone.program;
  auto rewrites = test::convertText(Dialect::Cpfg, "a.l",
                                    "Lsystem: 1\nderivation length: 0\nAxiom: C(1)\ndecomposition\nC(x) --> F(x)\n"
                                    "endlsystem\n");
  EXPECT_EQ(rewrites.line, 2);
  EXPECT_EQ(rewrites.column, 20);
  EXPECT_NE(rewrites.error.find("derivation length 0 (the word is the axiom)"), std::string::npos) << rewrites.error;
}

}  // namespace
}  // namespace ontogen::convert
