// L-Py files (tests/convert/*.lpy) converted and grown by `ontogen word`: the words L-Py
// derives, stated beside each case, and the located warnings of what the converted word
// writes otherwise than L-Py's.

#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "tests/apps/ontogen_process.h"

namespace {

using Result = ontogen::test::OntogenRun;

Result ontogen(const std::string& args) { return ontogen::test::runOntogenShell(args); }

std::string file(const std::string& name) {
  return std::string(ONTOGEN_SOURCE_DIR) + "/tests/convert/" + name;
}

// step = 0.5 is the file's constant (step_, as the cell language's step() is built in);
// @c is L-Py's modules @ and c; @L(str(x)) and @L(txt(x / 4)) Labels of the numbers; the
// helper nothing calls (a while loop) changes nothing. L-Py derives F(0.5) @ c @L('1')
// @L('0.25') A(2), then F(0.5) @ c @L('1') @L('0.25') F(1.0) @ c @L('2') @L('0.5') A(3).
TEST(ConvertLPyWords, NamesTheCellLanguageSpellsOtherwise) {
  Result result = ontogen("word " + file("lpy_names.lpy") + " --at 1,2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "t = 1: F(0.5) @ c Label(1) Label(0.25) A(2)\n"
            "t = 2: F(0.5) @ c Label(1) Label(0.25) F(1) @ c Label(2) Label(0.5) A(3)\n");
  EXPECT_NE(result.err.find("lpy_names.lpy:16:22: warning: L-Py predefines no module '@c'"), std::string::npos)
      << result.err;
  EXPECT_NE(result.err.find("lpy_names.lpy:16:28: warning: L-Py's Label shows the text of a number"), std::string::npos)
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

// A loop over a range of constants in the axiom and randint's bounds of constants: L-Py
// derives A(0) A(1) A(2) A(3), then B(k, 0) B(k, 3) B(k, 6) B(k, 9) with each k from 1
// to 3, then each y one more (derivation length N - 1 = 2). The constants are written
// in place: --define cannot change them apart from the turns written out.
TEST(ConvertLPyWords, ConstantsWhereTheConverterWritesOutANumber) {
  Result result = ontogen("word " + file("lpy_constants.lpy") + " --at 0,2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const std::string out = result.out;
  ASSERT_EQ(out.rfind("t = 0: A(0) A(1) A(2) A(3)\nt = 2: ", 0), 0u) << out;
  const std::string word = out.substr(out.find("t = 2: ") + 7);
  const std::regex module(R"(B\(([123]), (\d+)\) ?)");
  int y = 1;
  for (auto m = std::sregex_iterator(word.begin(), word.end(), module); m != std::sregex_iterator(); ++m, y += 3)
    EXPECT_EQ((*m)[2].str(), std::to_string(y)) << out;
  EXPECT_EQ(y, 13) << out;
  Result defined = ontogen("word " + file("lpy_constants.lpy") + " --at 1 --define N=5");
  EXPECT_EQ(defined.exitCode, 2) << defined.err;
  EXPECT_NE(defined.err.find("cannot set 'N'"), std::string::npos) << defined.err;
}

// randint(1, 3) drawn for 240 modules: only 1, 2 and 3, each near a third (80) of them.
TEST(ConvertLPyWords, RandintChoosesEachWholeNumberOfItsRangeAlike) {
  Result result = ontogen("word " + file("lpy_randint.lpy") + " --at 1");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  std::istringstream words(result.out.substr(result.out.find(": ") + 2));
  std::map<std::string, int> counts;
  std::string module;
  while (words >> module) ++counts[module];
  ASSERT_EQ(counts.size(), 3u) << result.out;
  for (const char* drawn : {"B(1)", "B(2)", "B(3)"}) {
    EXPECT_GT(counts[drawn], 50) << drawn;
    EXPECT_LT(counts[drawn], 110) << drawn;
  }
}

// Strings alone on a line (holding an arrow or produce) and a string given to a name
// nothing reads change no word: L-Py derives B(2), then A(4).
TEST(ConvertLPyWords, StringsPythonDropsChangeNoWord) {
  Result result = ontogen("word " + file("lpy_strings.lpy") + " --at 1,2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, "t = 1: B(2)\nt = 2: A(4)\n");
}

// L-Py's vectors as parameters (its tutorial chaikin.lpy): Chaikin's corner cutting of
// (0,0), (0,4), (4,4), as Python and PlantGL compute it: each cut at 1/4 and 3/4 of an
// edge, the ends kept.
TEST(ConvertLPyWords, VectorParametersAreTheirComponents) {
  Result result = ontogen("word " + file("lpy_vectors.lpy") + " --at 1,2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "t = 1: P(0, 0) E P(0, 1) E P(0, 3) E P(1, 4) E P(3, 4) E P(4, 4)\n"
            "t = 2: P(0, 0) E P(0, 0.25) E P(0, 0.75) E P(0, 1.5) E P(0, 2.5) E P(0.25, 3.25) E P(0.75, 3.75) "
            "E P(1.5, 4) E P(2.5, 4) E P(3.25, 4) E P(3.75, 4) E P(4, 4)\n");
}

// One draw against rising thresholds, 0.2 and 0.7, for 250 modules: B, C and D with
// chances 0.2, 0.5 and 0.3 (50, 125 and 75 expected).
TEST(ConvertLPyWords, OneDrawAgainstRisingThresholdsChoosesEachBranchWithItsChance) {
  Result result = ontogen("word " + file("lpy_drawn_choice.lpy") + " --at 1");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  std::istringstream words(result.out.substr(result.out.find(": ") + 2));
  std::map<std::string, int> counts;
  std::string module;
  while (words >> module) ++counts[module];
  ASSERT_EQ(counts.size(), 3u) << result.out;
  EXPECT_GT(counts["B"], 25);
  EXPECT_LT(counts["B"], 80);
  EXPECT_GT(counts["C"], 90);
  EXPECT_LT(counts["C"], 160);
  EXPECT_GT(counts["D"], 45);
  EXPECT_LT(counts["D"], 110);
}

// Constants set again at the top level (R = 1.5; R *= R; N = 2; N += N; N = N * 10):
// Python's productions read R = 2.25 and N = 40 when they run.
TEST(ConvertLPyWords, AConstantSetAgainIsItsLastValue) {
  Result result = ontogen("word " + file("lpy_set_again.lpy") + " --at 1");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, "t = 1: B(2.25, 40)\n");
}

}  // namespace
