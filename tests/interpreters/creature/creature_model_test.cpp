// The walking models (models/creature.cell, models/quadruped.cell) by value, from their
// joint tracks (--format joints): feet planted in stance, the duty factor, the phases by
// segment and side, a pose that repeats every period, drivers that are continuous,
// counts that grow with SEGMENTS, angles inside their ranges, the same bytes for the
// same seed; and the skinned glTF through the Khronos validator and Blender.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "tests/interpreters/external_tools.h"
#include "interpreters/run.h"
#include "tests/core/test_support.h"
#include "tests/interpreters/creature/joint_tracks.h"

namespace ontogen {
namespace {

namespace fs = std::filesystem;
using testing_support::runCommand;

// A checker the test needs: missing, it skips on a developer's machine and fails in CI.
#define REQUIRE_CHECKER(available, what)                                           \
  do {                                                                             \
    if (!(available)) {                                                            \
      const char* ci = std::getenv("CI");                                          \
      if (ci != nullptr && std::string(ci) == "true") FAIL() << what << " is missing"; \
      GTEST_SKIP() << what << " is missing (bash .ci/setup --checkers installs it)"; \
    }                                                                              \
  } while (false)

using test::Walk;

std::shared_ptr<const Program> compileWith(const std::string& model, const std::map<std::string, double>& defines) {
  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  for (const auto& [name, value] : defines) options.defines.push_back({name, value});
  auto program = compileSource("models/" + model, testing_support::readModel(model), sink, options);
  EXPECT_NE(program, nullptr) << formatDiagnostics(sink);
  return program;
}

Walk walk(const std::string& model, const std::map<std::string, double>& defines, const std::string& formats = "joints",
          std::optional<int> frames = {}, uint64_t seed = 1, std::optional<double> from = {}) {
  // Each test its own folder: ctest runs tests in parallel processes.
  std::string name = std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" + model;
  for (const auto& [key, value] : defines) name += "_" + key + std::to_string(value);
  name += "_" + std::to_string(seed) + "_" + std::to_string(frames.value_or(0));
  Walk result;
  result.dir = fs::path(ONTOGEN_BINARY_DIR) / "creature_model_test" / name;
  fs::remove_all(result.dir);
  RunDef def;
  def.program = compileWith(model, defines);
  if (!def.program) return result;
  result.program = def.program;
  def.stem = fs::path(model).stem().string();
  def.world.seed = seed;
  def.frames = frames;
  def.from = from;
  def.sets = {"creature"};
  def.setOptions.formats = formats;
  def.out = result.dir;
  Run run(std::move(def));
  result.report = run.execute();
  EXPECT_TRUE(result.report.ok()) << (result.report.diagnostics.empty() ? "" : result.report.diagnostics[0].message);
  std::ifstream in(result.dir / (fs::path(model).stem().string() + ".joints.json"));
  if (in) result.tracks = nlohmann::json::parse(in);
  return result;
}

// The frames (indices) in which a foot is on the ground.
bool onGround(const Walk& w, std::size_t frame, std::size_t foot) { return w.at(frame, foot).y <= 1e-9; }

constexpr double kPeriod = 1.2, kStride = 0.55, kFps = 30;  // models/creature.cell's defaults
constexpr int kFramesPerCycle = 36;

// A gait out of range (DUTY 1: a foot never off the ground; DUTY 0; a negative stride)
// makes no creature, and the set says why once a frame, located at the gait's call in
// models/creature.cell (line 67, column 5).
TEST(CreatureModel, AGaitOutOfRangeIsAWarningAtItsCallSayingWhy) {
  const std::map<double, std::string> reasons{{1.0, "the duty factor must be between 0 and 1"},
                                              {0.0, "the duty factor must be between 0 and 1"}};
  for (const auto& [duty, reason] : reasons) {
    const Walk w = walk("creature.cell", {{"DUTY", duty}}, "joints", 2);
    int named = 0;
    for (const RunDiagnostic& d : w.report.diagnostics) {
      if (d.message.find("made no creature") == std::string::npos) continue;
      ++named;
      EXPECT_EQ(d.severity, Severity::Warning);
      EXPECT_EQ(d.message, "the creature set made no creature of " + std::to_string(d.count) + (d.count == 1 ? " gait" : " gaits") +
                               " out of range: " + reason + " (the first here)");
      EXPECT_GE(d.count, 1u);
      ASSERT_TRUE(d.span.valid());
      EXPECT_EQ(d.span.line(), 67);
      EXPECT_EQ(d.span.column(), 5);
    }
    EXPECT_EQ(named, 1) << "DUTY " << duty;
  }
  const Walk negative = walk("creature.cell", {{"STRIDE", -1}}, "joints", 2);
  bool said = false;
  for (const RunDiagnostic& d : negative.report.diagnostics)
    said = said || d.message.find("out of range: the stride must be >= 0") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(CreatureModel, StanceFeetDoNotSlip) {
  for (double noise : {0.0, 0.15}) {
    const Walk w = walk("creature.cell", {{"NOISE", noise}, {"SEGMENTS", 4}});
    ASSERT_GT(w.frames().size(), 0u);
    double worst = 0;
    int stances = 0;
    for (std::size_t foot : w.feet()) {
      glm::dvec3 planted(0.0);
      bool down = false;
      for (std::size_t f = 0; f < w.frames().size(); ++f) {
        if (!onGround(w, f, foot)) {
          down = false;
          continue;
        }
        if (!down) {
          planted = w.at(f, foot);
          down = true;
          ++stances;
        }
        worst = std::max(worst, glm::length(w.at(f, foot) - planted));
      }
    }
    EXPECT_GE(stances, 8 * 2) << "every foot touched down at least twice";
    EXPECT_LE(worst, 0.01 * kStride) << "noise " << noise;
    EXPECT_LT(worst, 1e-9) << "in fact the feet do not move at all";
  }
}

TEST(CreatureModel, EachFootIsDownForTheDutyFactorWithinAFrame) {
  for (double duty : {0.5, 2.0 / 3, 5.0 / 6}) {
    const Walk w = walk("creature.cell", {{"DUTY", duty}});
    const std::size_t frames = w.frames().size();
    ASSERT_EQ(frames, 2u * kFramesPerCycle + 1) << "#fps 30 over two cycles";
    for (std::size_t foot : w.feet()) {
      int down = 0;
      for (std::size_t f = 0; f + 1 < frames; ++f) down += onGround(w, f, foot);  // two whole cycles
      EXPECT_NEAR(down / (frames - 1.0), duty, 1.0 / kFramesPerCycle + 1e-9) << "duty " << duty << ", foot " << foot;
    }
  }
}

// The time of each touchdown of a foot: the first frame on the ground after one in the air.
std::vector<double> touchdowns(const Walk& w, std::size_t foot) {
  std::vector<double> out;
  for (std::size_t f = 1; f < w.frames().size(); ++f)
    if (onGround(w, f, foot) && !onGround(w, f - 1, foot)) out.push_back(w.time(f));
  return out;
}

TEST(CreatureModel, FeetTouchDownBySegmentAndSideHalfACycleApart) {
  const double duty = 2.0 / 3;
  const Walk w = walk("creature.cell", {{"DUTY", duty}, {"SEGMENTS", 5}});
  const double frame = 1 / kFps;
  std::map<std::pair<int, std::string>, double> firstDown;
  for (std::size_t foot : w.feet()) {
    const auto& joint = w.joints()[foot];
    const std::vector<double> times = touchdowns(w, foot);
    ASSERT_GE(times.size(), 1u);
    const int m = joint["segment"].get<int>();
    const std::string side = joint["side"].get<std::string>();
    // Touchdown at phase frac(m * DUTY) (left) or frac(1/2 + m * DUTY) (right): within a frame after.
    const double phase = m * duty + (side == "right" ? 0.5 : 0.0);
    const double expected = kPeriod * (phase - std::floor(phase));
    const double seen = std::fmod(times[0], kPeriod);
    double gap = std::fmod(seen - expected + 2 * kPeriod, kPeriod);
    if (gap > kPeriod / 2) gap -= kPeriod;  // a hair early: rounding
    EXPECT_GE(gap, -1e-9) << "segment " << m << " " << side;
    EXPECT_LE(gap, frame + 1e-9) << "segment " << m << " " << side;
    firstDown[{m, side}] = seen;
  }
  for (int m = 0; m < 5; ++m) {
    const double apart = std::fmod(firstDown[{m, "right"}] - firstDown[{m, "left"}] + kPeriod, kPeriod);
    EXPECT_NEAR(apart, kPeriod / 2, frame + 1e-9) << "segment " << m;
  }
}

TEST(CreatureModel, ThePoseRepeatsEveryPeriodRelativeToTheBody) {
  const Walk w = walk("creature.cell", {{"NOISE", 0}});
  const std::size_t root = w.root();
  for (std::size_t f = 0; f + kFramesPerCycle < w.frames().size(); ++f)
    for (std::size_t j = 0; j < w.joints().size(); ++j) {
      const glm::dvec3 now = w.at(f, j) - w.at(f, root);
      const glm::dvec3 later = w.at(f + kFramesPerCycle, j) - w.at(f + kFramesPerCycle, root);
      ASSERT_LT(glm::length(now - later), 1e-9) << "joint " << j << " at frame " << f;
    }
  // And the body has moved on by the distance the stance feet push.
  const glm::dvec3 travelled = w.at(kFramesPerCycle, root) - w.at(0, root);
  EXPECT_NEAR(travelled.x, kStride / 0.5, 1e-9) << "speed * period = stride / duty";
}

TEST(CreatureModel, TheDriversAreContinuous) {
  // At 240 frames a second, no joint moves relative to the body by more than its
  // fastest smooth motion allows in a frame; a jump of the kind paper 000's g_su makes
  // (40 degrees on a limb) would move a knee by more than half a unit.
  for (double noise : {0.0, 0.15}) {
    const Walk w = walk("creature.cell", {{"NOISE", noise}}, "joints", 2 * 240 + 1);
    const std::size_t root = w.root();
    double worst = 0;
    for (std::size_t f = 1; f < w.frames().size(); ++f)
      for (std::size_t j = 0; j < w.joints().size(); ++j) {
        const glm::dvec3 d = (w.at(f, j) - w.at(f, root)) - (w.at(f - 1, j) - w.at(f - 1, root));
        worst = std::max(worst, glm::length(d));
      }
    EXPECT_LT(worst, 0.05) << "noise " << noise << ": the largest move in 1/240 s";
  }
}

TEST(CreatureModel, JointAndFootCountsGrowLinearlyWithSegments) {
  for (int segments : {1, 2, 5, 16}) {
    const Walk w = walk("creature.cell", {{"SEGMENTS", segments}}, "joints", 2);
    EXPECT_EQ(w.joints().size(), 1u + 7u * segments) << "the root, and per segment a bend and two hips, knees, feet";
    EXPECT_EQ(w.feet().size(), 2u * segments);
  }
}

TEST(CreatureModel, JointAnglesStayInsideTheirRanges) {
  for (const auto& defines : std::vector<std::map<std::string, double>>{
           {{"SEGMENTS", 3}}, {{"SEGMENTS", 6}, {"DUTY", 0.5}}, {{"SEGMENTS", 6}, {"DUTY", 5.0 / 6}}}) {
    const Walk w = walk("creature.cell", defines);
    for (const RunDiagnostic& d : w.report.diagnostics) ADD_FAILURE() << "unexpected: " << d.message;
    // The knees' bend, from the hip, knee and foot positions: inside the model's 0..160 deg.
    for (std::size_t foot : w.feet()) {
      const std::size_t knee = w.joints()[foot]["parent"].get<std::size_t>();
      const std::size_t hip = w.joints()[knee]["parent"].get<std::size_t>();
      for (std::size_t f = 0; f < w.frames().size(); ++f) {
        const glm::dvec3 upper = glm::normalize(w.at(f, knee) - w.at(f, hip));
        const glm::dvec3 lower = glm::normalize(w.at(f, foot) - w.at(f, knee));
        const double bend = std::acos(std::clamp(glm::dot(upper, lower), -1.0, 1.0)) * 180 / std::numbers::pi;
        EXPECT_GE(bend, 0);
        EXPECT_LE(bend, 160);
      }
      for (std::size_t f = 0; f < w.frames().size(); ++f) EXPECT_GE(w.at(f, foot).y, -1e-9) << "below the ground";
    }
  }
}

TEST(CreatureModel, TheSameSeedGivesTheSameBytesAndAnotherSeedAnotherWalk) {
  auto bytes = [](const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream out;
    out << in.rdbuf();
    return out.str();
  };
  const Walk a = walk("creature.cell", {{"SEGMENTS", 3}}, "glb,joints", {}, 7);
  const std::string first = bytes(a.dir / "creature.glb");
  ASSERT_GT(first.size(), 1000u);
  const Walk b = walk("creature.cell", {{"SEGMENTS", 3}, {"NOISE", 0.15}}, "glb,joints", {}, 7);
  EXPECT_EQ(bytes(b.dir / "creature.glb"), first);
  const Walk c = walk("creature.cell", {{"SEGMENTS", 3}}, "glb,joints", {}, 8);
  EXPECT_NE(bytes(c.dir / "creature.glb"), first) << "the noise of the creature's age is seeded";
}

TEST(CreatureModel, TheWalkIsTheSameWhateverTheFrames) {
  const Walk coarse = walk("creature.cell", {}, "joints", 2 * 36 + 1);
  const Walk fine = walk("creature.cell", {}, "joints", 4 * 36 + 1);
  ASSERT_EQ(coarse.joints(), fine.joints());
  for (std::size_t f = 0; f < coarse.frames().size(); ++f) {
    ASSERT_DOUBLE_EQ(coarse.time(f), fine.time(2 * f));
    EXPECT_EQ(coarse.frames()[f]["positions"], fine.frames()[2 * f]["positions"]) << "at " << coarse.time(f);
  }
}

// From t = 0 the body has not grown yet (its segments come in the first step): the skin
// holds the grown body, and the joints a frame lacks are listed as null and hidden.
TEST(CreatureModel, ABodyThatGrowsIsWrittenGrown) {
  const Walk w = walk("creature.cell", {}, "glb,joints", 13, 1, 0.0);
  ASSERT_EQ(w.joints().size(), 1u + 7u * 3);
  std::size_t missing = 0;
  for (const auto& position : w.frames()[0]["positions"]) missing += position.is_null();
  EXPECT_EQ(missing, 7u * 3) << "at t = 0 only the root";
  for (const auto& position : w.frames()[1]["positions"]) EXPECT_FALSE(position.is_null());
  std::ifstream in(w.dir / "creature.glb", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(bytes.size(), 20u);
  const uint32_t length = static_cast<uint8_t>(bytes[12]) | static_cast<uint8_t>(bytes[13]) << 8 |
                          static_cast<uint8_t>(bytes[14]) << 16 | static_cast<uint32_t>(static_cast<uint8_t>(bytes[15])) << 24;
  const nlohmann::json gltf = nlohmann::json::parse(bytes.substr(20, length));
  ASSERT_EQ(gltf["skins"][0]["joints"].size(), 1u + 7u * 3);
  int scales = 0;
  for (const auto& channel : gltf["animations"][0]["channels"]) scales += channel["target"]["path"] == "scale";
  EXPECT_EQ(scales, 7 * 3) << "every joint but the root appears after the first frame";
  ASSERT_EQ(gltf["cameras"].size(), 1u) << "a camera framing the walk";
  EXPECT_EQ(bytes.substr(20, length).find("KHR_lights_punctual"), std::string::npos) << "no light: viewers bring their own";
}

TEST(CreatureModel, TheSkinPassesTheKhronosValidatorAtThreeAndSixSegments) {
  const fs::path modules = fs::path(ONTOGEN_SOURCE_DIR) / ".tools" / "node_modules";
  REQUIRE_CHECKER(fs::exists(modules / "gltf-validator" / "package.json"), "the Khronos glTF validator");
  const fs::path script = fs::path(ONTOGEN_SOURCE_DIR) / "tests" / "interpreters" / "validate_gltf.js";
  for (int segments : {3, 6}) {
    const Walk w = walk("creature.cell", {{"SEGMENTS", segments}}, "glb");
    const fs::path file = w.dir / "creature.glb";
    auto [status, report] = runCommand("node '" + script.string() + "' '" + modules.string() + "' '" + file.string() + "' 2>&1");
    EXPECT_EQ(status, 0) << report;
    EXPECT_NE(report.find("errors 0"), std::string::npos) << report;
  }
  {
    const Walk grown = walk("creature.cell", {}, "glb", 13, 1, 0.0);
    auto [status, report] = runCommand("node '" + script.string() + "' '" + modules.string() + "' '" +
                                       (grown.dir / "creature.glb").string() + "' 2>&1");
    EXPECT_EQ(status, 0) << "a body that grows: " << report;
  }
  for (double gait : {0, 1, 2}) {
    const Walk w = walk("quadruped.cell", {{"GAIT", gait}}, "glb");
    auto [status, report] = runCommand("node '" + script.string() + "' '" + modules.string() + "' '" +
                                       (w.dir / "quadruped.glb").string() + "' 2>&1");
    EXPECT_EQ(status, 0) << report;
  }
}

TEST(CreatureModel, BlenderImportsAnArmatureASkinnedMeshAndAnAction) {
  REQUIRE_CHECKER(runCommand("command -v blender >/dev/null 2>&1").first == 0, "Blender");
  const Walk w = walk("creature.cell", {{"SEGMENTS", 3}}, "glb");
  const fs::path script = fs::path(ONTOGEN_SOURCE_DIR) / "tests" / "interpreters" / "creature" / "blender_import.py";
  auto [status, output] = runCommand("blender -b --factory-startup --python '" + script.string() + "' -- '" +
                                     (w.dir / "creature.glb").string() + "' 2>&1");
  const std::size_t at = output.find("ONTOGEN-REPORT ");
  ASSERT_NE(at, std::string::npos) << output;
  const nlohmann::json report = nlohmann::json::parse(output.substr(at + 15, output.find('\n', at) - at - 15));
  ASSERT_EQ(report["armatures"].size(), 1u) << report.dump();
  EXPECT_EQ(report["armatures"][0]["bones"].get<int>(), 1 + 7 * 3);
  EXPECT_EQ(report["skinned"].size(), 1u) << report.dump();
  ASSERT_EQ(report["actions"].size(), 1u) << report.dump();
  EXPECT_GT(report["actions"][0]["curves"].get<int>(), 22) << "a rotation for every joint and the root's translation";
}

TEST(CreatureModel, TheQuadrupedWalksTrotsAndBounds) {
  struct Expected {
    double gait, duty;
    // Touchdown phases of LF, RF, LH, RH.
    std::array<double, 4> phases;
  };
  for (const Expected& e : {Expected{0, 0.75, {0.25, 0.75, 0, 0.5}}, Expected{1, 0.5, {0, 0.5, 0.5, 0}},
                            Expected{2, 0.4, {0, 0.05, 0.5, 0.55}}}) {
    const Walk w = walk("quadruped.cell", {{"GAIT", e.gait}}, "joints", 2 * 240 + 1);
    for (const RunDiagnostic& d : w.report.diagnostics) ADD_FAILURE() << "gait " << e.gait << ": " << d.message;
    const double period = e.gait == 0 ? 1.1 : e.gait == 1 ? 0.7 : 0.55;
    ASSERT_EQ(w.feet().size(), 4u);
    for (std::size_t foot : w.feet()) {
      const int m = w.joints()[foot]["segment"].get<int>();
      const bool right = w.joints()[foot]["side"].get<std::string>() == "right";
      const double phase = e.phases[2 * m + (right ? 1 : 0)];
      const std::vector<double> times = touchdowns(w, foot);
      ASSERT_GE(times.size(), 1u);
      const double frame = 2 * period / 480;
      double gap = std::fmod(std::fmod(times[0], period) - phase * period + 2 * period, period);
      if (gap > period / 2) gap -= period;
      EXPECT_GE(gap, -1e-9) << "gait " << e.gait << " leg " << 2 * m + right;
      EXPECT_LE(gap, frame + 1e-9) << "gait " << e.gait << " leg " << 2 * m + right;
      int down = 0;
      for (std::size_t f = 0; f + 1 < w.frames().size(); ++f) down += onGround(w, f, foot);
      EXPECT_NEAR(down / (w.frames().size() - 1.0), e.duty, 1.0 / 240 + 1e-9);
    }
  }
}

}  // namespace
}  // namespace ontogen

namespace ontogen {
namespace {

// `#interpret` takes the name of every set there is (its list is lang's own copy).
TEST(CreatureModel, InterpretDirectiveNamesEverySet) {
  for (const std::string& name : interpretationSetNames()) {
    auto program = testing_support::compileOrFail("#interpret " + name + "\nsystem s { pool linear; axiom A; }");
    ASSERT_NE(program, nullptr) << name;
    EXPECT_EQ(program->interpretSets, std::vector<std::string>{name});
  }
  DiagnosticSink sink;
  EXPECT_EQ(compileSource("t.cell", "#interpret geometree\nsystem s { pool linear; axiom A; }", sink), nullptr);
}

}  // namespace
}  // namespace ontogen
