#pragma once
// The constants that keep ontogen's random streams and ids apart, in one place (the
// noise functions' own salt stays with them in model/noise.cpp, below core): every
// stochastic choice draws from a stream keyed by (seed ^ salt, cell id, instant), and
// changing one of these changes every stochastic model's output, so they never move.

#include <cstdint>

namespace ontogen {

/// Per-step rules draw apart from terminal (production) rules of the same cell at the
/// same instant, and per-step births get other ids than terminal births.
inline constexpr uint64_t kStepRuleSalt = 0x5354455052554c45ull;  // "STEPRULE"
/// Development functions draw apart from the cell's rule draws.
inline constexpr uint64_t kDevelopSalt = 0x444556454c4f50ull;  // "DEVELOP"
/// Values of grid placements (`fill A(gaussian(0, 1))`).
inline constexpr uint64_t kPlacementSalt = 0x504c414345ull;  // "PLACE"
/// Draws in `rate` expressions.
inline constexpr uint64_t kRateSalt = 0x52415445ull;  // "RATE"
/// Draws of interpretation blocks (interpreters/interpret.cpp).
inline constexpr uint64_t kInterpretSalt = 0x494e54455250ull;  // "INTERP"
/// Draws of decomposition rules (a module decomposes at the instant it was produced).
inline constexpr uint64_t kDecompositionSalt = 0x4445434f4d50ull;  // "DECOMP"
/// Draws of homomorphism rules and the ids of the image's modules (core/homomorphism.h).
inline constexpr uint64_t kHomomorphismSalt = 0x484f4d4f4dull;  // "HOMOM"
/// Ids of a world's axiom cells start from this, mixed with the system's index.
inline constexpr uint64_t kWorldIdSalt = 0x6f6e746f67656eull;  // "ontogen"

/// Ids are 64 bits inside the engine; rules read them (`id`), and words print them, as
/// their low 53 bits, which a double (and a JSON reader) holds exactly.
inline constexpr uint64_t kIdBits = (uint64_t{1} << 53) - 1;
inline constexpr double idValue(uint64_t id) { return static_cast<double>(id & kIdBits); }

}  // namespace ontogen
