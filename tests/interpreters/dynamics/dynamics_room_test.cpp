// The dynamics set's room for MuJoCo's contacts, its solver's settings and the steps
// MuJoCo finds unstable: a raft of hinged limbs on, in and above the ground.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <mujoco/mujoco.h>

#include "interpreters/dynamics/dynamics_set.h"
#include "interpreters/run.h"
#include "interpreters/sweep/measure.h"
#include "interpreters/sweep/variant_run.h"
#include "tests/interpreters/dynamics/dynamics_walk.h"

namespace ontogen {
namespace {

using namespace dynamics_testing;

// A raft of 12 limbs of radius 0.1 joined by hinges, held with its joints at `height`
// (0.1: lying on the ground).
std::string raftOf(double height) {
  std::string raft = "#interpret dynamics\nsystem raft { pool linear; axiom Raft; }\n"
                     "cell Raft { interpret dynamics { gait(1, 0.5, 0, 0, " +
                     std::to_string(height) + ") limb(0.3, 0.1)";
  for (int i = 1; i < 12; ++i) raft += " hinge(0) limb(0.3, 0.1)";
  return raft + " } }\n";
}

// solver(iterations, tolerance) reaches the MJCF's <option> and MuJoCo's model read from
// it; without it the MJCF says MuJoCo's defaults (100, 1e-8). solver(0), solver(2.5) and
// solver(10, 1) are ignored and named as bad arguments, located at the first.
TEST(DynamicsSet, TheSolversIterationsAndToleranceReachMujoco) {
  auto run = [](const std::string& solver) {
    WalkDef w;
    w.model = "solver.cell";
    w.text = raftOf(0.1);
    w.text.replace(w.text.find("gait("), 0, solver + " ");
    w.until = 0.1;
    w.frames = 2;
    w.formats = "mjcf";
    return walk(w);
  };
  auto option = [](const Walk& w, int& iterations, double& tolerance) {
    const fs::path path = w.dir / "solver.xml";
    char error[1000] = "";
    mjModel* m = mj_loadXML(path.string().c_str(), nullptr, error, sizeof error);
    ASSERT_NE(m, nullptr) << error;
    iterations = m->opt.iterations;
    tolerance = m->opt.tolerance;
    mj_deleteModel(m);
  };
  int iterations = 0;
  double tolerance = 0;
  const Walk set = run("solver(37, 2.5e-5)");
  EXPECT_NE(bytesOf(set.dir / "solver.xml").find(" iterations=\"37\" tolerance=\"2.5000000000000001e-05\""),
            std::string::npos);
  option(set, iterations, tolerance);
  EXPECT_EQ(iterations, 37);
  EXPECT_EQ(tolerance, 2.5e-5);
  const Walk fewer = run("solver(3)");
  option(fewer, iterations, tolerance);
  EXPECT_EQ(iterations, 3);
  EXPECT_EQ(tolerance, 1e-8);
  const Walk plain = run("");
  EXPECT_NE(bytesOf(plain.dir / "solver.xml").find(" iterations=\"100\" tolerance=\"1e-08\""), std::string::npos);
  option(plain, iterations, tolerance);
  EXPECT_EQ(iterations, 100);
  EXPECT_EQ(tolerance, 1e-8);
  const Walk bad = run("solver(0) solver(2.5) solver(10, 1)");
  option(bad, iterations, tolerance);
  EXPECT_EQ(iterations, 100);
  EXPECT_EQ(tolerance, 1e-8);
  int named = 0;
  for (const RunDiagnostic& d : bad.report.diagnostics) {
    if (d.message.find("bad arguments") == std::string::npos) continue;
    ++named;
    EXPECT_EQ(d.count, 3u) << d.message;
    EXPECT_TRUE(d.span.valid()) << d.message;
  }
  EXPECT_EQ(named, 1);
}

// A raft of 12 limbs joined by hinges, lying on the ground: each capsule touches it at
// both ends, 24 contacts, more than the room a model starts with (one contact a limb).
// The steps that run out are taken again with twice the room, so no contact is dropped
// and no part of the raft sinks (MuJoCo's soft contact lets it in by less than 2 mm).
TEST(DynamicsSet, ABodyTouchingTheGroundEverywhereGetsTheRoomItsContactsNeed) {
  const std::string raft = raftOf(0.1);
  int growths = 0;
  WalkDef w;
  w.model = "raft.cell";
  w.text = raft;
  w.until = 2;
  w.frames = 5;
  w.onFrame = [&](const DynamicsSet& set, double) { growths = set.stats().roomGrowths; };
  const Walk lying = walk(w);
  ASSERT_EQ(lying.frames().size(), 5u);
  ASSERT_EQ(lying.joints().size(), 12u);
  EXPECT_GE(growths, 1);
  for (std::size_t f = 0; f < 5; ++f)
    for (std::size_t j = 0; j < 12; ++j) EXPECT_NEAR(lying.at(f, j).y, 0.1, 2e-3) << "frame " << f << ", joint " << j;
}

// The same raft set 1 cm into the ground: the model's first pose already has more
// contacts than its room (MuJoCo counts the overflow in its data), and the first step runs
// out too. The step is taken again with more room once or twice, not until MuJoCo cannot
// make its data (the overflow counted before the step is not this step's), the room never
// passes what the raft's limbs can touch (4 contacts a limb), and the raft rises onto the
// ground.
TEST(DynamicsSet, ABodyStartingInTheGroundGrowsTheRoomItNeedsOnly) {
  const std::string raft = raftOf(0.09);
  int growths = 0;
  WalkDef w;
  w.model = "sunk_raft.cell";
  w.text = raft;
  w.until = 1;
  w.frames = 3;
  w.onFrame = [&](const DynamicsSet& set, double) { growths = set.stats().roomGrowths; };
  const Walk sunk = walk(w);
  EXPECT_EQ(sunk.report.status, RunStatus::Ok);
  ASSERT_EQ(sunk.frames().size(), 3u);
  EXPECT_GE(growths, 1);
  EXPECT_LE(growths, 2);
  for (std::size_t j = 0; j < 12; ++j) EXPECT_NEAR(sunk.at(2, j).y, 0.1, 2e-3) << "joint " << j;
}

// The report of a run of `program` (stem `stem`) to 0.1 s under a memory limit of 512 KiB.
RunReport runUnderHalfAMebibyte(const std::string& program, const std::string& stem) {
  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  RunDef def;
  def.program = compileSource(stem + ".cell", program, sink, options);
  EXPECT_NE(def.program, nullptr) << formatDiagnostics(sink);
  def.stem = stem;
  def.frames = 2;
  def.until = 0.1;
  def.sets = {"dynamics"};
  def.setOptions.formats = "joints";
  def.world.limits.maxMemoryBytes = 512 << 10;
  def.out = fs::path(ONTOGEN_BINARY_DIR) / "dynamics_set_test" / (stem + "_limit");
  fs::remove_all(def.out);
  ontogen::Run run(std::move(def));
  return run.execute();
}

// MuJoCo's room for contacts counts against the memory limit before MuJoCo makes its
// data: the sunk raft's model starts with room for 16 contacts and 64 rows (190 KiB);
// under a limit of 512 KiB its first step, which asks for twice that (700 KiB), stops the
// run with a limit's message, not an allocation MuJoCo cannot make.
TEST(DynamicsSet, RoomForContactsPastTheMemoryLimitStopsAtTheLimit) {
  const RunReport report = runUnderHalfAMebibyte(raftOf(0.09), "sunk_raft");
  EXPECT_EQ(report.status, RunStatus::ModelFailed);
  ASSERT_EQ(report.diagnostics.size(), 1u);
  const std::string& message = report.diagnostics[0].message;
  EXPECT_NE(message.find("touched the ground at more than 16 points"), std::string::npos) << message;
  EXPECT_NE(message.find("room for 32 contacts and 128 constraint rows, about 1 MiB, past the memory limit"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("raise it with --max-memory MIB"), std::string::npos) << message;
  EXPECT_EQ(message.find("unstable"), std::string::npos) << message;
}

// The same sunk raft under a gravity past MuJoCo's bound on accelerations (1e10): its
// first step is reset as unstable and then runs out of room; the limit's message says so.
TEST(DynamicsSet, RoomPastTheLimitInAnUnstableRunSaysItWasUnstable) {
  std::string raft = raftOf(0.09);
  raft.replace(raft.find("gait("), 0, "gravity(1e11) ");
  const RunReport report = runUnderHalfAMebibyte(raft, "unstable_sunk_raft");
  EXPECT_EQ(report.status, RunStatus::ModelFailed);
  ASSERT_EQ(report.diagnostics.size(), 1u);
  const std::string& message = report.diagnostics[0].message;
  EXPECT_NE(message.find("at t = 0.002 s the dynamics set's body touched the ground at more than 16 points while its "
                         "simulation was unstable (MuJoCo reset it; a smaller #timestep or gentler servos may steady "
                         "it), and needs MuJoCo's room for 32 contacts"),
            std::string::npos)
      << message;
}

// Under a gravity of 1e11, past MuJoCo's bound of 1e10 on accelerations, every step of a
// hinged body in the air is unstable and reset: `unstable` counts the 50 steps of 0.1 s
// at 0.002 s, and the run warns once with that count. The walking creature counts none.
TEST(DynamicsSet, UnstableCountsTheStepsMujocoReset) {
  const std::string program = "#interpret dynamics\nsystem s { pool linear; axiom Body; }\n"
                              "cell Body { interpret dynamics { gravity(1e11) gait(1, 0.5, 0, 0, 1) limb(0.3, 0.1) "
                              "hinge(0) limb(0.3, 0.1) } }\n";
  VariantDef def;
  def.name = "models/unstable.cell";
  def.text = program;
  def.compile.commandSets = commandSets();
  def.run.sets = {"dynamics"};
  def.run.setOptions.formats = "joints";
  def.run.out = fs::path(ONTOGEN_BINARY_DIR) / "dynamics_set_test" / "unstable";
  def.run.until = 0.1;
  def.run.frames = 2;
  def.measures.push_back(parseMeasure("u=unstable"));
  const VariantResult result = runVariant(std::move(def));
  ASSERT_EQ(result.error, "");
  EXPECT_EQ(result.measures[0], 50);

  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  RunDef run;
  run.program = compileSource("unstable.cell", program, sink, options);
  ASSERT_NE(run.program, nullptr) << formatDiagnostics(sink);
  run.stem = "unstable";
  run.frames = 2;
  run.until = 0.1;
  run.sets = {"dynamics"};
  run.setOptions.formats = "joints";
  run.out = fs::path(ONTOGEN_BINARY_DIR) / "dynamics_set_test" / "unstable_run";
  fs::remove_all(run.out);
  const RunReport report = ontogen::Run(std::move(run)).execute();
  int warned = 0;
  for (const RunDiagnostic& d : report.diagnostics) {
    if (d.message.find("unstable") == std::string::npos) continue;
    ++warned;
    EXPECT_EQ(d.message, "MuJoCo found the simulation unstable at 50 steps and reset it: a smaller #timestep or "
                         "weaker servos (the first here)");
    EXPECT_EQ(d.count, 50u);
    EXPECT_EQ(d.severity, Severity::Warning);
  }
  EXPECT_EQ(warned, 1);
}

}  // namespace
}  // namespace ontogen
