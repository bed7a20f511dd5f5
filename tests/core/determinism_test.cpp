// Determinism pinned (Box2D's test_determinism): a hash of the whole world (ids, labels,
// birth times and state bits, nested pools included) after developing each kind of pool,
// on 1, 2 and 7 threads and stopping at 1 or 7 frames on the way, must be one constant
// per model. A change that moves any bit of any development fails here; if the change
// is meant, the constants are updated in the same commit, saying why.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <string>

#include "core/world.h"
#include "test_support.h"

namespace ontogen {
namespace {

// FNV-1a, 64 bits, over the bytes of each value.
struct Hash {
  uint64_t value = 0xcbf29ce484222325ull;
  void add(uint64_t word) {
    for (int byte = 0; byte < 8; ++byte) {
      value ^= (word >> (8 * byte)) & 0xff;
      value *= 0x100000001b3ull;
    }
  }
  void add(double number) { add(std::bit_cast<uint64_t>(number)); }
  void add(const std::string& text) {
    add(static_cast<uint64_t>(text.size()));
    for (char c : text) add(static_cast<uint64_t>(static_cast<unsigned char>(c)));
  }
};

void hashWorld(const World& world, Hash& hash) {
  const Pool& pool = world.rootPool();
  hash.add(static_cast<uint64_t>(pool.size()));
  for (size_t i = 0; i < pool.size(); ++i) {
    const CellRecord& cell = pool.cells()[i];
    const MasterCell& master = world.program().masters[cell.master];
    hash.add(cell.id);
    hash.add(master.label);
    hash.add(cell.birth);
    const double* state = pool.stateOf(cell);
    for (uint32_t k = 0; k < master.stateCount(); ++k) hash.add(state[k]);
    for (double coordinate : world.positionOf(i)) hash.add(coordinate);
    if (const World* child = world.childOf(cell)) hashWorld(*child, hash);
  }
}

struct Case {
  const char* name;
  std::string text;  ///< the program
  double until;      ///< seconds
  double step;       ///< seconds
  uint64_t expected;
};

// A grid with `rate` and actions: a diffusing substance, and cells that divide into free
// neighbouring sites with a probability, or die.
const char* kGridWithRatesAndActions = R"(
cell C(u = 0) {
  rules {
    rate(u) = 0.2 * (sum(u) - count() * u) - 0.05 * u;
    u > 0.05 && count() < 4 : -> me C(u / 2) : 0.3;
    age > 6 && u < 0.02 : -> ;
  }
}
system plate { pool grid(24, 24) closed vonneumann; at(12, 12) C(1); at(3, 5) C(0.5); }
)";

// Large enough (781,249 modules at t = 8) for the context-free pass on several threads.
const char* kKoch = R"(lsystem koch {
  axiom F
  F -> F + F - F - F + F
})";

std::vector<Case> cases() {
  using testing_support::readModel;
  return {
      {"piston: timed linear", readModel("piston.cell"), 12.37, 0.1, 0x4448a2d17afc9cdeull},
      {"markov_melody: stochastic linear", readModel("markov_melody.cell"), 30, 1, 0xc22114fcfc8db98eull},
      {"heterocysts: linear with rate and stochastic division", readModel("heterocysts.cell"), 30, 0.1, 0xbd684537a782cc0eull},
      {"grid with rate and actions", kGridWithRatesAndActions, 20, 0.25, 0xad51dde22eefe0d0ull},
      {"colony: spatial", readModel("colony.cell"), 20, 0.1, 0xef470aea37d9c7b1ull},
      {"orchard: nested systems", readModel("orchard.cell"), 8, 0.1, 0xcb9b8bcee7ff1a6cull},
      {"koch: a large context-free word", kKoch, 8, 1, 0x3aa7a9ac08c47be6ull},
  };
}

uint64_t developAndHash(const std::shared_ptr<const Program>& program, double until, double step, unsigned threads,
                        int frames) {
  WorldDef def;
  def.seed = 7;
  def.threads = threads;
  World world(program, def);
  for (int frame = 1; frame <= frames; ++frame) world.advanceTo(until * frame / frames, step);
  Hash hash;
  hash.add(world.time());
  hashWorld(world, hash);
  return hash.value;
}

TEST(Determinism, OneHashPerModelWhateverTheThreadsAndFrames) {
  for (const Case& test : cases()) {
    auto program = testing_support::compileOrFail(test.text, test.name);
    ASSERT_NE(program, nullptr) << test.name;
    const uint64_t reference = developAndHash(program, test.until, test.step, 1, 1);
    for (unsigned threads : {1u, 2u, 7u})
      for (int frames : {1, 7})
        EXPECT_EQ(developAndHash(program, test.until, test.step, threads, frames), reference)
            << test.name << " on " << threads << " threads, " << frames << " frames";
    EXPECT_EQ(reference, test.expected) << test.name << ": the development changed (hash 0x" << std::hex
                                        << reference << ")";
  }
}

}  // namespace
}  // namespace ontogen
