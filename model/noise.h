#pragma once
// Smooth gradient noise for the language's `noise(x, y, z)`. This is Perlin's classic
// 3-D gradient noise: a random unit gradient sits on every integer lattice point, a
// point's value blends the eight surrounding gradients' ramps with a quintic fade, so
// the noise is C2-continuous and exactly 0 on the lattice. The lattice hash is a
// permutation of 0..255 shuffled from the run's seed, so the pattern repeats every 256
// units along each axis and changes completely with the seed.

#include <cstdint>

namespace ontogen {

/// Gradient noise at (x, y, z) for a seed: roughly in [-1, 1] (about [-0.85, 0.85] in
/// practice), 0 at integer points, smooth everywhere; NaN if a coordinate is not finite. Safe to
/// call from several threads at once; the tables built from a seed are cached per
/// thread, so runs with different seeds never see each other's tables.
double smoothNoise(double x, double y, double z, uint64_t seed);

}  // namespace ontogen
