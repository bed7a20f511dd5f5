// The growth limits (core/limits.h): checked as cells are made within a step, across
// nested systems, for steps and for the time itself; the default memory limit is sized
// from the machine.

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
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
// counts every pool of the world, as each grows, and the word before each pool's last
// step, which its development keeps to write the next word into.
TEST(Limits, MemoryCountsEveryNestedPoolTogether) {
  std::string axiom;
  for (int i = 0; i < 64; ++i) axiom += " S";
  auto program = compileOrFail("system top { pool linear; axiom" + axiom +
                               "; }\nsystem S { pool linear; axiom A; }\n"
                               "cell A { rules { -> A A; } }\n");
  WorldDef def;
  def.limits.maxMemoryBytes = 1 << 20;
  def.rewriteBySlices = false;  // words of records, 24 bytes a cell
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
  // 65 worlds of 12 KiB leave 244 KiB of the MiB to the cells: after step k the 64 pools
  // hold 2^k cells and the 2^(k-1) of the word before, 2304 · 2^k bytes, which passes it
  // at k = 7 (294,912 bytes). The words alone (1536 · 2^k) would not before k = 8.
  EXPECT_EQ(stopped, 7);
}

// A nested world holds its word and the word before its last step, kept to write the
// next one into; both count, in held() and against the memory limit. Eight nested
// systems whose words double peaked at 137 MB under --max-memory 100 while only the
// words counted.
TEST(Limits, NestedWorldsCountThePreviousWordTheyKeep) {
  WorldDef def;
  def.rewriteBySlices = false;  // words of records, 24 bytes a cell and 8 a value
  World world(compileOrFail("system top { pool linear; axiom S; }\nsystem S { pool linear; axiom A; }\n"
                            "cell A(x = 0) { rules { -> A(x + 1) A(x); } }\n"),
              def);
  world.advanceTo(10, 1);
  const World* nested = world.childOf(world.rootPool().cellAt(0).id);
  ASSERT_NE(nested, nullptr);
  EXPECT_EQ(nested->rootPool().size(), 1024u);
  // 1024 cells of one value, and the 512 of the word before.
  EXPECT_EQ(nested->held().bytes, World::kWorldBytes + (1024 + 512) * (sizeof(CellRecord) + sizeof(double)));
  // The top world's word of one system cell is rewritten each step too: it and the word
  // before.
  EXPECT_EQ(world.held().bytes, World::kWorldBytes + 2 * sizeof(CellRecord) + nested->held().bytes);
}

// A cell whose successors expire within the same step develops depth first on a work
// list, whose values grow by the whole chain; the list is kept, emptied, for the next
// step, and counts in held() (it did not: the world held its word and the one before).
// A(x) lives 1/1024 s: a step of 1 s makes 1024 generations, 1024 values on the list.
TEST(Limits, AChainWithinAStepCountsTheWorkListItKeeps) {
  WorldDef def;
  def.rewriteBySlices = false;  // words of records, 24 bytes a cell and 8 a value
  World world(compileOrFail("cell A(x = 0) { lifetime 0.0009765625; rules { terminal: -> A(x + 1); } }\n"
                            "system s { pool linear; axiom A; }\n"),
              def);
  world.advanceTo(1, 1);
  ASSERT_EQ(world.rootPool().size(), 1u);
  EXPECT_EQ(world.rootPool().cellAt(0).state[0], 1024);
  // The word and the one before: a cell of one value each.
  const uint64_t words = World::kWorldBytes + 2 * (sizeof(CellRecord) + sizeof(double));
  // The list's 1024 values (grown by doubling, to 1024 exactly), the one cell waiting on
  // it, and the one cell and value each expansion wrote.
  const uint64_t scratch = 1024 * sizeof(double) + sizeof(CellRecord) + (sizeof(CellRecord) + sizeof(double));
  EXPECT_EQ(world.held().bytes, words + scratch);
}

// A world that integrates rates and stops between two grid instants keeps a copy of
// itself as it was at the last one (the next advance starts from there): its bytes count
// in held(), and so against the memory limit, but not its cells.
TEST(Limits, TheCopyKeptAtTheLastGridInstantIsHeld) {
  World world(compileOrFail("cell A(x = 1) { rules { rate(x) = -x; } }\nsystem s { pool linear; axiom A A A; }\n"));
  const WorldHeld alone = world.held();
  EXPECT_EQ(alone.bytes, World::kWorldBytes + 3 * (sizeof(CellRecord) + sizeof(double)));
  world.advanceTo(2, 1);
  EXPECT_EQ(world.held().bytes, alone.bytes);
  world.advanceTo(2.5, 1);  // between the instants 2 and 3
  EXPECT_EQ(world.held().cells, 3u);
  EXPECT_EQ(world.held().bytes, 2 * alone.bytes);
}

// Systems nested `depth` levels, each holding two of the next; the last holds a cell
// without rules. 2^depth - 1 worlds.
std::string nestedSystems(int depth) {
  std::string text;
  for (int i = 0; i + 1 < depth; ++i)
    text += "system s" + std::to_string(i) + " { pool linear; axiom s" + std::to_string(i + 1) + " s" +
            std::to_string(i + 1) + "; }\n";
  return text + "system s" + std::to_string(depth - 1) + " { pool linear; axiom A; }\ncell A { }\n";
}

// What a world holds counts every world of the tree, not only their cells: 1023 worlds
// hold 1534 cells (two system cells in each of 511 worlds, a cell in each of 512).
TEST(Limits, NestedWorldsAreHeldWithTheirCells) {
  World world(compileOrFail(nestedSystems(10)));
  const WorldHeld held = world.held();
  EXPECT_EQ(held.cells, 1534u);
  EXPECT_EQ(held.bytes, 1023 * World::kWorldBytes + 1534 * sizeof(CellRecord));
  world.advanceTo(2, 1);
  EXPECT_EQ(world.totalCells(), 1534u);
  EXPECT_EQ(world.held().bytes, held.bytes);
}

// 4095 worlds of a cell or two: 48 MiB, which passes 16 MiB while the worlds are made,
// and 1000 cells after the first few hundred worlds.
TEST(Limits, NestedWorldsStopAtTheLimitsAsTheyAreMade) {
  auto program = compileOrFail(nestedSystems(12));
  WorldDef def;
  def.limits.maxMemoryBytes = 16 << 20;
  try {
    World world(program, def);
    FAIL() << "4095 worlds made within 16 MiB";
  } catch (const LimitError& error) {
    EXPECT_NE(std::string(error.what()).find("passed 16 MiB, the memory limit; raise it with --max-memory"),
              std::string::npos)
        << error.what();
  }
  def = WorldDef{};
  def.limits.maxCells = 1000;
  try {
    World world(program, def);
    FAIL() << "6142 cells made within the limit of 1000";
  } catch (const LimitError& error) {
    EXPECT_NE(std::string(error.what()).find("past 1000 cells in all its systems"), std::string::npos) << error.what();
  }
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

TEST(Limits, TheDefaultMemoryLimitIsHalfTheLeastBound) {
  EXPECT_EQ(defaultMemoryLimitBytes(), defaultMemoryLimitBytes(readMemoryBounds()));
  EXPECT_EQ(WorldLimits{}.maxMemoryBytes, defaultMemoryLimitBytes());
  const uint64_t gib = uint64_t{1} << 30;
  EXPECT_EQ(defaultMemoryLimitBytes(MemoryBounds{.physical = 16 * gib}), 8 * gib);
  // Each bound, the least of them taken; 0 is no bound.
  EXPECT_EQ(defaultMemoryLimitBytes(MemoryBounds{.physical = 16 * gib, .controlGroupV2 = 2 * gib}), gib);
  EXPECT_EQ(defaultMemoryLimitBytes(MemoryBounds{.physical = 16 * gib, .controlGroupV1 = gib}), gib / 2);
  EXPECT_EQ(defaultMemoryLimitBytes(MemoryBounds{.physical = 16 * gib, .addressSpace = 600 * (uint64_t{1} << 20)}),
            300 * (uint64_t{1} << 20));
  EXPECT_EQ(defaultMemoryLimitBytes(
                MemoryBounds{.physical = 16 * gib, .controlGroupV2 = 4 * gib, .controlGroupV1 = 3 * gib, .addressSpace = 5 * gib}),
            3 * gib / 2);
  EXPECT_EQ(defaultMemoryLimitBytes(MemoryBounds{}), 8 * gib);  // nothing says
  EXPECT_EQ(defaultMemoryLimitBytes(MemoryBounds{.addressSpace = 1000}), uint64_t{1} << 20);
}

// A folder standing for `/`: /proc/self/cgroup and the control groups' files.
class FakeRoot {
 public:
  explicit FakeRoot(const std::string& name) : root_(std::filesystem::temp_directory_path() /
                                                     ("ontogen_limits_" + name + "_" + std::to_string(getpid()))) {
    std::filesystem::remove_all(root_);
  }
  ~FakeRoot() { std::filesystem::remove_all(root_); }
  void write(const std::string& path, const std::string& text) const {
    const std::filesystem::path file = root_ / path;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file) << text;
  }
  std::string path() const { return root_.string(); }

 private:
  std::filesystem::path root_;
};

TEST(Limits, ControlGroupV2IsReadFromTheProcesssGroupAndItsAncestors) {
  FakeRoot root("v2");
  EXPECT_EQ(readControlGroupV2Bytes(root.path()), 0u);  // no cgroup at all
  root.write("proc/self/cgroup", "0::/user.slice/job\n");
  root.write("sys/fs/cgroup/memory.max", "max\n");
  EXPECT_EQ(readControlGroupV2Bytes(root.path()), 0u);
  root.write("sys/fs/cgroup/user.slice/job/memory.max", "1073741824\n");
  EXPECT_EQ(readControlGroupV2Bytes(root.path()), 1073741824u);
  root.write("sys/fs/cgroup/user.slice/memory.max", "536870912\n");  // a parent's limit binds too
  EXPECT_EQ(readControlGroupV2Bytes(root.path()), 536870912u);
  // A v1 memory line is not v2's.
  EXPECT_EQ(readControlGroupV1Bytes(root.path()), 0u);
}

TEST(Limits, ControlGroupV2OfAContainerIsItsMountsOwnFile) {
  FakeRoot root("v2_container");
  // The group's path is not under the container's mount: its own group is the mount.
  root.write("proc/self/cgroup", "0::/kubepods/pod1/abc\n");
  root.write("sys/fs/cgroup/memory.max", "2147483648\n");
  EXPECT_EQ(readControlGroupV2Bytes(root.path()), 2147483648u);
}

TEST(Limits, ControlGroupV1IsReadAndItsUnlimitedIsNoLimit) {
  FakeRoot root("v1");
  root.write("proc/self/cgroup", "9:name=systemd:/\n5:cpu,memory:/docker/abc\n3:cpuset:/\n0::/\n");
  root.write("sys/fs/cgroup/memory/memory.limit_in_bytes", "9223372036854771712\n");
  EXPECT_EQ(readControlGroupV1Bytes(root.path()), 0u);
  root.write("sys/fs/cgroup/memory/docker/abc/memory.limit_in_bytes", "1073741824\n");
  EXPECT_EQ(readControlGroupV1Bytes(root.path()), 1073741824u);
  EXPECT_EQ(readControlGroupV2Bytes(root.path()), 0u);
  // The container sees its group as the mount's root (the path above does not exist there).
  FakeRoot container("v1_container");
  container.write("proc/self/cgroup", "4:memory:/process_api/0ccd\n0::/\n");
  container.write("sys/fs/cgroup/memory/memory.limit_in_bytes", "1073741824\n");
  EXPECT_EQ(readControlGroupV1Bytes(container.path()), 1073741824u);
  const MemoryBounds bounds = readMemoryBounds(container.path());
  EXPECT_EQ(bounds.controlGroupV1, 1073741824u);
  EXPECT_EQ(defaultMemoryLimitBytes(bounds), 536870912u);  // the machine has more than 1 GiB
}

TEST(Limits, ControlGroupFilesThatSayNothingAreNoLimit) {
  FakeRoot root("junk");
  root.write("proc/self/cgroup", "0::/a\n4:memory:/a\n");
  root.write("sys/fs/cgroup/a/memory.max", "lots\n");
  root.write("sys/fs/cgroup/memory/a/memory.limit_in_bytes", "-1\n");
  root.write("sys/fs/cgroup/memory.max", "99999999999999999999999\n");
  EXPECT_EQ(readControlGroupV2Bytes(root.path()), 0u);
  EXPECT_EQ(readControlGroupV1Bytes(root.path()), 0u);
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
