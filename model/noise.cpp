#include "model/noise.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <utility>

#include "model/random.h"

namespace ontogen {

namespace {

// The lattice period: Perlin's 256, small enough that the tables stay in L1 cache.
constexpr int kPeriod = 256;
// Keeps the noise tables' stream apart from any other stream built from the same seed.
constexpr uint64_t kNoiseSalt = 0x6E6F6973655F7631ull;  // "noise_v1"
// With unit gradients the value reaches sqrt(3)/2 at the centre of a cell whose eight
// gradients all point away from it, the known extreme of Perlin noise; this scale maps
// it to 1. Random gradients rarely come close: 2e7 samples stayed within 0.83.
constexpr double kScale = 1.1547005383792515;  // 2 / sqrt(3)
// Tables kept per thread: a run uses one seed, two lets two runs interleave on one thread
// (a comparison, a test) without rebuilding on every call.
constexpr int kCachedTables = 2;

struct NoiseTable {
  bool built = false;
  uint64_t seed = 0;
  // The permutation twice over, so that perm[perm[i] + j] needs no wrapping.
  std::array<uint8_t, 2 * kPeriod> perm{};
  std::array<std::array<double, 3>, kPeriod> gradients{};
};

void buildTable(NoiseTable& table, uint64_t seed) {
  RandomStream random(mixKey(seed, kNoiseSalt));
  std::array<int, kPeriod> order;
  std::iota(order.begin(), order.end(), 0);
  // Fisher-Yates; the index is a multiply-shift of 32 random bits (Lemire), whose bias
  // (under 2^-24 for 256 buckets) is far below anything a model could notice.
  for (int i = kPeriod - 1; i > 0; --i) {
    const uint64_t bound = static_cast<uint64_t>(i) + 1;
    const int j = static_cast<int>(((random.next() >> 32) * bound) >> 32);
    std::swap(order[static_cast<size_t>(i)], order[static_cast<size_t>(j)]);
  }
  for (size_t i = 0; i < static_cast<size_t>(kPeriod); ++i) {
    table.perm[i] = static_cast<uint8_t>(order[i]);
    table.perm[i + kPeriod] = static_cast<uint8_t>(order[i]);
  }
  // Unit vectors uniform on the sphere by rejection from the cube: only +, * and sqrt,
  // which IEEE arithmetic rounds the same everywhere, so a seed gives the same tables
  // on every platform. The lower bound avoids amplifying rounding in tiny vectors.
  for (auto& gradient : table.gradients) {
    double gx = 0.0, gy = 0.0, gz = 0.0, length2 = 0.0;
    do {
      gx = 2.0 * random.uniform() - 1.0;
      gy = 2.0 * random.uniform() - 1.0;
      gz = 2.0 * random.uniform() - 1.0;
      length2 = gx * gx + gy * gy + gz * gz;
    } while (length2 > 1.0 || length2 < 1e-4);
    const double inverse = 1.0 / std::sqrt(length2);
    gradient = {gx * inverse, gy * inverse, gz * inverse};
  }
  table.seed = seed;
  table.built = true;
}

const NoiseTable& tableFor(uint64_t seed) {
  // Per thread: no locks, and nothing one thread does is visible to another.
  thread_local std::array<NoiseTable, kCachedTables> cache;
  thread_local int nextVictim = 0;
  for (const NoiseTable& table : cache) {
    if (table.built && table.seed == seed) return table;
  }
  NoiseTable& table = cache[static_cast<size_t>(nextVictim)];
  nextVictim = (nextVictim + 1) % kCachedTables;
  buildTable(table, seed);
  return table;
}

// The lattice cell of a coordinate modulo the period. fmod is exact, so this works for
// coordinates far beyond the range of an int.
size_t latticeIndex(double floored) {
  double wrapped = std::fmod(floored, static_cast<double>(kPeriod));
  if (wrapped < 0.0) wrapped += kPeriod;
  return static_cast<size_t>(wrapped);
}

// Perlin's quintic fade 6t^5 - 15t^4 + 10t^3: zero first and second derivatives at 0 and
// 1, so neighbouring cells join without creases.
double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

double lerp(double t, double a, double b) { return a + t * (b - a); }

double ramp(const NoiseTable& table, size_t hash, double dx, double dy, double dz) {
  const std::array<double, 3>& g = table.gradients[hash];
  return g[0] * dx + g[1] * dy + g[2] * dz;
}

}  // namespace

double smoothNoise(double x, double y, double z, uint64_t seed) {
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const NoiseTable& table = tableFor(seed);
  const double floorX = std::floor(x), floorY = std::floor(y), floorZ = std::floor(z);
  const size_t ix = latticeIndex(floorX), iy = latticeIndex(floorY), iz = latticeIndex(floorZ);
  const double fx = x - floorX, fy = y - floorY, fz = z - floorZ;
  const double u = fade(fx), v = fade(fy), w = fade(fz);

  const auto& p = table.perm;
  const size_t a = p[ix] + iy, b = p[ix + 1] + iy;
  const size_t aa = p[a] + iz, ab = p[a + 1] + iz, ba = p[b] + iz, bb = p[b + 1] + iz;

  const double nearZ =
      lerp(v, lerp(u, ramp(table, p[aa], fx, fy, fz), ramp(table, p[ba], fx - 1, fy, fz)),
           lerp(u, ramp(table, p[ab], fx, fy - 1, fz), ramp(table, p[bb], fx - 1, fy - 1, fz)));
  const double farZ = lerp(v,
                           lerp(u, ramp(table, p[aa + 1], fx, fy, fz - 1),
                                ramp(table, p[ba + 1], fx - 1, fy, fz - 1)),
                           lerp(u, ramp(table, p[ab + 1], fx, fy - 1, fz - 1),
                                ramp(table, p[bb + 1], fx - 1, fy - 1, fz - 1)));
  return kScale * lerp(w, nearZ, farZ);
}

}  // namespace ontogen
