// A message writes its numbers one way (model/message_number.h): non-finite values as the
// language writes them, whatever sign a NaN carries, finite ones as printf's %g.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "model/message_number.h"

namespace ontogen {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

TEST(MessageNumber, NonFiniteValuesReadAsTheLanguageWritesThem) {
  EXPECT_EQ(messageNumber(kInfinity), "inf");
  EXPECT_EQ(messageNumber(-kInfinity), "-inf");
  EXPECT_EQ(messageNumber(std::numeric_limits<double>::quiet_NaN()), "NaN");
  // printf writes this one "-nan": the sign of a NaN means nothing to a reader.
  EXPECT_EQ(messageNumber(-std::numeric_limits<double>::quiet_NaN()), "NaN");
  EXPECT_EQ(messageNumber(std::copysign(std::numeric_limits<double>::quiet_NaN(), -1.0), 15), "NaN");
  EXPECT_EQ(messageNumber(-kInfinity, kShortestDigits), "-inf");
  EXPECT_EQ(messageNumber(std::numeric_limits<double>::signaling_NaN(), kShortestDigits), "NaN");
}

TEST(MessageNumber, FiniteValuesTakeTheirSignificantDigits) {
  EXPECT_EQ(messageNumber(0.5), "0.5");
  EXPECT_EQ(messageNumber(-0.5), "-0.5");
  EXPECT_EQ(messageNumber(1e302), "1e+302");
  EXPECT_EQ(messageNumber(1234567.0), "1.23457e+06");
  EXPECT_EQ(messageNumber(1234567.0, 15), "1234567");
  EXPECT_EQ(messageNumber(0.1, kShortestDigits), "0.1");
  EXPECT_EQ(messageNumber(9007199254740991.0, 17), "9007199254740991");
  EXPECT_EQ(messageNumber(std::numeric_limits<double>::max()), "1.79769e+308");
}

}  // namespace
}  // namespace ontogen
