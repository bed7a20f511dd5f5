#include "model/noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <thread>
#include <vector>

#include "model/random.h"

namespace ontogen {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Point {
  double x, y, z;
};

// Points spread over several cells, negative coordinates included.
std::vector<Point> samplePoints(int count, uint64_t key, double extent = 20.0) {
  RandomStream random(key);
  std::vector<Point> points;
  for (int i = 0; i < count; ++i) {
    points.push_back({extent * (2.0 * random.uniform() - 1.0),
                      extent * (2.0 * random.uniform() - 1.0),
                      extent * (2.0 * random.uniform() - 1.0)});
  }
  return points;
}

TEST(SmoothNoise, IsDeterministicPerSeed) {
  for (const Point& p : samplePoints(1000, 1)) {
    EXPECT_EQ(smoothNoise(p.x, p.y, p.z, 42), smoothNoise(p.x, p.y, p.z, 42));
  }
}

TEST(SmoothNoise, SurvivesOtherSeedsInBetween) {
  // The per-thread cache holds a few tables: using more seeds than it holds, then the
  // first seed again, must give the first values back.
  const std::vector<Point> points = samplePoints(50, 2);
  std::vector<double> before;
  for (const Point& p : points) before.push_back(smoothNoise(p.x, p.y, p.z, 1));
  for (uint64_t seed = 2; seed < 10; ++seed) smoothNoise(0.5, 0.5, 0.5, seed);
  for (size_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(smoothNoise(points[i].x, points[i].y, points[i].z, 1), before[i]);
    // Alternating seeds call by call.
    smoothNoise(0.5, 0.5, 0.5, 1000 + i);
  }
}

TEST(SmoothNoise, DiffersBetweenSeeds) {
  int differing = 0, total = 0;
  for (const Point& p : samplePoints(1000, 3)) {
    ++total;
    if (std::fabs(smoothNoise(p.x, p.y, p.z, 1) - smoothNoise(p.x, p.y, p.z, 2)) > 1e-6) {
      ++differing;
    }
  }
  EXPECT_GT(differing, total * 95 / 100);
  // Neighbouring seeds, and seeds differing in high bits only.
  EXPECT_NE(smoothNoise(0.5, 0.5, 0.5, 0), smoothNoise(0.5, 0.5, 0.5, 1));
  EXPECT_NE(smoothNoise(0.5, 0.5, 0.5, 0), smoothNoise(0.5, 0.5, 0.5, uint64_t{1} << 63));
}

TEST(SmoothNoise, IsZeroAtLatticePoints) {
  for (uint64_t seed : {0ull, 1ull, 12345ull}) {
    for (int x = -5; x <= 5; ++x) {
      for (int y = -5; y <= 5; ++y) {
        for (int z = -5; z <= 5; ++z) {
          EXPECT_EQ(smoothNoise(x, y, z, seed), 0.0) << x << " " << y << " " << z;
        }
      }
    }
    EXPECT_EQ(smoothNoise(1e6, -3e7, 255.0, seed), 0.0);
    EXPECT_EQ(smoothNoise(std::ldexp(1.0, 40), 256.0, -257.0, seed), 0.0);
  }
}

TEST(SmoothNoise, IsBoundedAndNotFlat) {
  double lowest = kInf, highest = -kInf, sumSquares = 0.0;
  const std::vector<Point> points = samplePoints(200000, 4, 100.0);
  for (uint64_t seed : {7ull, 8ull}) {
    for (const Point& p : points) {
      const double value = smoothNoise(p.x, p.y, p.z, seed);
      ASSERT_TRUE(std::isfinite(value));
      lowest = std::min(lowest, value);
      highest = std::max(highest, value);
      sumSquares += value * value;
    }
  }
  EXPECT_GE(lowest, -1.1);
  EXPECT_LE(highest, 1.1);
  // It uses a good part of its range.
  EXPECT_LT(lowest, -0.5);
  EXPECT_GT(highest, 0.5);
  const double rms = std::sqrt(sumSquares / (2.0 * static_cast<double>(points.size())));
  EXPECT_GT(rms, 0.1);
  EXPECT_LT(rms, 0.6);
}

TEST(SmoothNoise, HasMeanNearZero) {
  double sum = 0.0;
  const std::vector<Point> points = samplePoints(100000, 5, 100.0);
  for (const Point& p : points) sum += smoothNoise(p.x, p.y, p.z, 9);
  EXPECT_NEAR(sum / static_cast<double>(points.size()), 0.0, 0.02);
}

TEST(SmoothNoise, IsContinuous) {
  // A small step gives a proportionally small change: the gradient is bounded.
  const double h = 1e-6;
  for (const Point& p : samplePoints(5000, 6)) {
    const double value = smoothNoise(p.x, p.y, p.z, 3);
    EXPECT_NEAR(smoothNoise(p.x + h, p.y, p.z, 3), value, 10 * h);
    EXPECT_NEAR(smoothNoise(p.x, p.y + h, p.z, 3), value, 10 * h);
    EXPECT_NEAR(smoothNoise(p.x, p.y, p.z + h, 3), value, 10 * h);
  }
}

TEST(SmoothNoise, IsContinuousAcrossCellFaces) {
  const double h = 1e-9;
  for (const Point& p : samplePoints(500, 7)) {
    const double face = std::round(p.x);
    EXPECT_NEAR(smoothNoise(face - h, p.y, p.z, 3), smoothNoise(face + h, p.y, p.z, 3), 1e-7);
    const double faceZ = std::round(p.z);
    EXPECT_NEAR(smoothNoise(p.x, p.y, faceZ - h, 3), smoothNoise(p.x, p.y, faceZ + h, 3), 1e-7);
  }
}

TEST(SmoothNoise, SlopeIsContinuousAcrossCellFaces) {
  // The quintic fade makes the noise smooth, not just continuous: one-sided slopes
  // on either side of a cell face agree.
  const double h = 1e-5;
  for (const Point& p : samplePoints(500, 8)) {
    const double face = std::round(p.y);
    const double below = (smoothNoise(p.x, face, p.z, 5) - smoothNoise(p.x, face - h, p.z, 5)) / h;
    const double above = (smoothNoise(p.x, face + h, p.z, 5) - smoothNoise(p.x, face, p.z, 5)) / h;
    EXPECT_NEAR(below, above, 1e-3);
  }
}

TEST(SmoothNoise, OneDimensionalSliceVariesInEveryCell) {
  // noise(x) is the slice y = z = 0. No unit interval along it may be flat.
  for (uint64_t seed : {1ull, 2ull, 3ull}) {
    for (int cell = -32; cell < 32; ++cell) {
      double largest = 0.0;
      for (double f = 0.05; f < 1.0; f += 0.05) {
        largest = std::max(largest, std::fabs(smoothNoise(cell + f, 0.0, 0.0, seed)));
      }
      EXPECT_GT(largest, 1e-3) << "seed " << seed << " cell " << cell;
    }
  }
}

TEST(SmoothNoise, RepeatsEvery256Units) {
  for (const Point& p : samplePoints(200, 9)) {
    const double value = smoothNoise(p.x, p.y, p.z, 4);
    EXPECT_NEAR(smoothNoise(p.x + 256.0, p.y, p.z, 4), value, 1e-9);
    EXPECT_NEAR(smoothNoise(p.x, p.y - 256.0, p.z, 4), value, 1e-9);
    EXPECT_NEAR(smoothNoise(p.x, p.y, p.z + 512.0, 4), value, 1e-9);
  }
}

TEST(SmoothNoise, HugeCoordinatesAreFinite) {
  for (double x : {1e12, -1e12, 1e18 + 0.5, -1e300, 1e300}) {
    EXPECT_TRUE(std::isfinite(smoothNoise(x, 0.25, 0.75, 1))) << x;
    EXPECT_TRUE(std::isfinite(smoothNoise(0.25, x, 0.75, 1))) << x;
  }
  EXPECT_TRUE(std::isfinite(smoothNoise(1e6 + 0.3, -2e6 + 0.7, 3e6 + 0.1, 1)));
}

TEST(SmoothNoise, NonFiniteCoordinatesGiveNaN) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(smoothNoise(nan, 0.5, 0.5, 1)));
  EXPECT_TRUE(std::isnan(smoothNoise(0.5, kInf, 0.5, 1)));
  EXPECT_TRUE(std::isnan(smoothNoise(0.5, 0.5, -kInf, 1)));
}

TEST(SmoothNoise, ThreadsWithDifferentSeedsDoNotInterfere) {
  const std::vector<Point> points = samplePoints(2000, 10);
  const int threadCount = 8;
  // Expected values, computed on this thread.
  std::vector<std::vector<double>> expected(threadCount);
  for (int t = 0; t < threadCount; ++t) {
    const uint64_t seed = static_cast<uint64_t>(t % 3);  // shared and distinct seeds
    for (const Point& p : points) expected[t].push_back(smoothNoise(p.x, p.y, p.z, seed));
  }
  std::vector<std::vector<double>> actual(threadCount);
  std::vector<std::thread> threads;
  for (int t = 0; t < threadCount; ++t) {
    threads.emplace_back([&, t] {
      const uint64_t seed = static_cast<uint64_t>(t % 3);
      for (int round = 0; round < 5; ++round) {
        actual[t].clear();
        for (const Point& p : points) {
          actual[t].push_back(smoothNoise(p.x, p.y, p.z, seed));
          smoothNoise(p.x, p.y, p.z, seed + 100 + static_cast<uint64_t>(round));  // churn
        }
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < threadCount; ++t) EXPECT_EQ(actual[t], expected[t]) << "thread " << t;
}

}  // namespace
}  // namespace ontogen
