// The articulated creature (models/creature.cell) at 64 segments, 10 s at 30 frames a
// second, exported to a skinned .glb as `ontogen run --format glb` does it, against the
// same walk written by hand: the same poses (closed-form gait, two-bone legs, the body's
// wave) computed in loops over arrays and written by the same glTF writer.

#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <glm/geometric.hpp>

#include "bench/bench_support.h"
#include "interpreters/creature/gait.h"
#include "interpreters/creature/two_bone_ik.h"
#include "interpreters/formats/skinned_glb_writer.h"
#include "interpreters/geometry/gc_mesher.h"
#include "interpreters/run.h"

namespace ontogen::bench {
namespace {

namespace fs = std::filesystem;
constexpr int kSegments = 64, kFrames = 301;
constexpr double kUntil = 10;

void BM_CreatureExport(benchmark::State& state) {
  static const Compiled compiled = [] {
    Compiled model = compileModel("creature.cell");
    if (!model.program) return model;
    DiagnosticSink sink;
    CompileOptions options;
    options.commandSets = commandSets();
    options.defines = {{"SEGMENTS", static_cast<double>(kSegments)}};
    std::ifstream in(std::string(ONTOGEN_SOURCE_DIR) + "/models/creature.cell");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto program = compileSource("models/creature.cell", text, sink, options);
    return Compiled{std::move(program), formatDiagnostics(sink)};
  }();
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  const fs::path out = fs::temp_directory_path() / "ontogen_creature_bench";
  for (auto _ : state) {
    RunDef def;
    def.program = compiled.program;
    def.stem = "creature";
    def.from = 0;
    def.until = kUntil;
    def.frames = kFrames;
    def.sets = {"creature"};
    def.setOptions.formats = "glb";
    def.out = out;
    Run run(std::move(def));
    const RunReport report = run.execute();
    if (!report.ok() || fs::file_size(out / "creature.glb") < 1000000) {
      state.SkipWithError("the export failed");
      return;
    }
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(kFrames), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_CreatureExport)->Unit(benchmark::kMillisecond);

// The same creature by hand: a root, per segment a bend and two legs of hip, knee, foot.
void BM_CreatureExportHandWritten(benchmark::State& state) {
  constexpr double period = 1.2, duty = 0.5, stride = 0.55, lift = 0.3, height = 0.75;
  constexpr double segment = 1.1, upper = 0.95, lower = 1.15, reach = 1.25, sway = 5 * std::numbers::pi / 180;
  const GaitDef gait{.period = period, .duty = duty, .stride = stride, .lift = lift, .height = height};
  const glm::dvec3 forward(1, 0, 0), up(0, 1, 0);
  const fs::path out = fs::temp_directory_path() / "ontogen_creature_bench" / "hand_written.glb";
  fs::create_directories(out.parent_path());
  const Mesh limb = meshGeneralizedCylinder(std::array<GcControlPoint, 3>{
      GcControlPoint{glm::dvec3(0.0), {0, 1, 0}, 0.1, nullptr}, GcControlPoint{{0.5, 0, 0}, {0, 1, 0}, 0.12, nullptr},
      GcControlPoint{{1, 0, 0}, {0, 1, 0}, 0.08, nullptr}});
  auto rotation = [](const glm::dvec3& axis, double a) {
    const double c = std::cos(a), s = std::sin(a);
    const glm::dvec3 u = glm::normalize(axis);
    return glm::dmat3(c + u.x * u.x * (1 - c), u.y * u.x * (1 - c) + u.z * s, u.z * u.x * (1 - c) - u.y * s,
                      u.x * u.y * (1 - c) - u.z * s, c + u.y * u.y * (1 - c), u.z * u.y * (1 - c) + u.x * s,
                      u.x * u.z * (1 - c) + u.y * s, u.y * u.z * (1 - c) - u.x * s, c + u.z * u.z * (1 - c));
  };
  for (auto _ : state) {
    SkinnedGlbWriter writer;
    Scene scene;
    for (int f = 0; f < kFrames; ++f) {
      const double t = kUntil * f / (kFrames - 1);
      scene.clear();
      scene.time = t;
      auto& joints = scene.skeleton.joints;
      const glm::dvec3 root = glm::dvec3(gait.speed() * t, height, 0);
      const glm::dmat3 rootFrame(forward, glm::cross(up, forward), up);
      joints.push_back({1, -1, "root", root, rootFrame, false, BodySide::None, -1});
      glm::dmat3 frame = glm::dmat3(-rootFrame[0], -rootFrame[1], rootFrame[2]);  // tailward
      glm::dvec3 at = root;
      int parent = 0;
      for (int m = 0; m < kSegments; ++m) {
        auto heading = [&](int k) { return sway * std::cos(2 * std::numbers::pi * (t / period - k / 4.0)); };
        frame = rotation(frame[2], heading(m) - (m > 0 ? heading(m - 1) : 0)) * frame;
        const int bend = static_cast<int>(joints.size());
        joints.push_back({uint64_t(10 + m), parent, "bend", at, frame, false, BodySide::None, m});
        const glm::dvec3 hip = at + segment / 2 * frame[0];
        const glm::dvec3 restHip = root - (m * segment + segment / 2) * forward;
        for (int side = 0; side < 2; ++side) {
          const glm::dvec3 outward = side == 0 ? rootFrame[1] : -rootFrame[1];  // left, right
          const glm::dvec3 neutral = restHip + reach * outward - height * up;
          const glm::dvec3 foot = footPosition(gait, m * duty + side / 2.0, lift, t, neutral, forward, up);
          const TwoBoneLeg leg = solveTwoBone(hip, foot, upper, lower, up);
          const glm::dvec3 knee = hip + upper * leg.upperDirection;
          const glm::dmat3 hipFrame(leg.upperDirection, glm::cross(leg.kneeSide, leg.upperDirection), leg.kneeSide);
          const int h = static_cast<int>(joints.size());
          const BodySide s = side == 0 ? BodySide::Left : BodySide::Right;
          joints.push_back({uint64_t(1000 + 4 * m + side), bend, "hip", hip, hipFrame, false, s, m});
          joints.push_back({uint64_t(5000 + 4 * m + side), h, "knee", knee,
                            glm::dmat3(leg.lowerDirection, hipFrame[1], glm::cross(leg.lowerDirection, hipFrame[1])),
                            false, s, m});
          joints.push_back({uint64_t(9000 + 4 * m + side), h + 1, "foot", knee + lower * leg.lowerDirection,
                            joints.back().orientation, true, s, m});
        }
        at += segment * frame[0];
        parent = bend;
      }
      if (f == 0) {
        // The limbs of the bind pose: one per joint but the root and feet.
        for (std::size_t j = 1; j < joints.size(); ++j) {
          if (joints[j].foot) continue;
          Mesh placed = limb;
          for (glm::dvec3& v : placed.positions) v = joints[j].position + joints[j].orientation * v;
          for (glm::dvec3& n : placed.normals) n = joints[j].orientation * n;
          const auto first = static_cast<uint32_t>(scene.geometry.triangleCount());
          scene.geometry.addMesh(placed);
          scene.skeleton.skin.push_back(
              {first, static_cast<uint32_t>(scene.geometry.triangleCount()) - first, static_cast<int>(j)});
        }
      }
      writer.addFrame(scene);
    }
    std::ofstream file(out, std::ios::binary);
    writer.write(file);
    if (!file) {
      state.SkipWithError("cannot write");
      return;
    }
  }
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(kFrames), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_CreatureExportHandWritten)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ontogen::bench
