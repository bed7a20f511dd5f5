// The dynamics set on models/creature.cell (SEGMENTS 6 and 64): ten simulated seconds of
// walking under physics, against MuJoCo alone stepping the model the set writes
// (`--format mjcf`) for as many steps, its servos held at the first frame's targets. The
// difference is ontogen's coupling: the word's development, the kinematic gait replayed
// on the control grid for the servos' targets, the wind, the contacts and measures read
// back, the model's builds. MuJoCo alone holds its servos at the first frame's targets: the
// body stands where the set's walks, so its contacts differ.
// The counter sim_s/s is simulated seconds per second of the process's processor time.

#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include <mujoco/mujoco.h>

#include "bench/bench_support.h"
#include "interpreters/dynamics/dynamics_set.h"
#include "interpreters/dynamics/mujoco_model.h"
#include "interpreters/run.h"

namespace ontogen::bench {
namespace {

namespace fs = std::filesystem;

constexpr double kPeriod = 1.2;   // the gait's period: the runs start after its first cycle
constexpr double kGrown = 1;      // when models/creature.cell's body appears and its simulation starts
constexpr double kUntil = kPeriod + 10;
constexpr double kSimulated = kUntil - kGrown;  // seconds simulated by each run

// One run of the set from the end of the first cycle to 10 s later (the simulation starts
// when the body appears), two frames, the given formats.
RunReport runCreature(const Compiled& compiled, const std::string& formats, const fs::path& out,
                      int* rebuilds = nullptr) {
  RunDef def;
  def.program = compiled.program;
  def.stem = "creature";
  def.frames = 2;
  def.from = kPeriod;
  def.until = kUntil;
  def.world = kBenchWorld;
  def.world.threads = 1;
  def.sets = {"dynamics"};
  def.setOptions.formats = formats;
  def.out = out;
  Run run(std::move(def));
  const DynamicsSet* dynamics = nullptr;
  for (const auto& set : run.sets())
    if (const auto* found = dynamic_cast<const DynamicsSet*>(set.get())) dynamics = found;
  RunReport report = run.execute();
  if (rebuilds && dynamics) *rebuilds = dynamics->stats().rebuilds;
  return report;
}

Compiled compiledCreature(int segments) {
  return compileModel("creature.cell", {{"SEGMENTS", static_cast<double>(segments)}});
}

void BM_DynamicsCreature(benchmark::State& state) {
  const int segments = static_cast<int>(state.range(0));
  const Compiled compiled = compiledCreature(segments);
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  const fs::path out = fs::temp_directory_path() / ("ontogen_dynamics_bench_" + std::to_string(segments));
  int rebuilds = 0;
  for (auto _ : state) {
    const RunReport report = runCreature(compiled, "joints", out, &rebuilds);
    if (!report.ok()) {
      const std::string message =
          "the run failed: " + (report.diagnostics.empty() ? std::string() : report.diagnostics[0].message);
      state.SkipWithError(message.c_str());
      break;
    }
  }
  state.counters["sim_s/s"] = benchmark::Counter(kSimulated, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["rebuilds"] = rebuilds;
}
BENCHMARK(BM_DynamicsCreature)->Arg(6)->Arg(64)->Unit(benchmark::kMillisecond);

// The same creature's model at the first frame, written by the set and stepped by MuJoCo
// alone from its keyframe for as many steps as the run's simulation takes.
void BM_MujocoAlone(benchmark::State& state) {
  const int segments = static_cast<int>(state.range(0));
  const Compiled compiled = compiledCreature(segments);
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  const fs::path out = fs::temp_directory_path() / ("ontogen_dynamics_bench_mjcf_" + std::to_string(segments));
  fs::remove_all(out);
  if (!runCreature(compiled, "mjcf", out).ok()) {
    state.SkipWithError("the run that writes the MJCF failed");
    return;
  }
  std::ifstream in(out / "creature.xml", std::ios::binary);
  std::ostringstream mjcf;
  mjcf << in.rdbuf();
  MujocoModel model(mjcf.str());
  const long steps = std::lround(kSimulated / model.model()->opt.timestep);
  for (auto _ : state) {
    mj_resetDataKeyframe(model.model(), model.data(), 0);
    mj_forward(model.model(), model.data());
    for (long n = 0; n < steps; ++n) model.step();
    benchmark::DoNotOptimize(model.data()->qpos[0]);
  }
  if (!std::isfinite(model.data()->qpos[1])) state.SkipWithError("MuJoCo's state is not finite");
  state.counters["sim_s/s"] = benchmark::Counter(kSimulated, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_MujocoAlone)->Arg(6)->Arg(64)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ontogen::bench
