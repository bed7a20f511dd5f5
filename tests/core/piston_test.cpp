// Paper 000, section 5.1: the piston of Fig. 5 and its derivation word in Table 1.

#include <gtest/gtest.h>

#include <cmath>

#include "core/word.h"
#include "interpreters/text/word_text.h"
#include "core/world.h"
#include "test_support.h"

namespace ontogen {
namespace {

using testing_support::compileModel;

struct Expected {
  std::string label;
  std::vector<double> developed;
  double age;  // NaN: untimed module, age not printed in Table 1
};

void expectWord(const std::vector<WordCell>& word, const std::vector<Expected>& expected, double tolerance) {
  ASSERT_EQ(word.size(), expected.size()) << formatWord(word);
  for (size_t i = 0; i < word.size(); ++i) {
    SCOPED_TRACE("module " + std::to_string(i) + " (" + expected[i].label + ")");
    EXPECT_EQ(word[i].label, expected[i].label);
    ASSERT_EQ(word[i].developed.size(), expected[i].developed.size());
    for (size_t p = 0; p < expected[i].developed.size(); ++p) {
      EXPECT_NEAR(word[i].developed[p], expected[i].developed[p], tolerance);
    }
    if (!std::isnan(expected[i].age)) {
      EXPECT_NEAR(word[i].age, expected[i].age, 1e-9);
    }
  }
}

std::vector<WordCell> wordAt(double t, double step) {
  World world(compileModel("piston.cell"));
  world.advanceTo(t, step);
  return captureWord(world);
}

const double kUntimed = NAN;

// The rest of the word after (turn, ...), identical in every row of Table 1.
std::vector<Expected> withFixedParts(double mov, double movAge, double bend, double bendAge, double turn,
                                     double turnAge) {
  return {{"mov", {mov}, movAge},   {"!", {10}, kUntimed},   {"cC", {60, 1}, kUntimed},
          {"bend", {bend}, bendAge}, {"!", {2}, kUntimed},    {"cC", {200, 1}, kUntimed},
          {"turn", {turn}, turnAge}, {"f", {50}, kUntimed},   {"+", {M_PI / 2}, kUntimed},
          {"[", {}, kUntimed},       {"disc", {0, 50}, kUntimed}, {"]", {}, kUntimed}};
}

TEST(Piston, Table1AtTime0) {
  auto word = wordAt(0.0, 0.01);
  ASSERT_EQ(word.size(), 1u);
  EXPECT_EQ(word[0].label, "piston");
  EXPECT_EQ(word[0].age, 0);
}

TEST(Piston, Table1AtTime0_04) {
  expectWord(wordAt(0.04, 0.01), withFixedParts(0, 0, 0, 0, 0, 0), 1e-12);
}

TEST(Piston, Table1AtTime1_04) {
  // mov: 50 (1 - cos(pi/2)) = 50; bend: asin(50/200) = 0.2527; turn: 0.2527 + pi/2 = 1.8235.
  auto word = wordAt(1.04, 0.01);
  expectWord(word, withFixedParts(50, 1, std::asin(0.25), 1, std::asin(0.25) + M_PI / 2, 1), 1e-9);
  // As printed in the paper, to its three significant digits.
  EXPECT_NEAR(word[3].developed[0], 0.253, 0.0005);
  EXPECT_NEAR(word[6].developed[0], 1.82, 0.005);
}

TEST(Piston, Table1AtTime4_04ShowsTheWordAtTheInstant) {
  // At t = 4.04 mov, bend and turn reach their terminal age 4 and are replaced at that
  // instant: ontogen shows the successors (age 0, g = 0). The paper prints the dying
  // turn's value, g_turn(beta, beta) = 2 pi = 6.28 (docs/LANGUAGE.md).
  auto word = wordAt(4.04, 0.01);
  expectWord(word, withFixedParts(0, 0, 0, 0, 0, 0), 1e-9);
  EXPECT_EQ(word[3].params[0], 2);  // p3 counted one period: bend(x + 1)
}

TEST(Piston, TheDyingTurnModuleShows2Pi) {
  // Just before its terminal age, turn develops to 2 pi, the paper's 6.28.
  auto word = wordAt(4.04 - 1e-7, 0.01);
  EXPECT_NEAR(word[6].developed[0], 2 * M_PI, 1e-5);
  EXPECT_NEAR(word[6].developed[0], 6.28, 0.005);
}

TEST(Piston, WordAt12_37DoesNotDependOnTheStep) {
  auto fine = wordAt(12.37, 0.01);
  for (double step : {0.1, 1.0, 0.37, 12.37}) {
    SCOPED_TRACE("step " + std::to_string(step));
    auto coarse = wordAt(12.37, step);
    ASSERT_EQ(coarse.size(), fine.size());
    for (size_t i = 0; i < fine.size(); ++i) {
      EXPECT_EQ(coarse[i].label, fine[i].label);
      EXPECT_EQ(coarse[i].id, fine[i].id);
      EXPECT_EQ(coarse[i].params, fine[i].params);
      EXPECT_NEAR(coarse[i].age, fine[i].age, 1e-9);
      for (size_t p = 0; p < fine[i].developed.size(); ++p)
        EXPECT_NEAR(coarse[i].developed[p], fine[i].developed[p], 1e-9);
    }
  }
  // And it is the expected word: three periods after 0.04, ages 0.33, bend counted 4.
  EXPECT_NEAR(fine[0].age, 0.33, 1e-9);
  EXPECT_EQ(fine[3].params[0], 4);
}

}  // namespace
}  // namespace ontogen
