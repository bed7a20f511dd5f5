// .glb files of real models through independent readers: the Khronos validator, the
// OBJ of the same frame, and Blender.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
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
#include "interpreters/formats/still_glb.h"
#include "interpreters/geometry.h"
#include "interpreters/palette.h"
#include "interpreters/run.h"
#include "interpreters/scene.h"
#include "interpreters/set_registry.h"
#include "tests/checkers.h"
#include "tests/interpreters/formats/glb_reading.h"
#include "tests/core/test_support.h"
#include "tests/interpreters/external_tools.h"

namespace ontogen {
namespace {

using test::Glb;
using test::instancedLines;
using test::InstancedLine;
using test::nodeNames;

// ---- The models, through the Khronos validator and Blender --------------------------

namespace fs = std::filesystem;
using testing_support::runCommand;

// Runs a model into its own folder and returns the .glb's path. The folder is named by the
// test too: ctest runs each test in its own process, two at a time, and a folder shared by
// two tests would be removed by one while the other writes into it.
fs::path runModel(const std::string& model, std::optional<int> frames, std::optional<double> until = {},
                  const std::string& formats = "glb", unsigned threads = 1, const std::string& folder = "") {
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "glb_writer_test" /
                       ::testing::UnitTest::GetInstance()->current_test_info()->name() /
                       (folder.empty() ? model : folder);
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
  def.setOptions.formats = formats;
  def.world.threads = threads;
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
  // One frame each, with the OBJ of the same frame: Koch at n = 4 (625 lines, baked) and
  // n = 6 (15,625 lines, instanced), the cube of tubes (triangles).
  fs::path koch = runModel("koch.cell", std::nullopt, std::nullopt, "glb,obj");
  fs::path koch6 = runModel("koch.cell", std::nullopt, 6.0, "glb,obj", 1, "koch6");
  fs::path cube = runModel("cube.cell", std::nullopt, std::nullopt, "glb,obj", 1, "cube");
  // Koch grown to n = 4 over 5 frames, with each frame's OBJ: each frame's cells are new
  // and never move.
  fs::path kochFrames = runModel("koch.cell", 5, std::nullopt, "glb,obj", 1, "koch_frames");
  // And to n = 6 over 7 frames: 19,531 lines, more than kMaxBakedLines.
  fs::path kochFrames6 = runModel("koch.cell", 7, 6.0, "glb,obj", 1, "koch_frames6");
  // And to n = 7 over 8 frames: 97,656 parts, more than kMaxJoints.
  fs::path kochFrames7 = runModel("koch.cell", 8, 7.0, "glb,obj", 1, "koch_frames7");
};
const Models& models() {
  static const Models grown;
  return grown;
}

TEST(GlbModels, TheFlowerTheColonyAndKochPassTheKhronosValidator) {
  const std::string modules = validatorModules();
  ONTOGEN_REQUIRE_CHECKER(!modules.empty(), "gltf-validator not installed (bash .ci/setup installs it)");
  const fs::path script = fs::path(ONTOGEN_SOURCE_DIR) / "tests" / "interpreters" / "validate_gltf.js";
  for (const fs::path& file : {models().flower, models().colony, models().koch, models().koch6, models().cube,
                               models().kochFrames, models().kochFrames6, models().kochFrames7}) {
    auto [status, report] = runCommand("node '" + script.string() + "' '" + modules + "' '" + file.string() + "' 2>&1");
    EXPECT_EQ(status, 0) << file << ": " << report;
    EXPECT_NE(report.find("errors 0 warnings 0"), std::string::npos) << file << ": " << report;
  }
}

std::string fileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

// An OBJ as ontogen writes it: its positions, and per material its faces' (v, vt, vn)
// corners and its lines' vertices (1-based as written).
struct Obj {
  std::vector<glm::dvec3> positions;
  std::map<std::string, std::vector<std::array<long, 3>>> corners;  // three per triangle
  std::vector<std::pair<long, long>> lines;
  explicit Obj(const fs::path& path) {
    std::ifstream in(path);
    std::string line, material;
    while (std::getline(in, line)) {
      std::istringstream words(line);
      std::string tag;
      words >> tag;
      if (tag == "v") {
        glm::dvec3 p;
        words >> p.x >> p.y >> p.z;
        positions.push_back(p);
      } else if (tag == "usemtl") {
        words >> material;
      } else if (tag == "f") {
        std::string corner;
        while (words >> corner) {
          std::array<long, 3> c{};
          std::sscanf(corner.c_str(), "%ld/%ld/%ld", &c[0], &c[1], &c[2]);
          corners[material].push_back(c);
        }
      } else if (tag == "l") {
        long a = 0, b = 0;
        words >> a >> b;
        lines.emplace_back(a, b);
      }
    }
  }
};

// A one-frame run of Koch's curve at n = 4: one still mesh (and the camera and light),
// its tubes the OBJ's line segments, kTubeSides sides each.
TEST(GlbModels, OneFrameOfKochIsOneStillMeshOfTheObjsLines) {
  const Glb glb(fileBytes(models().koch));
  EXPECT_EQ(nodeNames(glb), (std::vector<std::string>{"still", "ontogen camera"}));
  EXPECT_FALSE(glb.json.contains("skins"));
  EXPECT_FALSE(glb.json.contains("animations"));
  const Obj obj(models().koch.parent_path() / "koch.obj");
  ASSERT_EQ(obj.lines.size(), 625u);
  const auto& primitive = glb.json["meshes"][0]["primitives"][0];
  EXPECT_EQ(glb.json["accessors"][primitive["attributes"]["POSITION"].get<int>()]["count"].get<std::size_t>(),
            obj.lines.size() * 2 * kTubeSides);
  EXPECT_EQ(glb.json["accessors"][primitive["indices"].get<int>()]["count"].get<std::size_t>(),
            obj.lines.size() * 2 * kTubeSides * 3);
}

// Koch's curve at n = 6 (15,625 lines): three nodes, instances of one tube, each on one
// of the OBJ's segments, in its order; the same bytes on one thread and two.
TEST(GlbModels, OneFrameOfKochAtSixIsInstancesOnTheObjsSegments) {
  const std::string bytes = fileBytes(models().koch6);
  const Glb glb(bytes);
  EXPECT_EQ(nodeNames(glb), (std::vector<std::string>{"lines 0", "ontogen camera"}));
  EXPECT_FALSE(glb.json.contains("skins"));
  EXPECT_FALSE(glb.json.contains("animations"));
  const Obj obj(models().koch6.parent_path() / "koch.obj");
  ASSERT_EQ(obj.lines.size(), 15625u);
  const auto& attributes = glb.json["nodes"][0]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
  const std::vector<double> t = glb.values(attributes["TRANSLATION"].get<int>());
  const std::vector<double> r = glb.values(attributes["ROTATION"].get<int>());
  const std::vector<double> sc = glb.values(attributes["SCALE"].get<int>());
  ASSERT_EQ(t.size(), 3 * obj.lines.size());
  for (std::size_t i = 0; i < obj.lines.size(); ++i) {
    const glm::dquat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);
    const glm::dvec3 middle(t[3 * i], t[3 * i + 1], t[3 * i + 2]);
    const glm::dvec3 half = q * glm::dvec3(0, sc[3 * i + 1], 0);
    // Koch's curve at n = 6 spans 729 units: floats hold it to about 1e-4.
    ASSERT_NEAR(glm::length(middle - half - obj.positions[obj.lines[i].first - 1]), 0, 1e-3) << i;
    ASSERT_NEAR(glm::length(middle + half - obj.positions[obj.lines[i].second - 1]), 0, 1e-3) << i;
  }
  const fs::path twoThreads = runModel("koch.cell", std::nullopt, 6.0, "glb", 2, "koch6_two_threads");
  EXPECT_TRUE(fileBytes(twoThreads) == bytes) << "the same bytes on two threads";
}

// Koch's curve grown over 5 frames: every cell shows in one frame and never moves, so
// the run is five joints, one per frame (it was a joint per cell: 788 nodes), in one skin.
TEST(GlbModels, KochGrownOverFramesIsAJointPerFrame) {
  const Glb glb(fileBytes(models().kochFrames));
  EXPECT_EQ(nodeNames(glb), (std::vector<std::string>{"frames 0 to 0", "frames 1 to 1", "frames 2 to 2", "frames 3 to 3",
                                                      "frames 4 to 4", "cells", "parts", "ontogen camera"}));
  EXPECT_EQ(glb.json["skins"].size(), 1u);
  EXPECT_EQ(glb.json["nodes"][4]["extras"]["parts"], 625);
  EXPECT_EQ(glb.json["animations"].size(), 1u);
}

// Koch's curve grown to n = 6 over 7 frames (19,531 lines, none moving while it shows):
// no skin, a node per frame of instances of one tube, each on one of that frame's OBJ
// segments in its order, shown (STEP scale) at that frame's time only. Baked, each line
// took 832 bytes: 18.8 MB.
TEST(GlbModels, KochGrownOverFramesPastTheBakedLinesIsInstancesPerFrame) {
  const std::string bytes = fileBytes(models().kochFrames6);
  const Glb glb(bytes);
  std::vector<std::string> names;
  for (int f = 0; f < 7; ++f) names.push_back("lines 0 frames " + std::to_string(f) + " to " + std::to_string(f));
  names.push_back("ontogen camera");
  EXPECT_EQ(nodeNames(glb), names);
  EXPECT_FALSE(glb.json.contains("skins"));
  std::size_t lines = 0;
  for (int f = 0; f < 7; ++f) {
    const Obj obj(models().kochFrames6.parent_path() / ("koch_000" + std::to_string(f) + ".obj"));
    ASSERT_EQ(obj.lines.size(), static_cast<std::size_t>(std::pow(5, f)));
    lines += obj.lines.size();
    const std::vector<InstancedLine> drawn = instancedLines(glb, f);
    ASSERT_EQ(drawn.size(), obj.lines.size()) << f;
    for (std::size_t i = 0; i < obj.lines.size(); ++i) {
      // Koch's curve at n = 6 spans 729 units: floats hold it to about 1e-4.
      ASSERT_NEAR(glm::length(drawn[i].from - obj.positions[obj.lines[i].first - 1]), 0, 1e-3) << f << " " << i;
      ASSERT_NEAR(glm::length(drawn[i].to - obj.positions[obj.lines[i].second - 1]), 0, 1e-3) << f << " " << i;
    }
    for (int g = 0; g < 7; ++g) EXPECT_EQ(glb.sample(f, "scale", g), f == g ? 1 : 0) << "node " << f << " at " << g;
  }
  EXPECT_EQ(lines, 19'531u);
  // 48 bytes an instance, and the JSON.
  EXPECT_LT(bytes.size(), 48 * lines + 64 * 1024);
}

// Koch's curve grown to n = 7 over 8 frames (97,656 parts, more than kMaxJoints): a node
// per frame, shown (STEP scale) at its time only, whose lines are instances of one tube
// in a node under it, each on one of that frame's OBJ segments. Baked, each line took
// 832 bytes: 68.8 MB.
TEST(GlbModels, KochGrownPastTheJointsIsANodePerFrameOfInstancedLines) {
  const std::string bytes = fileBytes(models().kochFrames7);
  const Glb glb(bytes);
  std::vector<std::string> names;
  for (int f = 0; f < 8; ++f)
    names.insert(names.end(), {"lines 0 frame " + std::to_string(f), "frame " + std::to_string(f)});
  names.push_back("ontogen camera");
  EXPECT_EQ(nodeNames(glb), names);
  std::size_t lines = 0;
  for (int f = 0; f < 8; ++f) {
    const Obj obj(models().kochFrames7.parent_path() / ("koch_000" + std::to_string(f) + ".obj"));
    ASSERT_EQ(obj.lines.size(), static_cast<std::size_t>(std::pow(5, f)));
    lines += obj.lines.size();
    const int frame = 2 * f + 1;
    EXPECT_EQ(glb.json["nodes"][frame]["children"], nlohmann::json({frame - 1}));
    EXPECT_FALSE(glb.json["nodes"][frame].contains("mesh")) << "Koch draws lines alone";
    for (int g = 0; g < 8; ++g)
      EXPECT_EQ(glb.sample(frame, "scale", g), f == g ? 1 : 0) << "frame " << f << " at " << g;
    const std::vector<InstancedLine> drawn = instancedLines(glb, frame - 1);
    ASSERT_EQ(drawn.size(), obj.lines.size()) << f;
    for (std::size_t i = 0; i < obj.lines.size(); ++i) {
      // Koch's curve at n = 7 spans 2187 units: floats hold it to about 3e-4.
      ASSERT_NEAR(glm::length(drawn[i].from - obj.positions[obj.lines[i].first - 1]), 0, 3e-3) << f << " " << i;
      ASSERT_NEAR(glm::length(drawn[i].to - obj.positions[obj.lines[i].second - 1]), 0, 3e-3) << f << " " << i;
    }
  }
  EXPECT_EQ(lines, 97'656u);
  EXPECT_LT(bytes.size(), 48 * lines + 64 * 1024);
}

// The cube of tubes in one frame: per colour, the OBJ's triangles corner by corner (the
// same positions, in the same order) and as many vertices as the OBJ's distinct corners;
// the same bytes on one thread and two.
TEST(GlbModels, OneFrameOfTheCubeIsTheObjsTrianglesByValue) {
  const std::string bytes = fileBytes(models().cube);
  const Glb glb(bytes);
  EXPECT_EQ(nodeNames(glb), (std::vector<std::string>{"still", "ontogen camera"}));
  const Obj obj(models().cube.parent_path() / "cube.obj");
  const auto& primitives = glb.json["meshes"][0]["primitives"];
  ASSERT_EQ(primitives.size(), obj.corners.size());
  std::size_t p = 0;
  for (const auto& [material, corners] : obj.corners) {
    const auto& primitive = primitives[p++];
    EXPECT_EQ(glb.json["materials"][primitive["material"].get<int>()]["name"], material);
    const std::vector<double> positions = glb.values(primitive["attributes"]["POSITION"].get<int>());
    const std::vector<double> indices = glb.values(primitive["indices"].get<int>());
    ASSERT_EQ(indices.size(), corners.size()) << material;
    std::set<std::array<long, 3>> distinct(corners.begin(), corners.end());
    EXPECT_EQ(positions.size(), 3 * distinct.size()) << material;
    for (std::size_t k = 0; k < corners.size(); ++k) {
      const glm::dvec3& expected = obj.positions[corners[k][0] - 1];
      const auto v = static_cast<std::size_t>(indices[k]);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(positions[3 * v + c], expected[c], 1e-6) << material << " " << k;
    }
  }
  const fs::path twoThreads = runModel("cube.cell", std::nullopt, std::nullopt, "glb", 2, "cube_two_threads");
  EXPECT_TRUE(fileBytes(twoThreads) == bytes) << "the same bytes on two threads";
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
  // The flower: an armature, one skinned mesh and the camera (no light); one action over
  // the run's 10 s at Blender's 24 frames a second.
  const nlohmann::json& flower = reports["flower.glb"];
  EXPECT_EQ(flower["objects"], nlohmann::json({{"ARMATURE", 1}, {"MESH", 1}, {"CAMERA", 1}})) << flower.dump();
  ASSERT_EQ(flower["actions"].size(), 1u) << flower.dump();
  EXPECT_EQ(flower["actions"][0]["range"], nlohmann::json({0.0, 240.0}));
  EXPECT_TRUE(flower["skinned"].get<bool>());
  // Each cell's id, label and birth as the bone's custom properties; (cell, birth) per
  // vertex as the second UV map.
  const auto& props = flower["bone"]["props"];
  EXPECT_TRUE(props.contains("id") && props.contains("label") && props.contains("birth")) << flower["bone"].dump();
  // (A cell's later shapes are joints of their own, named with " ~N".)
  const std::string boneName = flower["bone"]["name"].get<std::string>();
  const std::string labelAndId = props["label"].get<std::string>() + " " + props["id"].get<std::string>();
  EXPECT_TRUE(boneName == labelAndId || boneName.rfind(labelAndId + " ~", 0) == 0) << boneName;
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
  EXPECT_EQ(koch["objects"]["MESH"], 1) << "one frame: one still mesh";
}

// Blender lights a file that brings no light with its own scene (blender_lit.py: its
// startup light and world, Cycles, through the file's camera): the colony and the flower
// are drawn neither black nor washed white, and the only light is Blender's.
TEST(GlbModels, BlenderLightsTheModelWithItsOwnSceneNeitherBlackNorWhite) {
  ONTOGEN_REQUIRE_CHECKER(runCommand("command -v blender >/dev/null 2>&1").first == 0, "Blender is missing");
  const fs::path script = fs::path(ONTOGEN_SOURCE_DIR) / "tests" / "interpreters" / "formats" / "blender_lit.py";
  for (const fs::path& file : {models().colony, models().flower}) {
    auto [status, output] = runCommand("blender -b --factory-startup --python '" + script.string() + "' -- 96 '" +
                                       file.string() + "' 2>&1");
    const auto at = output.find("ONTOGEN-REPORT ");
    ASSERT_NE(at, std::string::npos) << output;
    const nlohmann::json report = nlohmann::json::parse(output.substr(at + 15, output.find('\n', at) - at - 15));
    EXPECT_EQ(report["from_file"], nlohmann::json::array()) << report.dump();
    EXPECT_EQ(report["lights"], nlohmann::json({"Light"})) << report.dump();
    const long model = report["model"].get<long>();
    EXPECT_GT(model, 96 * 96 / 100) << report.dump();
    EXPECT_LT(report["black"].get<long>(), model / 20) << report.dump();
    EXPECT_LT(report["white"].get<long>(), model / 100) << report.dump();
    EXPECT_GT(report["mean"].get<double>(), 0.05) << report.dump();
  }
}

// The distance from p to the segment [a, b].
double distanceToSegment(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec3 ab = b - a;
  const double t = glm::dot(ab, ab) > 0 ? std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0) : 0.0;
  return glm::length(p - (a + t * ab));
}

// Koch's curve grown over 5 frames, its parts skinned to one joint per frame, through
// Blender (blender_frames.py): at each of the action's five keys, the vertices Blender's
// armature shows are those of that frame's joint, each on a tube of the documented radius
// around a line of that frame's OBJ, both ends of every line reached, as many as the
// OBJ's lines make; every other joint's vertices are scaled to its origin.
TEST(GlbModels, BlenderShowsKochGrownOverFramesAsEachFramesObj) {
  ONTOGEN_REQUIRE_CHECKER(runCommand("command -v blender >/dev/null 2>&1").first == 0, "Blender is missing");
  const fs::path script = fs::path(ONTOGEN_SOURCE_DIR) / "tests" / "interpreters" / "formats" / "blender_frames.py";
  auto [status, output] = runCommand("blender -b --factory-startup --python '" + script.string() + "' -- '" +
                                     models().kochFrames.string() + "' 2>&1");
  ASSERT_EQ(status, 0) << output;
  std::vector<nlohmann::json> frames;
  for (std::size_t at = output.find("ONTOGEN-FRAME "); at != std::string::npos; at = output.find("ONTOGEN-FRAME ", at + 1))
    frames.push_back(nlohmann::json::parse(output.substr(at + 14, output.find('\n', at) - at - 14)));
  ASSERT_EQ(frames.size(), 5u) << output;
  std::vector<Obj> objs;
  Box all;
  for (int f = 0; f < 5; ++f) {
    objs.emplace_back(models().kochFrames.parent_path() / ("koch_000" + std::to_string(f) + ".obj"));
    for (const glm::dvec3& p : objs.back().positions) all.add(p);
  }
  const double radius = glm::length(all.max - all.min) * kLineRadiusFraction;
  for (int f = 0; f < 5; ++f) {
    const Obj& obj = objs[static_cast<std::size_t>(f)];
    ASSERT_EQ(obj.lines.size(), static_cast<std::size_t>(std::pow(5, f)));
    EXPECT_DOUBLE_EQ(frames[f]["time"].get<double>(), f);
    const std::string shown = "frames " + std::to_string(f) + " to " + std::to_string(f);
    ASSERT_EQ(frames[f]["bones"].size(), 5u) << frames[f].dump().substr(0, 400);
    for (const auto& [bone, xyz] : frames[f]["bones"].items()) {
      const std::vector<double> p = xyz.get<std::vector<double>>();
      if (bone != shown) {
        for (double c : p) ASSERT_NEAR(c, 0, 1e-6) << "frame " << f << ", " << bone << " is hidden at its origin";
        continue;
      }
      ASSERT_EQ(p.size(), 3 * obj.lines.size() * 2 * kTubeSides) << bone;
      std::vector<char> reachedA(obj.lines.size(), 0), reachedB(obj.lines.size(), 0);
      for (std::size_t v = 0; v < p.size() / 3; ++v) {
        const glm::dvec3 q(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
        // On some line's tube (at a corner it may lie nearer the next line, inside its
        // tube's end). Koch's curve at n = 4 spans 81 units: floats hold it to about 1e-5.
        bool onATube = false;
        for (std::size_t l = 0; l < obj.lines.size(); ++l) {
          const glm::dvec3& a = obj.positions[obj.lines[l].first - 1];
          const glm::dvec3& b = obj.positions[obj.lines[l].second - 1];
          onATube = onATube || std::abs(distanceToSegment(q, a, b) - radius) < 1e-4;
          if (glm::length(q - a) < radius + 1e-4) reachedA[l] = 1;
          if (glm::length(q - b) < radius + 1e-4) reachedB[l] = 1;
        }
        ASSERT_TRUE(onATube) << "frame " << f << ", vertex " << v << " at " << q.x << " " << q.y << " " << q.z;
      }
      for (std::size_t l = 0; l < obj.lines.size(); ++l)
        ASSERT_TRUE(reachedA[l] && reachedB[l]) << "frame " << f << ", line " << l;
    }
  }
}

}  // namespace
}  // namespace ontogen
