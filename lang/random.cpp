#include "lang/random.h"

#include <bit>
#include <cmath>
#include <numbers>

namespace ontogen {

namespace {

// 2^64 / golden ratio, the SplitMix64 increment: odd, and its multiples are spread
// evenly over the 64-bit circle, so consecutive counters give well-separated states.
constexpr uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ull;
// An odd multiplier (from Murmur3's fmix64) that separates the role of the second word.
constexpr uint64_t kSecondWordMultiplier = 0xC4CEB9FE1A85EC53ull;

// The SplitMix64 finaliser (Stafford's variant 13): a bijection with full avalanche.
constexpr uint64_t finalize(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

uint64_t mixKey(uint64_t a, uint64_t b) {
  // Each step is a bijection of the word it touches, so for a fixed b the map a -> key
  // is one-to-one, and likewise for a fixed a. The two words go through different
  // paths, which makes mixKey(a, b) differ from mixKey(b, a). Adding the gamma keeps
  // mixKey(0, 0) away from the finaliser's fixed point at 0.
  const uint64_t left = finalize(a + kGoldenGamma);
  const uint64_t right = std::rotl(b, 29) * kSecondWordMultiplier;
  return finalize(left ^ right);
}

uint64_t keyOf(double value) { return std::bit_cast<uint64_t>(value); }

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
