// The growth limits (core/limits.h): checked as cells are made within a step, across
// nested systems, for steps and for the time itself; the default memory limit is sized
// from the machine.

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "core/world.h"
#include "tests/core/test_support.h"

namespace ontogen {
namespace {

using testing_support::compileOrFail;

std::string messageOf(World& world, double until, double dt) {
  try {
    world.advanceTo(until, dt);
  } catch (const LimitError& error) {
    return error.what();
  }
  return "";
}

// A cell that divides every microsecond doubles a million times within one step: the
// cells waiting to expire within the step count as they are made, so the step stops near
// the limit instead of holding a million cells (or, a nanosecond, running out of memory).
TEST(Limits, MemoryIsCheckedAsCellsAreMadeWithinAStep) {
  auto program = compileOrFail("cell A { lifetime 1e-6; rules { terminal: -> A A; } }\nsystem s { pool linear; axiom A; }");
  WorldDef def;
  def.limits.maxMemoryBytes = 1 << 20;
  World world(program, def);
  const std::string message = messageOf(world, 1, 1);
  EXPECT_NE(message.find("--max-memory"), std::string::npos) << message;
  // Well before a leaf of the million-deep expansion is reached.
  EXPECT_LT(world.stats().events, 100'000u);
}

TEST(Limits, CellsWithinAStepCountAgainstTheCellLimit) {
  auto program = compileOrFail("cell A { lifetime 1e-9; rules { terminal: -> A A; } }\nsystem s { pool linear; axiom A; }");
  WorldDef def;
  def.limits.maxCells = 1000;
  def.limits.maxMemoryBytes = 100 << 20;
  World world(program, def);
  const std::string message = messageOf(world, 1, 1);
  EXPECT_NE(message.find("past 1000 cells"), std::string::npos) << message;
  EXPECT_LT(world.stats().events, 2000u);
}

// 64 systems that each stay within the limit but together pass it: the memory limit
// counts every pool of the world, as each grows.
TEST(Limits, MemoryCountsEveryNestedPoolTogether) {
  std::string axiom;
  for (int i = 0; i < 64; ++i) axiom += " S";
  auto program = compileOrFail("system top { pool linear; axiom" + axiom +
                               "; }\nsystem S { pool linear; axiom A; }\n"
                               "cell A { rules { -> A A; } }\n");
  WorldDef def;
  def.limits.maxMemoryBytes = 1 << 20;
  World world(program, def);
  double stopped = 0;
  try {
    for (double t = 1; t <= 30; ++t) {
      stopped = t;
      world.advanceTo(t, 1);
    }
  } catch (const LimitError& error) {
    EXPECT_NE(std::string(error.what()).find("--max-memory"), std::string::npos) << error.what();
  }
  // 64 pools of 2^k cells of 24 bytes, held twice, pass 1 MiB at k = 9; one pool alone
  // not before k = 15.
  EXPECT_GE(stopped, 8);
  EXPECT_LE(stopped, 11);
}

// The meter of a parallel step stops it as it passes the limit, and whether it stops does
// not depend on the number of threads.
TEST(Limits, ParallelStepsStopAtTheSameLimitOnAnyNumberOfThreads) {
  auto program = compileOrFail("system d { pool spatial(1); axiom A(0, 0, 0); }\n"
                               "cell A(x = 0, y = 0, z = 0) { rules { -> A(x + 1, y, z) A(x, y + 1, z) A(x, y, z + 1); } }\n");
  for (unsigned threads : {1u, 4u}) {
    WorldDef def;
    def.threads = threads;
    def.limits.maxCells = 50'000;
    World world(program, def);
    double stopped = 0;
    try {
      for (double t = 1; t <= 20; ++t) {
        stopped = t;
        world.advanceTo(t, 1);
      }
    } catch (const LimitError& error) {
      EXPECT_NE(std::string(error.what()).find("past 50000 cells"), std::string::npos) << error.what();
    }
    EXPECT_EQ(stopped, 10) << threads << " threads";  // 3^9 = 19683 cells, 3^10 = 59049
  }
}

TEST(Limits, AStepFarTooSmallStopsAtOnceWithTheStepLimitNamed) {
  auto program = compileOrFail("lsystem a { axiom A\n A -> A\n }");
  for (double dt : {1e-12, 1e-320}) {
    World world(program);
    const std::string message = messageOf(world, 10, dt);
    EXPECT_NE(message.find("--max-steps"), std::string::npos) << message;
    EXPECT_NE(message.find("step limit of 100000000"), std::string::npos) << message;
    EXPECT_EQ(world.stats().steps, 0u);
  }
  World far(program);
  EXPECT_NE(messageOf(far, 1e308, 1).find("--max-steps"), std::string::npos);
}

TEST(Limits, TheStepLimitCountsEveryStepOfTheWorld) {
  auto program = compileOrFail("lsystem a { axiom A\n A -> A\n }");
  WorldDef def;
  def.limits.maxSteps = 25;
  World world(program, def);
  EXPECT_EQ(messageOf(world, 20, 1), "");
  EXPECT_NE(messageOf(world, 30, 1).find("step limit of 25"), std::string::npos);
  EXPECT_EQ(world.stats().steps, 20u);  // stopped before the first step past it
  world.step(1);
  world.step(1);
  world.step(1);
  world.step(1);
  world.step(1);
  EXPECT_THROW(world.step(1), LimitError);
}

uint64_t expectedDefaultLimit() {
  uint64_t memory = static_cast<uint64_t>(sysconf(_SC_PHYS_PAGES)) * static_cast<uint64_t>(sysconf(_SC_PAGE_SIZE));
  std::ifstream group("/sys/fs/cgroup/memory.max");
  if (uint64_t bytes = 0; group >> bytes && bytes < memory) memory = bytes;
  return memory / 2;
}

TEST(Limits, TheDefaultMemoryLimitIsHalfTheMachine) {
  EXPECT_EQ(defaultMemoryLimitBytes(), expectedDefaultLimit());
  EXPECT_EQ(WorldLimits{}.maxMemoryBytes, defaultMemoryLimitBytes());
}

TEST(Limits, OutsideMemoryNamesWhatNeedsIt) {
  WorldLimits limits;
  limits.maxMemoryBytes = 100 << 20;
  EXPECT_NO_THROW(checkOutsideMemory("a picture", 60 << 20, 30 << 20, limits));
  try {
    checkOutsideMemory("a 8192x8192 picture", 1744830464, 0, limits);
    FAIL();
  } catch (const LimitError& error) {
    EXPECT_STREQ(error.what(),
                 "a 8192x8192 picture needs about 1664 MiB, past the memory limit of 100 MiB; raise it with "
                 "--max-memory MIB");
  }
  EXPECT_THROW(checkOutsideMemory("a picture", 60 << 20, 50 << 20, limits), LimitError);
}

}  // namespace
}  // namespace ontogen
