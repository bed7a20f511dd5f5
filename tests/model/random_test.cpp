#include "model/random.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <vector>

namespace ontogen {
namespace {

// ---- mixKey -------------------------------------------------------------------------

TEST(MixKey, IsDeterministic) {
  EXPECT_EQ(mixKey(1, 2), mixKey(1, 2));
  EXPECT_EQ(mixKey(0xDEADBEEF, 42), mixKey(0xDEADBEEF, 42));
}

TEST(MixKey, IsAsymmetric) {
  EXPECT_NE(mixKey(1, 2), mixKey(2, 1));
  EXPECT_NE(mixKey(0, 1), mixKey(1, 0));
  for (uint64_t a = 0; a < 50; ++a) {
    for (uint64_t b = a + 1; b < 50; ++b) {
      EXPECT_NE(mixKey(a, b), mixKey(b, a)) << a << ", " << b;
    }
  }
}

TEST(MixKey, ZeroIsNotAFixedPoint) {
  EXPECT_NE(mixKey(0, 0), 0u);
  EXPECT_NE(mixKey(0, 0), mixKey(0, 1));
  EXPECT_NE(mixKey(0, 0), mixKey(1, 0));
}

TEST(MixKey, NoCollisionsAlongEitherArgument) {
  // Each argument goes through a bijection, so neighbouring ids, seeds or instants give
  // distinct keys. Checks a grid and both one-argument lines.
  std::set<uint64_t> grid;
  for (uint64_t a = 0; a < 200; ++a) {
    for (uint64_t b = 0; b < 200; ++b) grid.insert(mixKey(a, b));
  }
  EXPECT_EQ(grid.size(), 200u * 200u);
  std::set<uint64_t> alongA, alongB;
  for (uint64_t i = 0; i < 20000; ++i) {
    alongA.insert(mixKey(i << 40, 12345));
    alongB.insert(mixKey(12345, i << 40));
  }
  EXPECT_EQ(alongA.size(), 20000u);
  EXPECT_EQ(alongB.size(), 20000u);
}

TEST(MixKey, OneBitFlipsAboutHalfTheOutput) {
  // Avalanche: flipping any single input bit, in either argument, changes about 32 of
  // the 64 output bits on average.
  for (int argument = 0; argument < 2; ++argument) {
    for (int bit = 0; bit < 64; ++bit) {
      double changed = 0.0;
      const int samples = 200;
      for (int i = 0; i < samples; ++i) {
        const uint64_t a = mixKey(static_cast<uint64_t>(i), 1);  // spread-out inputs
        const uint64_t b = mixKey(static_cast<uint64_t>(i), 2);
        const uint64_t flip = uint64_t{1} << bit;
        const uint64_t original = mixKey(a, b);
        const uint64_t flipped = argument == 0 ? mixKey(a ^ flip, b) : mixKey(a, b ^ flip);
        changed += std::popcount(original ^ flipped);
      }
      EXPECT_NEAR(changed / samples, 32.0, 2.5) << "argument " << argument << " bit " << bit;
    }
  }
}

// ---- keyOf --------------------------------------------------------------------------

TEST(KeyOf, IsTheBitPattern) {
  EXPECT_EQ(keyOf(1.0), 0x3FF0000000000000ull);
  EXPECT_EQ(keyOf(0.0), 0u);
  EXPECT_EQ(keyOf(-2.0), 0xC000000000000000ull);
  EXPECT_NE(keyOf(0.0), keyOf(-0.0));
  const uint64_t payload = 0x7FF8000000000123ull;
  EXPECT_EQ(keyOf(std::bit_cast<double>(payload)), payload);
  EXPECT_NE(keyOf(0.1), keyOf(std::nextafter(0.1, 1.0)));
}

// ---- RandomStream -------------------------------------------------------------------

TEST(RandomStream, IsSplitMix64) {
  // The reference outputs of SplitMix64 seeded with 0 (Vigna's splitmix64.c). Pinned
  // because a run's results must not change when the generator's code does.
  RandomStream stream(0);
  EXPECT_EQ(stream.next(), 0xE220A8397B1DCDAFull);
  EXPECT_EQ(stream.next(), 0x6E789E6AA1B965F4ull);
  EXPECT_EQ(stream.next(), 0x06C45D188009454Full);
  EXPECT_EQ(stream.next(), 0xF88BB8A8724C81ECull);
}

TEST(RandomStream, DefaultKeyIsZero) {
  RandomStream implicit, explicitZero(0);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(implicit.next(), explicitZero.next());
}

TEST(RandomStream, SameKeySameSequence) {
  RandomStream a(mixKey(7, 11)), b(mixKey(7, 11));
  for (int i = 0; i < 1000; ++i) {
    EXPECT_EQ(a.next(), b.next());
    EXPECT_EQ(a.uniform(), b.uniform());
    EXPECT_EQ(a.gaussian(), b.gaussian());
  }
}

TEST(RandomStream, CopiesContinueIdentically) {
  RandomStream original(5);
  original.next();
  RandomStream copy = original;
  for (int i = 0; i < 100; ++i) EXPECT_EQ(original.next(), copy.next());
}

TEST(RandomStream, DifferentKeysDifferentSequences) {
  std::set<uint64_t> firsts;
  for (uint64_t key = 0; key < 1000; ++key) {
    RandomStream a(key);
    firsts.insert(a.next());
  }
  EXPECT_EQ(firsts.size(), 1000u);

  RandomStream a(mixKey(1, 2)), b(mixKey(1, 3));
  int equal = 0;
  for (int i = 0; i < 1000; ++i) {
    if (a.next() == b.next()) ++equal;
  }
  EXPECT_EQ(equal, 0);
}

TEST(RandomStream, SequenceDoesNotRepeatSoon) {
  RandomStream stream(17);
  std::set<uint64_t> seen;
  for (int i = 0; i < 100000; ++i) seen.insert(stream.next());
  EXPECT_EQ(seen.size(), 100000u);
}

TEST(RandomStream, UniformIsInUnitIntervalWithMeanHalf) {
  RandomStream stream(2024);
  const int n = 100000;
  double sum = 0.0, sumSquares = 0.0;
  std::vector<int> bins(10, 0);
  for (int i = 0; i < n; ++i) {
    const double u = stream.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    // 53 random bits: u is a whole multiple of 2^-53.
    const double scaled = std::ldexp(u, 53);
    ASSERT_EQ(scaled, std::floor(scaled));
    sum += u;
    sumSquares += u * u;
    ++bins[static_cast<size_t>(u * 10)];
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 0.5, 0.01);
  EXPECT_NEAR(sumSquares / n - mean * mean, 1.0 / 12.0, 0.005);
  for (int count : bins) EXPECT_NEAR(count, n / 10, 500);  // ~5 standard deviations
}

TEST(RandomStream, UniformUsesTheTop53Bits) {
  RandomStream stream(99), reference(99);
  for (int i = 0; i < 100; ++i) {
    EXPECT_EQ(stream.uniform(), static_cast<double>(reference.next() >> 11) * 0x1.0p-53);
  }
}

TEST(RandomStream, GaussianHasMeanZeroVarianceOne) {
  RandomStream stream(31337);
  const int n = 100000;
  double sum = 0.0, sumSquares = 0.0;
  int withinOneSigma = 0;
  for (int i = 0; i < n; ++i) {
    const double g = stream.gaussian();
    ASSERT_TRUE(std::isfinite(g));
    sum += g;
    sumSquares += g * g;
    if (std::fabs(g) < 1.0) ++withinOneSigma;
  }
  const double mean = sum / n;
  EXPECT_NEAR(mean, 0.0, 0.02);
  EXPECT_NEAR(sumSquares / n - mean * mean, 1.0, 0.02);
  EXPECT_NEAR(static_cast<double>(withinOneSigma) / n, 0.6827, 0.01);
}

TEST(RandomStream, GaussianUsesTwoUniformsAndNoSpare) {
  // Self-contained calls: each gaussian() consumes exactly two draws.
  RandomStream stream(8), reference(8);
  for (int i = 0; i < 10; ++i) {
    stream.gaussian();
    reference.next();
    reference.next();
    EXPECT_EQ(stream.next(), reference.next());
  }
}

TEST(RandomStream, StreamsFromNeighbouringKeysAreUncorrelated) {
  // Cells with consecutive ids get keys mixKey(seed, id); their first draws must look
  // independent of each other.
  const int n = 20000;
  double sumXY = 0.0, sumX = 0.0, sumY = 0.0, sumXX = 0.0, sumYY = 0.0;
  for (int id = 0; id < n; ++id) {
    RandomStream first(mixKey(1, static_cast<uint64_t>(id)));
    RandomStream second(mixKey(1, static_cast<uint64_t>(id) + 1));
    const double x = first.uniform(), y = second.uniform();
    sumX += x;
    sumY += y;
    sumXY += x * y;
    sumXX += x * x;
    sumYY += y * y;
  }
  const double covariance = sumXY / n - (sumX / n) * (sumY / n);
  const double varianceX = sumXX / n - (sumX / n) * (sumX / n);
  const double varianceY = sumYY / n - (sumY / n) * (sumY / n);
  EXPECT_NEAR(covariance / std::sqrt(varianceX * varianceY), 0.0, 0.03);
}

}  // namespace
}  // namespace ontogen
