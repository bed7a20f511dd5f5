// The animated glTF binary read back by value: materials in linear light; each cell's
// part written once and moved by its joint (translation, rotation, scale from the
// scenes' nodes, in closed form); a shape many cells draw written once; lines as tubes of
// the documented radius; a shape that changes switching joints; the time keys; camera
// and light.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "interpreters/formats/glb_writer.h"
#include "interpreters/formats/gltf_builder.h"
#include "interpreters/formats/mesh_batches.h"
#include "interpreters/geometry.h"
#include "interpreters/palette.h"
#include "interpreters/run.h"
#include "interpreters/scene.h"
#include "interpreters/set_registry.h"
#include "tests/checkers.h"
#include "tests/core/test_support.h"
#include "tests/interpreters/external_tools.h"

namespace ontogen {
namespace {

// A .glb split into its JSON and binary chunks, with accessors read as numbers.
struct Glb {
  nlohmann::json json;
  std::string bin;

  explicit Glb(const std::string& glb) {
    uint32_t length = 0;
    std::memcpy(&length, glb.data() + 12, 4);
    json = nlohmann::json::parse(glb.substr(20, length));
    if (glb.size() > 20 + length + 8) bin = glb.substr(20 + length + 8);
  }
  // Every component of an accessor, in order (normalized integers as they are stored).
  std::vector<double> values(int accessor) const {
    const auto& a = json["accessors"][accessor];
    const auto& view = json["bufferViews"][a["bufferView"].get<int>()];
    const std::size_t offset = view["byteOffset"].get<std::size_t>() + a.value("byteOffset", 0);
    const std::string type = a["type"];
    const std::size_t width = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 16;
    const std::size_t n = a["count"].get<std::size_t>() * width;
    std::vector<double> out(n);
    const int component = a["componentType"];
    for (std::size_t k = 0; k < n; ++k) {
      if (component == 5126) {
        float f = 0;
        std::memcpy(&f, bin.data() + offset + 4 * k, 4);
        out[k] = f;
      } else if (component == 5121) {
        out[k] = static_cast<uint8_t>(bin[offset + k]);
      } else if (component == 5123) {
        uint16_t u = 0;
        std::memcpy(&u, bin.data() + offset + 2 * k, 2);
        out[k] = u;
      } else {
        uint32_t u = 0;
        std::memcpy(&u, bin.data() + offset + 4 * k, 4);
        out[k] = u;
      }
    }
    return out;
  }
  // The node of a name, or -1.
  int node(const std::string& name) const {
    for (std::size_t n = 0; n < json["nodes"].size(); ++n)
      if (json["nodes"][n].value("name", "") == name) return static_cast<int>(n);
    return -1;
  }
  // The output values of the animation's channel for node and path (empty: none), and its
  // interpolation.
  std::vector<double> channel(int node, const std::string& path, std::string* interpolation = nullptr) const {
    if (!json.contains("animations")) return {};
    const auto& animation = json["animations"][0];
    for (const auto& c : animation["channels"]) {
      if (c["target"]["node"].get<int>() != node || c["target"]["path"] != path) continue;
      const auto& sampler = animation["samplers"][c["sampler"].get<int>()];
      if (interpolation) *interpolation = sampler["interpolation"];
      return values(sampler["output"].get<int>());
    }
    return {};
  }
  // The value of a node's channel (first component) at an animation time, as a viewer
  // samples it: held before the first key and after the last.
  double sample(int node, const std::string& path, double time) const {
    const auto& animation = json["animations"][0];
    for (const auto& c : animation["channels"]) {
      if (c["target"]["node"].get<int>() != node || c["target"]["path"] != path) continue;
      const auto& sampler = animation["samplers"][c["sampler"].get<int>()];
      const std::vector<double> in = values(sampler["input"].get<int>());
      const std::vector<double> out = values(sampler["output"].get<int>());
      const std::size_t width = out.size() / in.size();
      std::size_t k = 0;
      while (k + 1 < in.size() && in[k + 1] <= time) ++k;
      return out[k * width];  // the channels this samples are STEP
    }
    return std::nan("");
  }
  std::vector<double> keys() const {
    return values(json["animations"][0]["samplers"][0]["input"].get<int>());
  }
};

std::string written(const GlbAnimationWriter& writer) {
  std::ostringstream out;
  writer.write(out);
  return out.str();
}

// A scene of cells, each drawing through `draw` as a node at the turtle's place.
struct SceneBuilder {
  Scene scene;
  explicit SceneBuilder(double time) { scene.time = time; }
  template <typename Draw>
  void cell(uint64_t id, const std::string& label, const glm::dvec3& position, const glm::dmat3& orientation,
            Draw draw) {
    SceneNode node;
    node.id = id;
    node.label = label;
    node.birth = 0.25 * static_cast<double>(id);
    node.position = position;
    node.orientation = orientation;
    node.range.firstTriangle = static_cast<uint32_t>(scene.geometry.triangleCount());
    node.range.firstSegment = static_cast<uint32_t>(scene.geometry.segmentCount());
    draw(scene.geometry);
    node.range.triangleCount = static_cast<uint32_t>(scene.geometry.triangleCount()) - node.range.firstTriangle;
    node.range.segmentCount = static_cast<uint32_t>(scene.geometry.segmentCount()) - node.range.firstSegment;
    scene.nodes.push_back(node);
  }
};

glm::dmat3 turnedAboutZ(double degrees) {
  const double a = degrees * M_PI / 180;
  return glm::dmat3(glm::dvec3(std::cos(a), std::sin(a), 0), glm::dvec3(-std::sin(a), std::cos(a), 0), glm::dvec3(0, 0, 1));
}

TEST(GlbWriter, MaterialsAreThePaletteInLinearLight) {
  Scene scene;
  scene.geometry.setMaterial(0);
  scene.geometry.addCylinder({0, 0, 0}, {0, 1, 0}, 0.1, true);
  scene.geometry.setMaterial(2);
  scene.geometry.addSphere({0, 2, 0}, 0.5);
  GlbAnimationWriter writer;
  writer.addFrame(scene);
  const nlohmann::json gltf = Glb(written(writer)).json;
  ASSERT_EQ(gltf["materials"].size(), 2u);
  // Palette 0 is sRGB (0.62, 0.55, 0.45) and 2 is (0.85, 0.20, 0.20); in linear light,
  // by IEC 61966-2-1's curve ((c + 0.055) / 1.055)^2.4, they are these.
  const auto& stem = gltf["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"];
  EXPECT_NEAR(stem[0].get<double>(), 0.342392, 1e-6);
  EXPECT_NEAR(stem[1].get<double>(), 0.263273, 1e-6);
  EXPECT_NEAR(stem[2].get<double>(), 0.170645, 1e-6);
  EXPECT_EQ(stem[3].get<double>(), 1.0);
  const auto& red = gltf["materials"][1]["pbrMetallicRoughness"]["baseColorFactor"];
  EXPECT_NEAR(red[0].get<double>(), 0.692071, 1e-6);
  EXPECT_NEAR(red[1].get<double>(), 0.033105, 1e-6);
  EXPECT_EQ(gltf["materials"][1]["name"], "ontogen_2");
}

TEST(Palette, LinearFromSrgbFollowsBothPiecesOfTheCurve) {
  EXPECT_DOUBLE_EQ(linearFromSrgb(0.0), 0.0);
  EXPECT_DOUBLE_EQ(linearFromSrgb(1.0), 1.0);
  EXPECT_NEAR(linearFromSrgb(0.03), 0.03 / 12.92, 1e-15);  // the straight piece near black
  EXPECT_NEAR(linearFromSrgb(0.5), 0.214041, 1e-6);
  EXPECT_DOUBLE_EQ(linearFromSrgb(-1.0), 0.0);  // clamped
}

// A ball that moves and grows (cell 7) beside a turned rod that stays (cell 9), over
// three frames: two joints, two shapes, the ball's translation and scale animated at the
// frames' times, the rod unanimated.
TEST(GlbWriter, EachCellsPartIsWrittenOnceAndMovedByItsJoint) {
  GlbAnimationWriter writer;
  const double times[3] = {1.0, 1.5, 2.5};
  for (int f = 0; f < 3; ++f) {
    SceneBuilder frame(times[f]);
    const glm::dvec3 ball(f, 2.0 * f, 0);
    const double radius = 0.5 + 0.25 * f;
    frame.cell(7, "Ball", {0, 0, 0}, glm::dmat3(1.0), [&](Geometry& g) { g.addSphere(ball, radius); });
    frame.cell(9, "Rod", {3, 0, 0}, turnedAboutZ(90), [&](Geometry& g) { g.addCylinder({3, 0, 0}, {3, 2, 0}, 0.1, true, {-1, 0, 0}); });
    writer.addFrame(frame.scene);
  }
  EXPECT_EQ(writer.parts().shapes().size(), 2u) << "the ball grows by a uniform scale: one shape";
  ASSERT_EQ(writer.parts().joints().size(), 2u);
  const Glb glb(written(writer));
  const int ball = glb.node("Ball 7"), rod = glb.node("Rod 9");
  ASSERT_GE(ball, 0);
  ASSERT_GE(rod, 0);
  EXPECT_EQ(glb.json["nodes"][ball]["extras"]["id"], "7");
  EXPECT_EQ(glb.json["nodes"][ball]["extras"]["label"], "Ball");
  EXPECT_DOUBLE_EQ(glb.json["nodes"][ball]["extras"]["birth"].get<double>(), 1.75);
  // Keys at the frames' times less the first's.
  const std::vector<double> keys = glb.keys();
  ASSERT_EQ(keys.size(), 3u);
  EXPECT_FLOAT_EQ(keys[1], 0.5f);
  EXPECT_FLOAT_EQ(keys[2], 1.5f);
  EXPECT_DOUBLE_EQ(glb.json["scenes"][0]["extras"]["ontogen_time_start"].get<double>(), 1.0);
  // The ball's joint stands at its centre, scaled by its radius (the sphere's poles and
  // its first meridian reach the radius exactly).
  std::string interpolation;
  const std::vector<double> t = glb.channel(ball, "translation");
  const std::vector<double> s = glb.channel(ball, "scale", &interpolation);
  ASSERT_EQ(t.size(), 9u);
  ASSERT_EQ(s.size(), 9u);
  EXPECT_EQ(interpolation, "LINEAR");
  for (int f = 0; f < 3; ++f) {
    EXPECT_NEAR(t[3 * f], f, 1e-6);
    EXPECT_NEAR(t[3 * f + 1], 2.0 * f, 1e-6);
    EXPECT_NEAR(t[3 * f + 2], 0, 1e-6);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(s[3 * f + k], 0.5 + 0.25 * f, 1e-6);
  }
  EXPECT_TRUE(glb.channel(ball, "rotation").empty()) << "the ball does not turn";
  for (const char* path : {"translation", "rotation", "scale"}) EXPECT_TRUE(glb.channel(rod, path).empty()) << path;
  // The rod's rest transform: its centre, its cell's turn (90 degrees about z), its half length.
  const auto& r = glb.json["nodes"][rod];
  EXPECT_NEAR(r["translation"][0].get<double>(), 3, 1e-9);
  EXPECT_NEAR(r["translation"][1].get<double>(), 1, 1e-9);
  EXPECT_NEAR(r["rotation"][2].get<double>(), std::sin(M_PI / 4), 1e-7);  // floats
  EXPECT_NEAR(r["rotation"][3].get<double>(), std::cos(M_PI / 4), 1e-7);
  EXPECT_FALSE(r.contains("scale")) << "1, the default";
  // One skin over both joints, its inverse bind matrices identities: shapes lie in their
  // cells' frames.
  ASSERT_EQ(glb.json["skins"].size(), 1u);
  EXPECT_EQ(glb.json["skins"][0]["joints"].size(), 2u);
  const std::vector<double> inverseBind = glb.values(glb.json["skins"][0]["inverseBindMatrices"].get<int>());
  ASSERT_EQ(inverseBind.size(), 32u);
  for (std::size_t k = 0; k < 32; ++k) EXPECT_EQ(inverseBind[k], k % 16 % 5 == 0 ? 1.0 : 0.0) << k;
  EXPECT_EQ(glb.json["meshes"].size(), 1u);
  EXPECT_EQ(glb.json["animations"].size(), 1u);
}

// A hundred cells drawing the same ball: the ball's vertices are written once, every
// cell's primitive reuses them with its own joint.
TEST(GlbWriter, AShapeManyCellsDrawIsWrittenOnce) {
  SceneBuilder frame(0);
  for (int c = 0; c < 100; ++c)
    frame.cell(100 + c, "C", {0, 0, 0}, glm::dmat3(1.0), [&](Geometry& g) { g.addSphere({c % 10, c / 10, 0}, 0.4); });
  GlbAnimationWriter writer;
  writer.addFrame(frame.scene);
  EXPECT_EQ(writer.parts().shapes().size(), 1u);
  const std::string bytes = written(writer);
  const Glb glb(bytes);
  const auto& primitives = glb.json["meshes"][0]["primitives"];
  ASSERT_EQ(primitives.size(), 100u);
  std::set<int> positions, joints;
  for (const auto& p : primitives) {
    positions.insert(p["attributes"]["POSITION"].get<int>());
    joints.insert(p["attributes"]["JOINTS_0"].get<int>());
  }
  EXPECT_EQ(positions.size(), 1u);
  EXPECT_EQ(joints.size(), 100u);
  // Each primitive's joint is its cell's, and TEXCOORD_1 carries (cell number, birth).
  const auto& last = primitives[99]["attributes"];
  const std::vector<double> j = glb.values(last["JOINTS_0"].get<int>());
  EXPECT_EQ(j[0], 99);
  EXPECT_EQ(j[1], 0);
  const std::vector<double> cell = glb.values(last["TEXCOORD_1"].get<int>());
  EXPECT_EQ(cell[0], 99);
  EXPECT_DOUBLE_EQ(cell[1], 0.25 * 199);
  // The whole file against the ball's vertices (32 bytes each) and triangles (12) a
  // hundred times over: less than half.
  Geometry one;
  one.addSphere({0, 0, 0}, 0.4);
  const MeshBatch ballBatch = batchByMaterial(one).front();
  const std::size_t ballBytes = ballBatch.positions.size() * 32 + ballBatch.indices.size() * 4;
  EXPECT_LT(bytes.size(), 100 * ballBytes / 2) << bytes.size() << " against " << 100 * ballBytes;
}

// Lines become tubes whose radius is kLineRadiusFraction of the run's diagonal.
TEST(GlbWriter, LinesAreTubesOfAFractionOfTheModelsSize) {
  SceneBuilder frame(0);
  frame.cell(1, "F", {0, 0, 0}, glm::dmat3(1.0), [](Geometry& g) { g.addSegment({0, 0, 0}, {30, 0, 0}); });
  frame.cell(2, "F", {30, 0, 0}, turnedAboutZ(90), [](Geometry& g) { g.addSegment({30, 0, 0}, {30, 40, 0}); });
  GlbAnimationWriter writer;
  writer.addFrame(frame.scene);
  const Glb glb(written(writer));
  for (const auto& p : glb.json["meshes"][0]["primitives"]) EXPECT_EQ(p["mode"], 4) << "triangles only";
  // In world units: joint scale times the shape's distance from its axis (its local x).
  const double diagonal = 50;  // of the 30 x 40 box
  for (const char* name : {"F 1", "F 2"}) {
    const int node = glb.node(name);
    ASSERT_GE(node, 0);
    const double scale = glb.json["nodes"][node]["scale"][0].get<double>();
    EXPECT_NEAR(scale, std::string(name) == "F 1" ? 15 : 20, 1e-9) << "half the segment's length";
  }
  // Both segments are the same tube at different scales: one shape, whose radius is that
  // of the mean scale (17.5).
  ASSERT_EQ(writer.parts().shapes().size(), 1u);
  const auto& primitive = glb.json["meshes"][0]["primitives"][0];
  const std::vector<double> p = glb.values(primitive["attributes"]["POSITION"].get<int>());
  double widest = 0;
  for (std::size_t v = 0; v < p.size(); v += 3) widest = std::max(widest, std::hypot(p[v + 1], p[v + 2]));
  EXPECT_NEAR(widest * 17.5, diagonal * kLineRadiusFraction, 1e-6);
}

// A cell whose part changes beyond a scale (a ball, then a rod) takes a second joint: each
// is shown (scale 1) in its own frames and hidden (scale 0) in the other's, by STEP.
TEST(GlbWriter, AShapeThatChangesSwitchesJoints) {
  GlbAnimationWriter writer;
  for (int f = 0; f < 4; ++f) {
    SceneBuilder frame(f);
    frame.cell(5, "X", {0, 0, 0}, glm::dmat3(1.0), [&](Geometry& g) {
      if (f < 2)
        g.addSphere({0, 0, 0}, 1);
      else
        g.addCylinder({0, 0, 0}, {1, 0, 0}, 0.2, true);
    });
    writer.addFrame(frame.scene);
  }
  ASSERT_EQ(writer.parts().joints().size(), 2u);
  const Glb glb(written(writer));
  const int first = glb.node("X 5"), second = glb.node("X 5 ~1");
  ASSERT_GE(first, 0);
  ASSERT_GE(second, 0);
  std::string interpolation;
  glb.channel(first, "scale", &interpolation);
  EXPECT_EQ(interpolation, "STEP");
  for (int f = 0; f < 4; ++f) {
    EXPECT_EQ(glb.sample(first, "scale", f) > 0, f < 2) << f;
    EXPECT_EQ(glb.sample(second, "scale", f) > 0, f >= 2) << f;
  }
  // Without animation the last frame shows: the ball's joint rests hidden.
  EXPECT_EQ(glb.json["nodes"][first]["scale"][0].get<double>(), 0.0);
}

// A run longer than kMaxAnimationSeconds is played faster to last that long, and says so.
TEST(GlbWriter, ALongRunIsPlayedInTenSeconds) {
  GlbAnimationWriter writer;
  for (int f = 0; f < 5; ++f) {
    SceneBuilder frame(2 + 10.0 * f);
    frame.cell(1, "B", {0, 0, 0}, glm::dmat3(1.0), [&](Geometry& g) { g.addSphere({f, 0, 0}, 1); });
    writer.addFrame(frame.scene);
  }
  const Glb glb(written(writer));
  const std::vector<double> keys = glb.keys();
  ASSERT_EQ(keys.size(), 5u);
  EXPECT_FLOAT_EQ(keys[4], kMaxAnimationSeconds);
  EXPECT_FLOAT_EQ(keys[1], kMaxAnimationSeconds / 4);
  const auto& extras = glb.json["scenes"][0]["extras"];
  EXPECT_DOUBLE_EQ(extras["ontogen_time_start"].get<double>(), 2);
  EXPECT_DOUBLE_EQ(extras["ontogen_time_scale"].get<double>(), kMaxAnimationSeconds / 40);
}

// The camera sees the centre of every frame's box down its -z axis, from the pictures'
// default view, far enough for the box's sphere to fill its field of view; the key light
// is a KHR_lights_punctual directional light.
TEST(GlbWriter, ACameraFramesEveryFrameAndAKeyLightShines) {
  GlbAnimationWriter writer;
  for (int f = 0; f < 2; ++f) {
    SceneBuilder frame(f);
    frame.cell(1, "B", {0, 0, 0}, glm::dmat3(1.0), [&](Geometry& g) { g.addCylinder({0, 0, 0}, {0, 4.0 + 4 * f, 0}, 1, true); });
    writer.addFrame(frame.scene);
  }
  const Glb glb(written(writer));
  const int camera = glb.node("ontogen camera");
  ASSERT_GE(camera, 0);
  const auto& node = glb.json["nodes"][camera];
  const glm::dvec3 eye(node["translation"][0].get<double>(), node["translation"][1].get<double>(),
                       node["translation"][2].get<double>());
  const glm::dquat q(node["rotation"][3].get<double>(), node["rotation"][0].get<double>(),
                     node["rotation"][1].get<double>(), node["rotation"][2].get<double>());
  const glm::dvec3 looking = q * glm::dvec3(0, 0, -1);
  const Box& box = writer.parts().bounds();
  const glm::dvec3 centre = (box.min + box.max) * 0.5;
  EXPECT_NEAR(box.max.y, 8, 1e-12) << "the union of both frames";
  EXPECT_NEAR(glm::length(glm::normalize(centre - eye) - looking), 0, 1e-9);
  const double radius = 0.5 * glm::length(box.max - box.min);
  EXPECT_NEAR(glm::length(centre - eye), radius / std::sin(gltf::kCameraFov / 2) * 1.05, 1e-9);
  EXPECT_NEAR(looking.y, -std::sin(20 * M_PI / 180), 1e-9) << "20 degrees of elevation";
  const auto& light = glb.json["extensions"]["KHR_lights_punctual"]["lights"][0];
  EXPECT_EQ(light["type"], "directional");
  EXPECT_EQ(light["intensity"].get<double>(), gltf::kKeyLightLux);
  EXPECT_NE(std::find(glb.json["extensionsUsed"].begin(), glb.json["extensionsUsed"].end(), "KHR_lights_punctual"),
            glb.json["extensionsUsed"].end());
}

// ---- The models, through the Khronos validator and Blender --------------------------

namespace fs = std::filesystem;
using testing_support::runCommand;

// Runs a model into its own folder and returns the .glb's path. The folder is named by the
// test too: ctest runs each test in its own process, two at a time, and a folder shared by
// two tests would be removed by one while the other writes into it.
fs::path runModel(const std::string& model, std::optional<int> frames, std::optional<double> until = {}) {
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "glb_writer_test" /
                       ::testing::UnitTest::GetInstance()->current_test_info()->name() / model;
  fs::remove_all(dir);
  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  RunDef def;
  // Named by its full path: the flower reads its surfaces beside it.
  const std::string path = (fs::path(ONTOGEN_SOURCE_DIR) / "models" / model).string();
  def.program = compileSource(path, testing_support::readModel(model), sink, options);
  EXPECT_NE(def.program, nullptr) << formatDiagnostics(sink);
  def.stem = fs::path(model).stem().string();
  def.frames = frames;
  def.until = until;
  def.setOptions.formats = "glb";
  def.out = dir;
  Run run(std::move(def));
  const RunReport report = run.execute();
  EXPECT_TRUE(report.ok()) << (report.diagnostics.empty() ? "" : report.diagnostics[0].message);
  return dir / (fs::path(model).stem().string() + ".glb");
}

std::string validatorModules() {
  const fs::path modules = fs::path(ONTOGEN_SOURCE_DIR) / ".tools" / "node_modules";
  return fs::exists(modules / "gltf-validator" / "package.json") ? modules.string() : "";
}

// The three models of the checks, grown once for every test of this file.
struct Models {
  fs::path flower = runModel("flower.cell", 12);            // 12 frames over 10 s
  fs::path colony = runModel("colony.cell", 4, 10.0);       // 4 frames over 10 s: ~200 cells
  fs::path koch = runModel("koch.cell", std::nullopt);      // n = 4: 625 lines, one frame
};
const Models& models() {
  static const Models grown;
  return grown;
}

TEST(GlbModels, TheFlowerTheColonyAndKochPassTheKhronosValidator) {
  const std::string modules = validatorModules();
  ONTOGEN_REQUIRE_CHECKER(!modules.empty(), "gltf-validator not installed (bash .ci/setup installs it)");
  const fs::path script = fs::path(ONTOGEN_SOURCE_DIR) / "tests" / "interpreters" / "validate_gltf.js";
  for (const fs::path& file : {models().flower, models().colony, models().koch}) {
    auto [status, report] = runCommand("node '" + script.string() + "' '" + modules + "' '" + file.string() + "' 2>&1");
    EXPECT_EQ(status, 0) << file << ": " << report;
    EXPECT_NE(report.find("errors 0 warnings 0"), std::string::npos) << file << ": " << report;
  }
}

// What Blender 3.4 makes of the files (blender_glb.py): objects, actions, frame ranges,
// custom properties, UV maps, and the colours of a flat Workbench render through the
// file's camera, by file name.
std::map<std::string, nlohmann::json> blenderReports() {
  const fs::path script = fs::path(ONTOGEN_SOURCE_DIR) / "tests" / "interpreters" / "formats" / "blender_glb.py";
  auto [status, output] = runCommand("blender -b --factory-startup --python '" + script.string() + "' -- 96 -1 '" +
                                     models().flower.string() + "' '" + models().colony.string() + "' '" +
                                     models().koch.string() + "' 2>&1");
  std::map<std::string, nlohmann::json> reports;
  for (std::size_t at = output.find("ONTOGEN-REPORT "); at != std::string::npos;
       at = output.find("ONTOGEN-REPORT ", at + 1)) {
    const nlohmann::json report = nlohmann::json::parse(output.substr(at + 15, output.find('\n', at) - at - 15));
    reports[report["file"].get<std::string>()] = report;
  }
  EXPECT_EQ(reports.size(), 3u) << output;
  return reports;
}

// Pixels of the render within `levels` of palette colour i in sRGB (8 bits).
long pixelsOf(const nlohmann::json& report, uint32_t i, int levels) {
  const Color c = paletteColor(i);
  long count = 0;
  for (const auto& entry : report["colours"]) {
    const auto& rgb = entry[0];
    if (std::abs(rgb[0].get<int>() - c.r * 255) <= levels && std::abs(rgb[1].get<int>() - c.g * 255) <= levels &&
        std::abs(rgb[2].get<int>() - c.b * 255) <= levels)
      count += entry[1].get<long>();
  }
  return count;
}

TEST(GlbModels, BlenderImportsAFewObjectsWithOneActionAndRendersThePalette) {
  ONTOGEN_REQUIRE_CHECKER(runCommand("command -v blender >/dev/null 2>&1").first == 0, "Blender is missing");
  auto reports = blenderReports();
  ASSERT_EQ(reports.size(), 3u);
  // The flower: an armature, one skinned mesh, the camera and the light; one action over
  // the run's 10 s at Blender's 24 frames a second.
  const nlohmann::json& flower = reports["flower.glb"];
  EXPECT_EQ(flower["objects"], nlohmann::json({{"ARMATURE", 1}, {"MESH", 1}, {"CAMERA", 1}, {"LIGHT", 1}})) << flower.dump();
  ASSERT_EQ(flower["actions"].size(), 1u) << flower.dump();
  EXPECT_EQ(flower["actions"][0]["range"], nlohmann::json({0.0, 240.0}));
  EXPECT_TRUE(flower["skinned"].get<bool>());
  // Each cell's id, label and birth as the bone's custom properties; (cell, birth) per
  // vertex as the second UV map.
  const auto& props = flower["bone"]["props"];
  EXPECT_TRUE(props.contains("id") && props.contains("label") && props.contains("birth")) << flower["bone"].dump();
  EXPECT_EQ(flower["bone"]["name"].get<std::string>(), props["label"].get<std::string>() + " " + props["id"].get<std::string>());
  EXPECT_EQ(flower["uv_maps"], nlohmann::json({"UVMap", "UVMap.001"}));
  EXPECT_DOUBLE_EQ(flower["scene_props"]["ontogen_time_scale"].get<double>(), 1.0);
  // The colony: its balls in the palette's colours (1, grown; 11, young) within 2 levels
  // of sRGB, all inside the picture (the camera frames every frame).
  const nlohmann::json& colony = reports["colony.glb"];
  EXPECT_EQ(colony["actions"].size(), 1u) << colony.dump();
  EXPECT_GT(pixelsOf(colony, 1, 2) + pixelsOf(colony, 11, 2), 96 * 96 / 10) << colony.dump();
  EXPECT_GT(pixelsOf(colony, 1, 2), 0) << colony.dump();
  const auto& box = colony["drawn_box"];
  ASSERT_EQ(box.size(), 4u) << colony.dump();
  EXPECT_GT(box[0].get<int>(), 0);
  EXPECT_GT(box[1].get<int>(), 0);
  EXPECT_LT(box[2].get<int>(), 95);
  EXPECT_LT(box[3].get<int>(), 95);
  // Koch's curve: lines drawn as tubes, in palette colour 0 within 2 levels.
  const nlohmann::json& koch = reports["koch.glb"];
  EXPECT_GT(pixelsOf(koch, 0, 2), 96) << koch.dump();
  EXPECT_EQ(koch["objects"]["MESH"], 3) << "625 joints: a mesh per 256";
}

}  // namespace
}  // namespace ontogen
