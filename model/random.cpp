#include "model/random.h"

#include <bit>
#include <cmath>
#include <numbers>

namespace ontogen {

using random_detail::finalize;
using random_detail::kGoldenGamma;

uint64_t RandomStream::next() {
  state_ += kGoldenGamma;
  return finalize(state_);
}

double RandomStream::uniform() {
  // The top 53 bits fill a double's mantissa exactly: k / 2^53 for k in [0, 2^53).
  constexpr double kInverse2To53 = 0x1.0p-53;
  return static_cast<double>(next() >> 11) * kInverse2To53;
}

double RandomStream::gaussian() {
  // 1 - u lies in (0, 1], so the logarithm is finite.
  const double u1 = 1.0 - uniform();
  const double u2 = uniform();
  const double radius = std::sqrt(-2.0 * std::log(u1));
  return radius * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace ontogen
