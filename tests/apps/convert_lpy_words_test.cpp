// L-Py files (tests/convert/*.lpy) converted and grown by `ontogen word`: the words L-Py
// derives, stated beside each case, and the located warnings of what the converted word
// writes otherwise than L-Py's.

#include <gtest/gtest.h>

#include <string>

#include "tests/apps/ontogen_process.h"

namespace {

using Result = ontogen::test::OntogenRun;

Result ontogen(const std::string& args) { return ontogen::test::runOntogenShell(args); }

std::string file(const std::string& name) {
  return std::string(ONTOGEN_SOURCE_DIR) + "/tests/convert/" + name;
}

// step = 0.5 is the file's constant (step_, as the cell language's step() is built in);
// @c is L-Py's modules @ and c; @L(str(x)) a Label of the number; the helper nothing
// calls (a while loop) changes nothing. L-Py derives F(0.5) @ c @L('1') A(2), then
// F(0.5) @ c @L('1') F(1.0) @ c @L('2') A(3).
TEST(ConvertLPyWords, NamesTheCellLanguageSpellsOtherwise) {
  Result result = ontogen("word " + file("lpy_names.lpy") + " --at 1,2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "t = 1: F(0.5) @ c Label(1) A(2)\n"
            "t = 2: F(0.5) @ c Label(1) F(1) @ c Label(2) A(3)\n");
  EXPECT_NE(result.err.find("lpy_names.lpy:13:22: warning: L-Py predefines no module '@c'"), std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("lpy_names.lpy:13:28: warning: L-Py's Label shows the text str(x)"), std::string::npos)
      << result.err;
}

// A global the productions set and the hooks only assert, as L-Py's
// test_simple_matching.lpy has it, is left out: L-Py derives F(2) I(2), then F(2) F(2)
// F(2) I(0) at step 3 and F(2) F(2) F(2) at step 4, where I(0) produces nothing.
TEST(ConvertLPyWords, AGlobalOnlyTheHooksAssertChangesNoWord) {
  Result result = ontogen("word " + file("lpy_body_globals.lpy") + " --at 1,3,4");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, "t = 1: F(2) I(2)\nt = 3: F(2) F(2) F(2) I(0)\nt = 4: F(2) F(2) F(2)\n");
  EXPECT_NE(result.err.find("lpy_body_globals.lpy:22:5: warning: 'matched' set in a production body is read by "
                            "nothing the word depends on"),
            std::string::npos)
      << result.err;
}

}  // namespace
