// Geometry back ends: generalized-cylinder meshing (triangles per second), the piston
// animated through the geometry set with the run's default outputs kept in memory
// (frames per second), and the software renderer.

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <sstream>
#include <vector>

#include "bench/bench_support.h"
#include "core/world.h"
#include "interpreters/formats/glb_writer.h"
#include "interpreters/formats/renderer.h"
#include "interpreters/geometry/gc_mesher.h"
#include "interpreters/geometry/geometry_set.h"
#include "interpreters/interpret.h"

namespace ontogen::bench {
namespace {

// A helix of control points: every span bends, so the frames do real work.
std::vector<GcControlPoint> helix(int count) {
  std::vector<GcControlPoint> points;
  for (int i = 0; i < count; ++i) {
    double a = i * 0.3;
    points.push_back({{3 * std::cos(a), 0.4 * i, 3 * std::sin(a)}, {-1, 0, 0}, 0.5 + 0.3 * std::sin(i * 0.1), nullptr});
  }
  return points;
}

// Tubes of 1000 control points at 12 points per ring and 8 rings per span: 192 k
// triangles per tube.
void BM_GcMeshing(benchmark::State& state) {
  const std::vector<GcControlPoint> points = helix(static_cast<int>(state.range(0)));
  std::size_t triangles = 0;
  for (auto _ : state) {
    Mesh mesh = meshGeneralizedCylinder(points);
    triangles += mesh.triangles.size();
    benchmark::DoNotOptimize(mesh.positions.data());
  }
  if (triangles == 0) state.SkipWithError("no triangles");
  state.counters["triangles/s"] = benchmark::Counter(static_cast<double>(triangles), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_GcMeshing)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

// The animated piston as `ontogen run --frames 200` does it per frame: develop to the
// frame's time, interpret, render the picture (400 x 400) and add the frame to the .glb,
// all in memory.
void BM_PistonAnimationFrame(benchmark::State& state) {
  static const Compiled compiled = compileModel("piston.cell");
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  const bool picture = state.range(0) != 0;
  GeometrySetDef def;
  def.output.writeSvg = def.output.writeObj = false;
  def.turtle.radians = true;
  def.sceneNodes = true;  // as a run writing a .glb records them
  GeometrySet set(def);
  GlbAnimationWriter glb;
  RenderDef render;
  render.width = render.height = 400;
  World world(compiled.program, kBenchWorld);
  double t = 0;
  for (auto _ : state) {
    t += 0.04;
    world.advanceTo(t, 0.04);
    FrameTarget target;
    target.time = t;
    set.beginFrame(target);
    interpretWord(world, set);
    // An animation of 200 frames is what a run makes; without a bound, repetitions of
    // this loop held every frame (20 GB at --benchmark_repetitions=3).
    if (glb.frameCount() == 200) glb.clear();
    glb.addFrame(set.scene());
    if (picture) benchmark::DoNotOptimize(renderGeometry(set.geometry(), render).rgb.data());
  }
  std::ostringstream out;
  glb.write(out);
  if (out.str().size() < 100) state.SkipWithError("empty glb");
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PistonAnimationFrame)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace ontogen::bench
