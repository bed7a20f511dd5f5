#include "model/message_number.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace ontogen {

std::string messageNumber(double value, int significantDigits) {
  if (std::isnan(value)) return "NaN";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  if (significantDigits == kShortestDigits) {
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
  }
  // At most 17 digits give back every double; more would only pad.
  const int digits = significantDigits < 1 ? 1 : significantDigits > 17 ? 17 : significantDigits;
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

}  // namespace ontogen
