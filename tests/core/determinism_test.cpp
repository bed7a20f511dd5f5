// Determinism pinned (Box2D's test_determinism): a hash of the whole world (ids, labels,
// birth times and state bits, nested pools included) after developing each kind of pool,
// on 1, 2 and 7 threads and stopping at 1 or 7 frames on the way, must be one constant
// per model. A change that moves any bit of any development fails here; if the change
// is meant, the constants are updated in the same commit, saying why.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/parents.h"
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
  // Through the cursor: a linear pool may hold records or a compact word.
  for (CellCursor cell = pool.cursor(); !cell.done(); cell.next()) {
    const MasterCell& master = world.program().masters[cell.master()];
    hash.add(cell.id());
    hash.add(master.label);
    hash.add(cell.birth());
    const double* state = cell.state();
    for (uint32_t k = 0; k < master.stateCount(); ++k) hash.add(state[k]);
    for (double coordinate : world.positionOf(cell.index())) hash.add(coordinate);
    if (const World* child = world.childOf(cell.id())) hashWorld(*child, hash);
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
      {"heterocysts: linear with rate and stochastic division", readModel("heterocysts.cell"), 30, 0.1,
       0xbd684537a782cc0eull},
      {"grid with rate and actions", kGridWithRatesAndActions, 20, 0.25, 0xad51dde22eefe0d0ull},
      {"colony: spatial", readModel("colony.cell"), 20, 0.1, 0xef470aea37d9c7b1ull},
      {"orchard: nested systems", readModel("orchard.cell"), 8, 0.1, 0xcb9b8bcee7ff1a6cull},
      {"koch: a large context-free word", kKoch, 8, 1, 0x3aa7a9ac08c47be6ull},
  };
}

// `withParents`: each cell's parent id (core/parents.h) is hashed after the world.
uint64_t developAndHash(const std::shared_ptr<const Program>& program, double until, double step, unsigned threads,
                        int frames, bool withParents) {
  WorldDef def;
  def.seed = 7;
  def.threads = threads;
  World world(program, def);
  for (int frame = 1; frame <= frames; ++frame) world.advanceTo(until * frame / frames, step);
  Hash hash;
  hash.add(world.time());
  hashWorld(world, hash);
  if (withParents)
    for (uint64_t parent : parentIds(world)) hash.add(parent);
  return hash.value;
}

void expectOneHashEach(const std::vector<Case>& tests, bool withParents) {
  for (const Case& test : tests) {
    auto program = testing_support::compileOrFail(test.text, test.name);
    ASSERT_NE(program, nullptr) << test.name;
    const uint64_t reference = developAndHash(program, test.until, test.step, 1, 1, withParents);
    for (unsigned threads : {1u, 2u, 7u})
      for (int frames : {1, 7})
        EXPECT_EQ(developAndHash(program, test.until, test.step, threads, frames, withParents), reference)
            << test.name << " on " << threads << " threads, " << frames << " frames";
    EXPECT_EQ(reference, test.expected) << test.name << ": the development changed (hash 0x" << std::hex << reference
                                        << ")";
  }
}

TEST(Determinism, OneHashPerModelWhateverTheThreadsAndFrames) {
  expectOneHashEach(cases(), false);
}

// ---- Every kind of successor, pinned by value before the linear pool's storage moves
// (docs/COMPACT_WORDS.md, section 7, slice 0). The seven cases above leave some of what a
// compact word must reproduce unpinned: parents, `me` in per-step rules, birth ages, `<<`,
// rules of more than 254 successors (once the largest k a compact run held), and the words
// the rewriting by slices writes with state. These hash each cell's parent id as well.

// Repeats `label` `count` times, separated by spaces.
std::string repeated(const std::string& label, int count) {
  std::string text;
  for (int i = 0; i < count; ++i) text += (i ? " " : "") + label;
  return text;
}

// Cells: `me` in a terminal rule (new birth) and in a per-step rule (same birth), `=X`
// with a draw keyed by the kept id, birth ages in the axiom and in successors, renewals
// (C has no rules) and a rule of 300 successors, whose k passes 254 (once the largest k a
// compact run held).
std::string cellsWithEveryKindOfSuccessor() {
  return "cell A(x = 1) { lifetime 2; rules { terminal: x += 1, -> (B(x), 0.5) me; } }\n"
         "cell B(y = 0) { lifetime 1.5; rules {\n"
         "  age > 0.5 && y < 5 : y += 1, -> me C(y);\n"
         "  terminal: -> =D(y + uniform(0, 1)) (C(-y), 0.25);\n"
         "} }\n"
         "cell C(c = 0) { lifetime 1; }\n"
         "cell D(d = 0) { lifetime 3; rules { terminal: -> W; } }\n"
         "cell W { lifetime 1; rules { terminal: -> " +
         repeated("w", 300) +
         "; } }\n"
         "cell w { }\n"
         "system s { pool linear; axiom A (C(2), 0.5); }\n";
}

// An L-system: timed predecessors, birth ages, branches, `=X` with a draw, a renewal (C's
// only production never holds), the new left context `<<` (E takes the value of the C
// produced before it) and a production of 300 successors whose last keeps growing.
std::string lsystemWithEveryKindOfSuccessor() {
  return "lsystem pin {\n"
         "  axiom A(1) [ (B(0), 0.5) ] S (W, 0.25)\n"
         "  (A(x), 2) -> A(x + 1) [ (B(x / 2), 0.25) ] A(x)\n"
         "  B(y) -> =C(y + uniform(0, 1)) D\n"
         "  (C(z), 1.5) : z > 100 -> C(0)\n"
         "  C(z) << D -> E(z)\n"
         "  D -> D\n"
         "  (E(v), 0.75) -> E(v + uniform(0, 1))\n"
         "  W -> " +
         repeated("w", 299) +
         " W\n"
         "}\n";
}

// A backward derivation (`>>`): a signal runs left through the successors in one step,
// passing over the branch, and falls back into A B where it has counted past 4.
const char* kNewRightContext = R"(lsystem back {
  axiom A A B A A A A S(1) A A [ A A ] A A S(2)
  A >> S(x) -> S(x + 1)
  S(x) : x > 4 -> A B(x)
  B(x) -> A
})";

std::vector<Case> everyKindOfSuccessor() {
  return {
      {"cells: me, =X, birth ages, renewals, 300 successors", cellsWithEveryKindOfSuccessor(), 12, 0.1,
       0x1dc04f3b5ff179aeull},
      {"lsystem: <<, =X, birth ages, a renewal, 300 successors", lsystemWithEveryKindOfSuccessor(), 9.5, 0.25,
       0xc837e298712c69b5ull},
      {"lsystem: >>", kNewRightContext, 5, 1, 0xf267d64fe8592bbdull},
      // The benchmarks' words, large enough (2^16 modules) for the rewriting by slices:
      // labels only on every thread count, state on 2 and 7 threads.
      {"thue-morse: labels only, by slices", testing_support::kThueMorse, 16, 1, 0xf68faf44005972b4ull},
      {"parametric: state, by slices", testing_support::kParametric, 16, 1, 0xa5a69aa5a1c4ae85ull},
  };
}

TEST(Determinism, EveryKindOfSuccessorHasOneHashWithItsParents) {
  expectOneHashEach(everyKindOfSuccessor(), true);
}

}  // namespace
}  // namespace ontogen
