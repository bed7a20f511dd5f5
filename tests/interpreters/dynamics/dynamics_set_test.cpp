// The dynamics set on the walking models (models/creature.cell, models/quadruped.cell):
// they walk under physics at least half as far as their kinematic walk, do not fall and
// do not sink into the ground; the motion is the same bytes on any number of threads and
// whatever frames are drawn; the MJCF written is the model of the first frame, which
// MuJoCo's own loader reads and steps as the set's model does.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <mujoco/mujoco.h>
#include <nlohmann/json.hpp>

#include "interpreters/dynamics/mujoco_model.h"
#include "interpreters/run.h"
#include "interpreters/sweep/measure.h"
#include "interpreters/sweep/variant_run.h"
#include "tests/core/test_support.h"

namespace ontogen {
namespace {

namespace fs = std::filesystem;

struct Walk {
  RunReport report;
  nlohmann::json tracks;  // the joints.json
  fs::path dir;

  const nlohmann::json& joints() const { return tracks["joints"]; }
  const nlohmann::json& frames() const { return tracks["frames"]; }
  glm::dvec3 at(std::size_t frame, std::size_t joint) const {
    const auto& p = tracks["frames"][frame]["positions"][joint];
    return {p[0].get<double>(), p[1].get<double>(), p[2].get<double>()};
  }
  std::size_t root() const {
    for (std::size_t j = 0; j < joints().size(); ++j)
      if (joints()[j]["parent"].get<int>() < 0) return j;
    return 0;
  }
  // The root's travel along the ground from the first frame to the last.
  double distance() const {
    const glm::dvec3 a = at(0, root()), b = at(frames().size() - 1, root());
    return std::hypot(b.x - a.x, b.z - a.z);
  }
  double lowest() const {
    double low = 1e300;
    for (std::size_t f = 0; f < frames().size(); ++f)
      for (std::size_t j = 0; j < joints().size(); ++j) low = std::min(low, at(f, j).y);
    return low;
  }
};

std::shared_ptr<const Program> compileWith(const std::string& model, const std::map<std::string, double>& defines) {
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
};

Walk walk(const WalkDef& w) {
  // Each run its own folder: ctest runs tests in parallel processes.
  std::string name = std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" + w.model;
  for (const auto& [key, value] : w.defines) name += "_" + key + std::to_string(value);
  name += "_" + std::to_string(w.frames) + "_" + std::to_string(w.threads);
  Walk result;
  result.dir = fs::path(ONTOGEN_BINARY_DIR) / "dynamics_set_test" / name;
  fs::remove_all(result.dir);
  RunDef def;
  def.program = compileWith(w.model, w.defines);
  if (!def.program) return result;
  def.stem = fs::path(w.model).stem().string();
  def.frames = w.frames;
  def.from = w.from;
  def.until = w.until;
  def.world.threads = w.threads;
  def.sets = {"dynamics"};
  def.setOptions.formats = w.formats;
  def.out = result.dir;
  Run run(std::move(def));
  result.report = run.execute();
  EXPECT_TRUE(result.report.ok()) << (result.report.diagnostics.empty() ? "" : result.report.diagnostics[0].message);
  for (const RunDiagnostic& diagnostic : result.report.diagnostics)
    EXPECT_EQ(diagnostic.message.find("unstable"), std::string::npos) << diagnostic.message;
  std::ifstream in(result.dir / (fs::path(w.model).stem().string() + ".joints.json"));
  if (in) result.tracks = nlohmann::json::parse(in);
  return result;
}

std::string bytesOf(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// models/creature.cell's defaults.
constexpr double kPeriod = 1.2, kStride = 0.55, kHeight = 0.75, kLeg = 0.95 + 1.15;

struct Gait {
  double segments, duty;
};

class CreatureWalks : public ::testing::TestWithParam<Gait> {};

// Ten seconds of walk from the first whole cycle on: the root travels at least half as
// far as the kinematic walk (its speed is STRIDE / (DUTY PERIOD)), the body's root never
// drops below half its height, no joint goes more than 5 % of a leg below the ground,
// and feet touch the ground.
TEST_P(CreatureWalks, AtLeastHalfAsFarAsItsKinematicWalk) {
  const Gait gait = GetParam();
  const Walk w = walk({.defines = {{"SEGMENTS", gait.segments}, {"DUTY", gait.duty}},
                       .from = kPeriod,
                       .until = kPeriod + 10,
                       .frames = 11});
  ASSERT_EQ(w.frames().size(), 11u);
  const double kinematic = kStride / (gait.duty * kPeriod) * 10;
  const double walked = w.distance();
  std::cout << "SEGMENTS " << gait.segments << " DUTY " << gait.duty << ": walked " << walked << " of "
            << kinematic << " (" << walked / kinematic << ")\n";
  EXPECT_GE(walked, kinematic / 2);
  for (std::size_t f = 0; f < w.frames().size(); ++f) EXPECT_GT(w.at(f, w.root()).y, kHeight / 2) << f;
  EXPECT_GE(w.lowest(), -0.05 * kLeg);
  std::size_t touching = 0;
  for (const auto& frame : w.frames()) {
    ASSERT_TRUE(frame.contains("contacts"));
    for (const auto& index : frame["contacts"]) {
      ASSERT_LT(index.get<std::size_t>(), w.joints().size());
      ++touching;
    }
  }
  EXPECT_GT(touching, w.frames().size());
}

INSTANTIATE_TEST_SUITE_P(TripodAndWave, CreatureWalks,
                         ::testing::Values(Gait{4, 0.5}, Gait{6, 0.5}, Gait{4, 5.0 / 6}, Gait{6, 5.0 / 6}));

TEST(DynamicsSet, TheQuadrupedWalks) {
  constexpr double period = 1.1, duty = 0.75, stride = 0.55;
  const Walk w = walk({.model = "quadruped.cell", .defines = {}, .from = period, .until = period + 6, .frames = 7});
  ASSERT_EQ(w.frames().size(), 7u);
  const double kinematic = stride / (duty * period) * 6;
  std::cout << "quadruped: walked " << w.distance() << " of " << kinematic << "\n";
  EXPECT_GE(w.distance(), kinematic / 2);
  EXPECT_GE(w.lowest(), -0.05 * (0.55 + 0.6));
}

// The simulation steps on its own grid: 1 or 3 threads, 7 or 13 frames over the same
// span, give the same positions at the frames they share, to the bit.
TEST(DynamicsSet, TheSameMotionOnAnyThreadsAndFrames) {
  const WalkDef def{.defines = {{"SEGMENTS", 3}}, .from = kPeriod, .until = 2 * kPeriod, .frames = 7};
  const Walk one = walk(def);
  WalkDef threaded = def;
  threaded.threads = 3;
  const Walk three = walk(threaded);
  EXPECT_EQ(bytesOf(one.dir / "creature.joints.json"), bytesOf(three.dir / "creature.joints.json"));
  WalkDef finer = def;
  finer.frames = 13;
  const Walk fine = walk(finer);
  ASSERT_EQ(one.frames().size(), 7u);
  ASSERT_EQ(fine.frames().size(), 13u);
  for (std::size_t f = 0; f < 7; ++f) {
    EXPECT_EQ(one.frames()[f]["t"], fine.frames()[2 * f]["t"]);
    EXPECT_EQ(one.frames()[f]["positions"], fine.frames()[2 * f]["positions"]) << f;
    EXPECT_EQ(one.frames()[f]["contacts"], fine.frames()[2 * f]["contacts"]) << f;
  }
}

// DIR/<model>.xml through MuJoCo's own loader: at its keyframe every body stands where the
// first frame has its joint, and it steps as the same text compiled in memory does.
TEST(DynamicsSet, TheWrittenMjcfIsTheFirstFramesModel) {
  const Walk w = walk({.defines = {{"SEGMENTS", 2}}, .from = kPeriod, .until = 2 * kPeriod, .frames = 3,
                       .formats = "joints,mjcf"});
  const fs::path path = w.dir / "creature.xml";
  ASSERT_TRUE(fs::exists(path));
  bool listed = false;
  for (const fs::path& file : w.report.files) listed = listed || file == path;
  EXPECT_TRUE(listed);
  char error[1000] = "";
  mjModel* m = mj_loadXML(path.string().c_str(), nullptr, error, sizeof error);
  ASSERT_NE(m, nullptr) << error;
  mjData* d = mj_makeData(m);
  ASSERT_EQ(m->nkey, 1);
  mj_resetDataKeyframe(m, d, 0);
  mj_forward(m, d);
  for (std::size_t j = 0; j < w.joints().size(); ++j) {
    const int body = mj_name2id(m, mjOBJ_BODY, ("b" + std::to_string(j)).c_str());
    ASSERT_GE(body, 0) << j;
    const glm::dvec3 p = w.at(0, j);
    EXPECT_NEAR(d->xpos[3 * body], p.x, 1e-6) << j;
    EXPECT_NEAR(d->xpos[3 * body + 1], p.y, 1e-6) << j;
    EXPECT_NEAR(d->xpos[3 * body + 2], p.z, 1e-6) << j;
  }
  MujocoModel memory(bytesOf(path));
  mj_resetDataKeyframe(memory.model(), memory.data(), 0);
  mj_forward(memory.model(), memory.data());
  for (int n = 0; n < 500; ++n) {
    mj_step(m, d);
    memory.step();
  }
  for (int i = 0; i < m->nq; ++i) {
    ASSERT_TRUE(std::isfinite(d->qpos[i]));
    EXPECT_EQ(d->qpos[i], memory.data()->qpos[i]) << i;
  }
  // Held at the first frame's targets, the body stands: its root stays up.
  EXPECT_GT(d->qpos[1], kHeight / 2);
  mj_deleteData(d);
  mj_deleteModel(m);
}

// The measures sweep and evolve read: a walk that goes forward, does not fall, spends
// energy and slips a little; a body given no servos (servo(0, 0)) spends none.
TEST(DynamicsSet, MeasuresTheWalk) {
  auto measure = [](const std::string& text) {
    VariantDef def;
    def.name = "models/creature.cell";
    def.text = text;
    def.compile.commandSets = commandSets();
    def.compile.defines = {{"SEGMENTS", 4}};
    def.run.sets = {"dynamics"};
    def.run.setOptions.formats = "joints";
    def.run.out = fs::path(ONTOGEN_BINARY_DIR) / "dynamics_set_test" / "measures";
    def.run.from = kPeriod;
    def.run.until = kPeriod + 3;
    def.run.frames = 4;
    for (const char* m : {"d=distance", "f=fallen", "e=energy", "s=slip"}) def.measures.push_back(parseMeasure(m));
    return runVariant(std::move(def));
  };
  const std::string model = testing_support::readModel("creature.cell");
  const VariantResult walking = measure(model);
  ASSERT_EQ(walking.error, "");
  EXPECT_GT(walking.measures[0], 0.5 * kStride / (0.5 * kPeriod) * 3);
  EXPECT_EQ(walking.measures[1], 0);
  EXPECT_GT(walking.measures[2], 0);
  EXPECT_GT(walking.measures[3], 0);
  std::string limp = model;
  limp.replace(limp.find("axiom Gait body;"), 16, "axiom Limp Gait body;");
  limp += "\ncell Limp { interpret dynamics { servo(0, 0) } }\n";
  const VariantResult fallen = measure(limp);
  ASSERT_EQ(fallen.error, "");
  EXPECT_EQ(fallen.measures[2], 0);
}

}  // namespace
}  // namespace ontogen
