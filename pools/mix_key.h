#pragma once
// The 64-bit hash behind every id and random stream: mixKey(a, b) mixes two words into
// one. It lives at the bottom of the stack (pools/) because a compact linear word
// (pools/compact_word.h) derives each module's id from its run's key with it, and lang's
// random streams (model/random.h) key themselves with it too.

#include <bit>
#include <cstdint>

namespace ontogen {

namespace random_detail {
// 2^64 / golden ratio, the SplitMix64 increment: odd, and its multiples are spread
// evenly over the 64-bit circle, so consecutive counters give well-separated states.
inline constexpr uint64_t kGoldenGamma = 0x9E3779B97F4A7C15ull;
// An odd multiplier (from Murmur3's fmix64) that separates the role of the second word.
inline constexpr uint64_t kSecondWordMultiplier = 0xC4CEB9FE1A85EC53ull;

// The SplitMix64 finaliser (Stafford's variant 13): a bijection with full avalanche.
constexpr uint64_t finalize(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
}  // namespace random_detail

// mixKey in three parts, for a caller that mixes one word with many others: the first
// word's part, the second word's, and their join. mixKey(a, b) is
// mixKeyJoin(mixKeyFirst(a), mixKeySecond(b)), bit for bit.
constexpr uint64_t mixKeyFirst(uint64_t a) {
  // Adding the gamma keeps mixKey(0, 0) away from the finaliser's fixed point at 0.
  return random_detail::finalize(a + random_detail::kGoldenGamma);
}
constexpr uint64_t mixKeySecond(uint64_t b) {
  return std::rotl(b, 29) * random_detail::kSecondWordMultiplier;
}
constexpr uint64_t mixKeyJoin(uint64_t first, uint64_t second) {
  return random_detail::finalize(first ^ second);
}

/// Mixes two 64-bit words into one (a strong, invertible-per-argument hash). Inline:
/// the engine computes one per cell born.
constexpr uint64_t mixKey(uint64_t a, uint64_t b) {
  // Each step is a bijection of the word it touches, so for a fixed b the map a -> key
  // is one-to-one, and likewise for a fixed a. The two words go through different
  // paths, which makes mixKey(a, b) differ from mixKey(b, a).
  return mixKeyJoin(mixKeyFirst(a), mixKeySecond(b));
}

/// The bits of a double as a key (so +0.0 and -0.0 differ; NaN payloads are kept).
constexpr uint64_t keyOf(double value) {
  return std::bit_cast<uint64_t>(value);
}

}  // namespace ontogen
