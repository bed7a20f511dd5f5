// What a linear development holds between steps (LinearDevelopment::heldBytes, the
// world's held() and the memory limit): its compact words by what they have written, not
// by their size now, and
// what the compact rewrite keeps from one rewrite to the next (ParallelRewrite::heldBytes).

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/rewrite_plan.h"
#include "core/world.h"
#include "tests/core/test_support.h"

namespace ontogen {
namespace {

using testing_support::compileOrFail;

// R renews itself every step; G0 doubles through G15 into 65,536 D at t = 16, which are
// deleted at t = 17: the word is one module again, but the two words the development
// writes into, in turns, keep the pages of 65,536 modules and of 32,768.
std::string shrinkingProgram() {
  std::string text = "cell R { lifetime 1; rules { terminal: -> R; } }\n";
  for (int g = 0; g < 16; ++g)
    text += "cell G" + std::to_string(g) + " { lifetime 1; rules { terminal: -> " +
            (g < 15 ? "G" + std::to_string(g + 1) + " G" + std::to_string(g + 1) : std::string("D D")) + "; } }\n";
  return text + "cell D { lifetime 1; rules { terminal: -> ; } }\nsystem s { pool linear; axiom R G0; }\n";
}

TEST(HeldBytes, ACompactWordWrittenAfterALargerOneHoldsTheLargerOnesBytes) {
  WorldDef def;
  def.wordsWithoutIds = false;  // the pool's bytes are the word's alone
  World world(compileOrFail(shrinkingProgram()), def);
  world.advanceTo(15, 1);
  ASSERT_TRUE(world.rootPool().holdsCompactWord());
  const uint64_t before = world.rootPool().compactWord().bytes();
  world.advanceTo(16, 1);
  ASSERT_EQ(world.rootPool().size(), 65537u);
  const uint64_t largest = world.rootPool().compactWord().bytes();
  world.advanceTo(18, 1);
  ASSERT_EQ(world.rootPool().size(), 1u);
  ASSERT_TRUE(world.rootPool().holdsCompactWord());
  // Held: the word of t = 18, written where the word of t = 16 was, and the word of
  // t = 17, written where the word of t = 15 was.
  EXPECT_GE(world.held().bytes, World::kWorldBytes + largest + before);
}

// The parts of a word whose choices vary (the Parts strategy on two threads) are kept
// for the next rewrite: they hold the word's modules once more.
TEST(HeldBytes, ThePartsOfAWordWrittenInPartsAreHeld) {
  std::string signals;
  for (int i = 0; i < 6000; ++i) signals += " b a a a a a a";
  auto program = compileOrFail("lsystem d {\n  axiom" + signals +
                               "\n  b < a -> b : 0.9\n  b < a -> c : 0.1\n  b -> a\n  c -> a\n}\n");
  auto grown = [&](double until) {
    WorldDef def;
    def.threads = 2;
    def.testRewriteStrategy = RewriteStrategy::Parts;
    auto world = std::make_unique<World>(program, def);
    world->advanceTo(until, 1);
    return world;
  };
  const auto before = grown(11), world = grown(12);
  ASSERT_TRUE(world->rootPool().holdsCompactWord());
  ASSERT_GT(world->stats().rewrites[static_cast<size_t>(RewriteStrategy::Parts)], 0u);
  // The word, the word before (kept to write the next into; as the world grown to t = 11
  // holds it), both by what they have written, and, in the parts, a label a module at least.
  const uint64_t words = world->rootPool().compactWord().heldBytes() + before->rootPool().compactWord().heldBytes();
  EXPECT_GE(world->held().bytes, World::kWorldBytes + words + world->rootPool().size());
}

}  // namespace
}  // namespace ontogen
