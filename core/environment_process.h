#pragma once
// The channel from interpretation back to development: the environmental process of
// open L-systems (Měch & Prusinkiewicz 1996; cpfg's query modules, ABOP 1.10). After the
// world is seeded and after every step, the world hands its developed word to its
// environment process, which answers the word's query modules (`?P(x, y, z)` ...): it
// writes values into their parameters, and rules read them there in the next step.
//
// Core only declares the interface; an environment lives on the interpretation side (the
// turtle that answers ?P, ?H, ?L and ?U is interpreters/geometry/turtle_queries.h) and
// may grow into obstacles, attractors or light that answer other queries. It must answer
// deterministically: the same world gives the same answers, whatever the threads, so a
// run stays the same bytes for the same program and seed.

#include <array>
#include <cstdint>
#include <vector>

namespace ontogen {

class World;

/// What the environment writes into one query module: up to three values, in order, into
/// the parameters of cell `cell` of the world's root pool (fewer when it has fewer).
struct QueryAnswer {
  uint32_t cell = 0;
  std::array<double, 3> values{0, 0, 0};
};

/// The environment of a world (WorldDef::environment).
class EnvironmentProcess {
 public:
  virtual ~EnvironmentProcess() = default;
  /// Appends to `answers` the answers to the query modules of `world`'s root pool, as the
  /// world is now. Modules it has no answer for keep their values.
  virtual void respond(const World& world, std::vector<QueryAnswer>& answers) const = 0;
};

}  // namespace ontogen
