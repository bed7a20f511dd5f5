#pragma once
// The dynamics set's tests' runs: a program (a model's file, or text) run under the
// dynamics set into its own folder, its joints' tracks read back.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <string>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "interpreters/dynamics/dynamics_set.h"
#include "interpreters/run.h"
#include "tests/core/test_support.h"
#include "tests/interpreters/creature/joint_tracks.h"

namespace ontogen::dynamics_testing {

namespace fs = std::filesystem;

using test::Walk;

inline std::shared_ptr<const Program> compileWith(const std::string& model, const std::map<std::string, double>& defines) {
  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  for (const auto& [name, value] : defines) options.defines.push_back({name, value});
  auto program = compileSource("models/" + model, testing_support::readModel(model), sink, options);
  EXPECT_NE(program, nullptr) << formatDiagnostics(sink);
  return program;
}

struct WalkDef {
  std::string model = "creature.cell";
  std::map<std::string, double> defines;
  double from = 0, until = 1;
  int frames = 11;
  std::string formats = "joints";
  int threads = 1;
  // Called after each frame with the set and the frame's time.
  std::function<void(const DynamicsSet&, double)> onFrame = {};
  std::string text = {};  // the program, when not the model's file
};

inline Walk walk(const WalkDef& w) {
  // Each run its own folder: ctest runs tests in parallel processes.
  std::string name = std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" + w.model;
  for (const auto& [key, value] : w.defines) name += "_" + key + std::to_string(value);
  name += "_" + std::to_string(w.frames) + "_" + std::to_string(w.threads);
  Walk result;
  result.dir = fs::path(ONTOGEN_BINARY_DIR) / "dynamics_set_test" / name;
  fs::remove_all(result.dir);
  RunDef def;
  if (w.text.empty()) {
    def.program = compileWith(w.model, w.defines);
  } else {
    DiagnosticSink sink;
    CompileOptions options;
    options.commandSets = commandSets();
    for (const auto& [key, value] : w.defines) options.defines.push_back({key, value});
    def.program = compileSource("models/" + w.model, w.text, sink, options);
    EXPECT_NE(def.program, nullptr) << formatDiagnostics(sink);
  }
  if (!def.program) return result;
  result.program = def.program;
  def.stem = fs::path(w.model).stem().string();
  def.frames = w.frames;
  def.from = w.from;
  def.until = w.until;
  def.world.threads = w.threads;
  def.sets = {"dynamics"};
  def.setOptions.formats = w.formats;
  def.out = result.dir;
  const DynamicsSet* dynamics = nullptr;
  if (w.onFrame)
    def.frameDrawn = [&](const Scene& scene) {
      if (dynamics) w.onFrame(*dynamics, scene.time);
    };
  Run run(std::move(def));
  for (const auto& set : run.sets())
    if (const auto* found = dynamic_cast<const DynamicsSet*>(set.get())) dynamics = found;
  result.report = run.execute();
  EXPECT_TRUE(result.report.ok()) << (result.report.diagnostics.empty() ? "" : result.report.diagnostics[0].message);
  for (const RunDiagnostic& diagnostic : result.report.diagnostics)
    EXPECT_EQ(diagnostic.message.find("unstable"), std::string::npos) << diagnostic.message;
  std::ifstream in(result.dir / (fs::path(w.model).stem().string() + ".joints.json"));
  if (in) result.tracks = nlohmann::json::parse(in);
  return result;
}

inline std::string bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}
}  // namespace ontogen::dynamics_testing
