// The cases of L-Py's own test suite that the cell language cannot express, written as
// small L-Py files: each is refused at its place (tests/programs/lpy_test_suite.md lists
// every case and where it is carried over). Also its cases of module names, which the
// converter reads.

#include <gtest/gtest.h>

#include "tests/lang/convert/convert_test_support.h"

namespace ontogen::convert {
namespace {

using test::convertText;

struct Refused {
  const char* cases;  // L-Py's test cases it stands for
  const char* text;
  int line, column;
  const char* message;  // a part of the message
};

TEST(LPyTestSuite, CasesTheCellLanguageCannotExpressAreRefusedAtTheirPlace) {
  const Refused refused[] = {
      // test_starmatching: test_match_mod_with_starmod and the other cases of '*' as the
      // predecessor; test_kwd: *(*args), *(**kwds).
      {"wildcard predecessor", "Axiom: A(2)\nproduction:\n*(name, x) --> B(x)\n", 3, 1, "a wildcard predecessor"},
      // test_matching: test_match_mod_with_stararg, _for_two, _for_zero.
      {"*args", "Axiom: A(3, 4)\nproduction:\nA(*args) --> B\n", 3, 3, "'*args' takes any number of parameters"},
      // test_regexpmatching: test_match_left_regexp_to_none, test_match_right_regexp_to_none,
      // test_match_regexp_including_start.
      {"repetition", "Axiom: A\nproduction:\nx(I) < A --> B\n", 3, 1, "repetition x(...)"},
      // test_endeach: test_endeach_lstring_modif (EndEach adds a module to the word).
      {"EndEach's word", "def EndEach(lstring):\n    lstring += 'B'\n    return lstring\nAxiom: A\n", 3, 5,
       "EndEach"},
  };
  for (const Refused& r : refused) {
    auto c = convertText(Dialect::LPy, "case.lpy", r.text);
    EXPECT_EQ(c.program, "") << r.cases;
    EXPECT_EQ(c.line, r.line) << r.cases << ": " << c.error;
    EXPECT_EQ(c.column, r.column) << r.cases << ": " << c.error;
    EXPECT_NE(c.error.find(r.message), std::string::npos) << r.cases << ": " << c.error;
  }
}

// test_modnamespace: a declared name is one module (module BABA: BABA is one; module
// BA: BABA is two), and a production of declared names rewrites it (test_querymodname).
TEST(LPyTestSuite, DeclaredModuleNamesAreReadWhole) {
  auto one = convertText(Dialect::LPy, "a.lpy", "module BABA, DADA\nAxiom: BABA\nproduction:\nBABA --> DADA\n");
  ASSERT_EQ(one.error, "");
  EXPECT_NE(one.program.find("  axiom BABA\n"), std::string::npos) << one.program;
  EXPECT_NE(one.program.find("  BABA -> DADA\n"), std::string::npos) << one.program;
  auto two = convertText(Dialect::LPy, "a.lpy", "module BA\nAxiom: BABA\n");
  ASSERT_EQ(two.error, "");
  EXPECT_NE(two.program.find("  axiom BA BA\n"), std::string::npos) << two.program;
}

}  // namespace
}  // namespace ontogen::convert
