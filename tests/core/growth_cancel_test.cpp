// Cooperative cancellation (WorldLimits::cancel, core/limits.h): a world stops growing
// with GrowthCancelled at the next step, within a long step as its events happen, and a
// Run reports it as Interrupted, keeping the world as it was when it stopped.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <limits>
#include <thread>

#include "core/world.h"
#include "interpreters/run.h"
#include "tests/core/test_support.h"

namespace ontogen {
namespace {

using testing_support::compileOrFail;

TEST(GrowthCancel, ASetFlagStopsTheGrowthBeforeItsNextStep) {
  auto program = compileOrFail("cell A { rules { -> A; } }\nsystem s { pool linear; axiom A; }");
  std::atomic<bool> cancel{false};
  WorldDef def;
  def.limits.cancel = &cancel;
  World world(program, def);
  world.advanceTo(3, 1);
  EXPECT_EQ(world.stats().steps, 3u);
  cancel = true;
  EXPECT_THROW(world.advanceTo(10, 1), GrowthCancelled);
  EXPECT_THROW(world.step(1), GrowthCancelled);
  EXPECT_EQ(world.stats().steps, 3u);
  EXPECT_DOUBLE_EQ(world.time(), 3);
}

// One step of a cell that renews itself every nanosecond holds a billion events (minutes
// of work, past no limit): the flag set by another thread stops it within the step.
TEST(GrowthCancel, AnotherThreadStopsALongStepAsItsEventsHappen) {
  auto program = compileOrFail("cell A { lifetime 1e-9; rules { terminal: -> A; } }\nsystem s { pool linear; axiom A; }");
  std::atomic<bool> cancel{false};
  WorldDef def;
  def.limits.cancel = &cancel;
  def.limits.maxEventsPerStep = std::numeric_limits<uint64_t>::max();
  World world(program, def);
  std::atomic<bool> growing{false};
  std::thread stopper([&] {
    while (!growing) std::this_thread::yield();
    // Most likely within the step by then; were it before, the step's start stops it.
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    cancel = true;
  });
  growing = true;
  EXPECT_THROW(world.advanceTo(1, 1), GrowthCancelled);
  stopper.join();
  EXPECT_EQ(world.stats().steps, 0u);
}

// Nothing but the flag differs from a run that grows to its end: cancelled after the
// third of six frames, the run is Interrupted at that frame's time, with a note.
TEST(GrowthCancel, ARunStoppedThroughTheFlagIsInterrupted) {
  auto program = compileOrFail("#until 5\ncell A { rules { -> A A; } }\nsystem s { pool linear; axiom A; }");
  std::atomic<bool> cancel{false};
  RunDef def;
  def.program = program;
  def.world.limits.cancel = &cancel;
  def.frames = 6;
  def.sets = {"trace"};
  def.out = ::testing::TempDir() + "growth_cancel_run";
  int frames = 0;
  def.frameGrown = [&](const World& world) {
    if (++frames == 3) {
      EXPECT_DOUBLE_EQ(world.time(), 2);
      cancel = true;
    }
  };
  ontogen::Run run(std::move(def));
  const RunReport report = run.execute();
  EXPECT_EQ(report.status, RunStatus::Interrupted);
  ASSERT_EQ(report.diagnostics.size(), 1u);
  EXPECT_EQ(report.diagnostics[0].severity, Severity::Note);
  EXPECT_EQ(report.diagnostics[0].message, "the growth was cancelled");
  EXPECT_EQ(frames, 3);
  EXPECT_DOUBLE_EQ(report.time, 2);
  EXPECT_EQ(report.cells, 4u);
}

}  // namespace
}  // namespace ontogen
