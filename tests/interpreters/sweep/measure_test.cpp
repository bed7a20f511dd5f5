// Measures: the arithmetic, the quantities and counts they read, the sets they need, and
// the messages of bad ones (pinned with their column).

#include "interpreters/sweep/measure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace ontogen {
namespace {

RunQuantities sample() {
  RunQuantities q;
  q.values = {{"cells", 12}, {"height", 2.5}, {"width", 4}, {"root_moment", 3}, {"N", 7}};
  q.labels = {{"Apex", 5}, {"F", 6}};
  return q;
}

double value(const std::string& text, std::vector<std::string> extra = {}) {
  return parseMeasure("m=" + text, extra).evaluate(sample());
}

TEST(Measure, ArithmeticAsTheLanguageReadsIt) {
  EXPECT_EQ(value("1 + 2 * 3"), 7);
  EXPECT_EQ(value("(1 + 2) * 3"), 9);
  EXPECT_EQ(value("2 ^ 3 ^ 2"), 512);  // right associative
  EXPECT_EQ(value("-2 ^ 2"), -4);      // the power binds tighter than the sign
  EXPECT_EQ(value("2 ^ -1"), 0.5);
  EXPECT_EQ(value("10 / 4 - 1e-1"), 2.4);
  EXPECT_EQ(value("abs(-3) + sqrt(16) + min(1, 2) + max(1, 2)"), 10);
  EXPECT_EQ(value("log(exp(2))"), 2);
}

TEST(Measure, QuantitiesCountsAndExtraNames) {
  EXPECT_EQ(value("height / width"), 0.625);
  EXPECT_EQ(value("count(Apex) + count( F ) + count(Missing)"), 11);
  EXPECT_EQ(value("cells * N", {"N"}), 84);
  // A quantity the run did not report is NaN: the caller makes it the row's error.
  EXPECT_TRUE(std::isnan(value("length")));
  EXPECT_TRUE(std::isinf(value("1 / (cells - 12)")));
}

TEST(Measure, SourcesAndLabelsAreKnownBeforeAnyRun) {
  const Measure measure = parseMeasure("x=root_moment + height * count(Apex) + cells");
  EXPECT_EQ(measure.name(), "x");
  EXPECT_EQ(measure.text(), "root_moment + height * count(Apex) + cells");
  EXPECT_EQ(measure.sources(),
            (std::vector<QuantitySource>{QuantitySource::Physics, QuantitySource::Scene, QuantitySource::World}));
  EXPECT_EQ(measure.labels(), (std::vector<std::string>{"Apex"}));
  for (const QuantityInfo& quantity : quantities()) {
    EXPECT_FALSE(quantity.doc.empty()) << quantity.name;
    EXPECT_NO_THROW(parseMeasure("q=" + std::string(quantity.name)));
  }
}

TEST(Measure, BadMeasuresSayWhatAndWhere) {
  auto message = [](const std::string& text) {
    try {
      parseMeasure(text);
    } catch (const MeasureError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("height"), "--measure takes NAME=EXPR, a name of letters, digits and '_' and an expression, as "
                               "in --measure tall=height, not 'height'");
  EXPECT_EQ(message("1x=height"), "--measure takes NAME=EXPR, a name of letters, digits and '_' and an expression, "
                                  "as in --measure tall=height, not '1x=height'");
  EXPECT_EQ(message("h=hieght").substr(0, 62), "--measure h: unknown quantity 'hieght' (known: cells, time, st");
  EXPECT_EQ(message("h=height +"), "--measure h: expected a number, a quantity or '(' at column 9 of 'height +'");
  EXPECT_EQ(message("h=(height"), "--measure h: expected ')' at column 8 of '(height'");
  EXPECT_EQ(message("h=height height"), "--measure h: unexpected 'h' at column 8 of 'height height'");
  EXPECT_EQ(message("h=count()"), "--measure h: count() takes a cell's label, as in count(Apex) at column 7 of 'count()'");
  EXPECT_EQ(message("h=min(1)"), "--measure h: expected ',' at column 6 of 'min(1)'");
  EXPECT_EQ(message("h=" + std::string(300, '(') + "1" + std::string(300, ')')).substr(0, 45),
            "--measure h: expression too deep (more than 2");
}

}  // namespace
}  // namespace ontogen
