// A plant's default output against its OBJ: ABOP Fig. 1.24 (d) (tests/convert/fig1_24d.cell)
// grown to n = 12 (1,054,690 segments) and written by a whole run, one frame, on one
// thread, as `ontogen run --format obj` and `--format glb` (the still merged mesh,
// interpreters/formats/still_glb.h) do, into a temporary folder; beside them the same
// plant derived, walked by a turtle and written as an OBJ by hand. The goal: the
// .glb within 3 times the OBJ path. Compare the CPU column (user and system, the kernel
// zeroing fresh pages included) within one run of the program.

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "bench/bench_support.h"
#include "interpreters/run.h"

namespace ontogen::bench {
namespace {

namespace fs = std::filesystem;

constexpr int kGenerations = 12;

const Compiled& fig124d() {
  static const Compiled compiled = [] {
    const std::string path = std::string(ONTOGEN_SOURCE_DIR) + "/tests/convert/fig1_24d.cell";
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return compileText(path, text.str());
  }();
  return compiled;
}

fs::path benchFolder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("ontogen_still_glb_bench_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Arg 0: obj, 1: glb.
void BM_Fig124dRun(benchmark::State& state) {
  const Compiled& compiled = fig124d();
  if (!compiled.program) {
    state.SkipWithError(compiled.error.c_str());
    return;
  }
  const std::string format = state.range(0) == 0 ? "obj" : "glb";
  const fs::path dir = benchFolder(format);
  std::uintmax_t bytes = 0;
  for (auto _ : state) {
    RunDef def;
    def.program = compiled.program;
    def.stem = "fig1_24d";
    def.until = kGenerations;
    def.setOptions.formats = format;
    def.world.threads = 1;
    def.out = dir;
    Run run(std::move(def));
    const RunReport report = run.execute();
    if (!report.ok()) {
      state.SkipWithError("the run failed");
      return;
    }
    bytes = fs::file_size(dir / ("fig1_24d." + format));
  }
  state.SetLabel(format);
  state.counters["MB"] = static_cast<double>(bytes) / 1e6;
  fs::remove_all(dir);
}
BENCHMARK(BM_Fig124dRun)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);

// The same by hand: X -> F[+X]F[-X]+X, F -> FF rewritten n times into a string, a turtle
// turning by 20 degrees in the plane, each F a segment, written as OBJ vertices and lines
// (a vertex shared by a segment and the one that starts where it ends).
void BM_Fig124dHandWritten(benchmark::State& state) {
  const fs::path dir = benchFolder("hand");
  std::size_t segments = 0;
  for (auto _ : state) {
    std::string word = "X", next;
    for (int n = 0; n < kGenerations; ++n) {
      next.clear();
      for (char c : word) {
        if (c == 'X')
          next += "F[+X]F[-X]+X";
        else if (c == 'F')
          next += "FF";
        else
          next += c;
      }
      word.swap(next);
    }
    struct State {
      glm::dvec3 position;
      double angle;
      long vertex;
    };
    const double turn = 20 * std::numbers::pi / 180;
    std::vector<State> stack;
    State turtle{{0, 0, 0}, std::numbers::pi / 2, 0};
    std::vector<glm::dvec3> vertices;
    std::vector<std::pair<long, long>> lines;
    for (char c : word) {
      if (c == 'F') {
        if (turtle.vertex == 0) {
          vertices.push_back(turtle.position);
          turtle.vertex = static_cast<long>(vertices.size());
        }
        turtle.position += glm::dvec3(std::cos(turtle.angle), std::sin(turtle.angle), 0);
        vertices.push_back(turtle.position);
        lines.emplace_back(turtle.vertex, static_cast<long>(vertices.size()));
        turtle.vertex = static_cast<long>(vertices.size());
      } else if (c == '+') {
        turtle.angle += turn;
        turtle.vertex = 0;
      } else if (c == '-') {
        turtle.angle -= turn;
        turtle.vertex = 0;
      } else if (c == '[') {
        stack.push_back(turtle);
      } else if (c == ']') {
        turtle = stack.back();
        stack.pop_back();
      }
    }
    std::FILE* out = std::fopen((dir / "hand.obj").c_str(), "w");
    if (out == nullptr) {
      state.SkipWithError("cannot write the OBJ");
      return;
    }
    for (const glm::dvec3& v : vertices) std::fprintf(out, "v %.9g %.9g %.9g\n", v.x, v.y, v.z);
    for (const auto& [a, b] : lines) std::fprintf(out, "l %ld %ld\n", a, b);
    std::fclose(out);
    segments = lines.size();
  }
  state.counters["segments"] = static_cast<double>(segments);
  fs::remove_all(dir);
}
BENCHMARK(BM_Fig124dHandWritten)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace
}  // namespace ontogen::bench
