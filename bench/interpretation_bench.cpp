// Interpretation per frame: what an animation pays after developing, for each frame.
// The geometry set draws into memory between beginFrame and interpretWord; endFrame,
// which writes the SVG and OBJ files, is left out so the figures do not measure a disk.

#include <benchmark/benchmark.h>

#include <memory>
#include <string>

#include "bench/bench_support.h"
#include "core/word.h"
#include "core/world.h"
#include "interpreters/interpret.h"
#include "interpreters/set_registry.h"

namespace ontogen::bench {
namespace {

constexpr double kPistonFrameTime = 5.0;  // seconds: the mechanism is built and moving
constexpr double kPistonStep = 0.04;      // seconds, the model's #dt

// One frame of the piston: the turtle walks its 12 modules through the development
// functions into cylinders, a disc and lines.
void BM_PistonInterpretFrame(benchmark::State& state) {
  static const Compiled compiled = compileModel("piston.cell");
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  World world(compiled.program, kBenchWorld);
  world.advanceTo(kPistonFrameTime, kPistonStep);
  std::unique_ptr<InterpretationSet> set = makeInterpretationSet("geometry", compiled.program->rootSystem().settings);
  for (auto _ : state) {
    set->beginFrame(FrameTarget{});
    interpretWord(world, *set);
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PistonInterpretFrame)->Unit(benchmark::kMicrosecond);

// The word as data (labels, parameters, developed values), as `ontogen word` prints it.
void BM_PistonCaptureWord(benchmark::State& state) {
  static const Compiled compiled = compileModel("piston.cell");
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  World world(compiled.program, kBenchWorld);
  world.advanceTo(kPistonFrameTime, kPistonStep);
  for (auto _ : state) {
    std::vector<WordCell> word = captureWord(world);
    benchmark::DoNotOptimize(word.data());
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PistonCaptureWord)->Unit(benchmark::kMicrosecond);

// An animation frame as `ontogen run` makes it: one step of development, then the turtle.
void BM_PistonStepAndInterpret(benchmark::State& state) {
  static const Compiled compiled = compileModel("piston.cell");
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  World world(compiled.program, kBenchWorld);
  world.advanceTo(kPistonFrameTime, kPistonStep);
  std::unique_ptr<InterpretationSet> set = makeInterpretationSet("geometry", compiled.program->rootSystem().settings);
  for (auto _ : state) {
    world.step(kPistonStep);
    set->beginFrame(FrameTarget{});
    interpretWord(world, *set);
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PistonStepAndInterpret)->Unit(benchmark::kMicrosecond);

// The turtle over a large word: Koch's curve at generation 7 (156,249 modules, 78,125
// segments), modules interpreted per second.
void BM_KochInterpret(benchmark::State& state) {
  static const Compiled compiled = compileModel("koch.cell");
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  const int n = static_cast<int>(state.range(0));
  World world(compiled.program, kBenchWorld);
  world.advanceTo(n, 1.0);
  std::unique_ptr<InterpretationSet> set = makeInterpretationSet("geometry", compiled.program->rootSystem().settings);
  for (auto _ : state) {
    set->beginFrame(FrameTarget{});
    interpretWord(world, *set);
  }
  const double modules = static_cast<double>(world.rootPool().size());
  state.counters["modules"] = modules;
  state.counters["modules/s"] =
      benchmark::Counter(modules * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_KochInterpret)->Arg(7)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ontogen::bench
