// The animated glTF binary read back by value: materials in linear light; each cell's
// part written once and moved by its joint (translation, rotation, scale from the
// scenes' nodes, in closed form); a shape many cells draw written once; lines as tubes of
// the documented radius; a shape that changes switching joints; the time keys; the
// camera, and no light. Whole models are in glb_models_test.cpp.

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
// three frames: two shapes, the ball a joint whose translation and scale are animated at
// the frames' times, the rod, which never moves, in the still mesh in world coordinates.
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
  const int ball = glb.node("Ball 7"), still = glb.node("still");
  ASSERT_GE(ball, 0);
  ASSERT_GE(still, 0);
  EXPECT_EQ(glb.node("Rod 9"), -1) << "a part that never moves is no joint";
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
  // The rod in world coordinates: around x = 3, z = 0, of radius 0.1, from y = 0 to 2,
  // each vertex with its cell (number 1, born at 2.25).
  const auto& rod = glb.json["meshes"][glb.json["nodes"][still]["mesh"].get<int>()]["primitives"][0]["attributes"];
  const std::vector<double> p = glb.values(rod["POSITION"].get<int>());
  ASSERT_FALSE(p.empty());
  for (std::size_t v = 0; v < p.size(); v += 3) {
    EXPECT_LE(std::hypot(p[v] - 3, p[v + 2]), 0.1 + 1e-6) << v;
    EXPECT_GE(p[v + 1], -1e-6);
    EXPECT_LE(p[v + 1], 2 + 1e-6);
  }
  const auto& bounds = glb.json["accessors"][rod["POSITION"].get<int>()];
  EXPECT_NEAR(bounds["min"][1].get<double>(), 0, 1e-6);
  EXPECT_NEAR(bounds["max"][1].get<double>(), 2, 1e-6);
  EXPECT_NEAR(bounds["max"][0].get<double>(), 3.1, 1e-6);
  const std::vector<double> cells = glb.values(rod["TEXCOORD_1"].get<int>());
  EXPECT_EQ(cells[0], 1);
  EXPECT_EQ(cells[1], 2.25);
  // One skin over the ball's joint, its inverse bind matrix the identity: shapes lie in
  // their cells' frames.
  ASSERT_EQ(glb.json["skins"].size(), 1u);
  EXPECT_EQ(glb.json["skins"][0]["joints"].size(), 1u);
  const std::vector<double> inverseBind = glb.values(glb.json["skins"][0]["inverseBindMatrices"].get<int>());
  ASSERT_EQ(inverseBind.size(), 16u);
  for (std::size_t k = 0; k < 16; ++k) EXPECT_EQ(inverseBind[k], k % 5 == 0 ? 1.0 : 0.0) << k;
  EXPECT_EQ(glb.json["meshes"].size(), 2u) << "the parts and the still mesh";
  EXPECT_EQ(glb.json["animations"].size(), 1u);
}

// A hundred cells drawing the same ball: the ball's vertices are written once, every
// cell's primitive reuses them with its own joint.
TEST(GlbWriter, AShapeManyCellsDrawIsWrittenOnce) {
  GlbAnimationWriter writer;
  for (int f = 0; f < 2; ++f) {  // two frames, the balls rising: animated parts
    SceneBuilder frame(f);
    for (int c = 0; c < 100; ++c)
      frame.cell(100 + c, "C", {0, 0, 0}, glm::dmat3(1.0), [&](Geometry& g) { g.addSphere({c % 10, c / 10, f}, 0.4); });
    writer.addFrame(frame.scene);
  }
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
  GlbAnimationWriter writer;
  for (int f = 0; f < 2; ++f) {  // two frames, the lines moving up z: animated parts
    SceneBuilder frame(f);
    const glm::dvec3 up(0, 0, f);
    frame.cell(1, "F", up, glm::dmat3(1.0), [&](Geometry& g) { g.addSegment(up, glm::dvec3(30, 0, 0) + up); });
    frame.cell(2, "F", glm::dvec3(30, 0, 0) + up, turnedAboutZ(90),
               [&](Geometry& g) { g.addSegment(glm::dvec3(30, 0, 0) + up, glm::dvec3(30, 40, 0) + up); });
    writer.addFrame(frame.scene);
  }
  const Glb glb(written(writer));
  for (const auto& p : glb.json["meshes"][0]["primitives"]) EXPECT_EQ(p["mode"], 4) << "triangles only";
  // In world units: joint scale times the shape's distance from its axis (its local x).
  const double diagonal = std::sqrt(30.0 * 30 + 40 * 40 + 1);  // of the 30 x 40 x 1 box
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
    frame.cell(5, "X", {0, 0, 0}, glm::dmat3(1.0), [&](Geometry& g) {  // moving along x
      if (f < 2)
        g.addSphere({f, 0, 0}, 1);
      else
        g.addCylinder({f, 0, 0}, {f + 1, 0, 0}, 0.2, true);
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
// default view, far enough for the box's sphere to fill its field of view. No light is
// written: a light in lux right for Blender washes a model white in three.js (docs/LANGUAGE.md).
TEST(GlbWriter, ACameraFramesEveryFrameAndNoLightIsWritten) {
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
  EXPECT_FALSE(glb.json.contains("extensions") && glb.json["extensions"].contains("KHR_lights_punctual"));
  EXPECT_EQ(glb.json.dump().find("KHR_lights_punctual"), std::string::npos) << "no light, nor its extension";
}

// ---- Runs of one frame: still meshes -------------------------------------------------


// Cells that never move while they show, each over a span of frames (A in frame 0, B in
// frames 1 and 2), beside one that moves (C): A and B are no joints of their own, but
// their span's joint ("frames 0 to 0", "frames 1 to 2"), their parts in world
// coordinates, shown by a STEP scale in their frames only.
TEST(GlbWriter, PartsSteadyOverASpanOfFramesShareTheSpansJoint) {
  GlbAnimationWriter writer;
  for (int f = 0; f < 3; ++f) {
    SceneBuilder frame(f);
    if (f == 0) frame.cell(1, "A", {0, 0, 0}, glm::dmat3(1.0), [](Geometry& g) { g.addSphere({5, 0, 0}, 1); });
    if (f > 0) {
      frame.cell(2, "B", {0, 0, 0}, glm::dmat3(1.0), [](Geometry& g) { g.addSphere({0, 5, 0}, 1); });
      frame.cell(4, "B", {0, 0, 0}, glm::dmat3(1.0), [](Geometry& g) { g.addSphere({0, 7, 0}, 1); });
    }
    frame.cell(3, "C", {0, 0, 0}, glm::dmat3(1.0), [&](Geometry& g) { g.addSphere({0, 0, f}, 0.5); });
    writer.addFrame(frame.scene);
  }
  const Glb glb(written(writer));
  EXPECT_EQ(nodeNames(glb), (std::vector<std::string>{"C 3", "frames 0 to 0", "frames 1 to 2", "cells", "parts",
                                                      "ontogen camera"}));
  ASSERT_EQ(glb.json["skins"].size(), 1u);
  EXPECT_EQ(glb.json["skins"][0]["joints"], nlohmann::json({0, 1, 2}));
  EXPECT_EQ(glb.json["nodes"][2]["extras"]["parts"], 2);
  for (int f = 0; f < 3; ++f) {
    EXPECT_EQ(glb.sample(1, "scale", f), f == 0 ? 1 : 0) << f;
    EXPECT_EQ(glb.sample(2, "scale", f), f == 0 ? 0 : 1) << f;
  }
  // The spans' vertices lie where their spheres were drawn, skinned to their span.
  std::map<int, Box> byJoint;
  for (const auto& primitive : glb.json["meshes"][0]["primitives"]) {
    const std::vector<double> p = glb.values(primitive["attributes"]["POSITION"].get<int>());
    const std::vector<double> j = glb.values(primitive["attributes"]["JOINTS_0"].get<int>());
    for (std::size_t v = 0; v < p.size() / 3; ++v) byJoint[static_cast<int>(j[4 * v])].add({p[3 * v], p[3 * v + 1], p[3 * v + 2]});
  }
  ASSERT_EQ(byJoint.size(), 3u);
  EXPECT_NEAR(byJoint[1].min.x, 4, 1e-6);
  EXPECT_NEAR(byJoint[1].max.x, 6, 1e-6);
  EXPECT_NEAR(byJoint[2].min.y, 4, 1e-6);
  EXPECT_NEAR(byJoint[2].max.y, 8, 1e-6);
}

// A frame of a ball (cell 7), a line (cell 9, colour 3) and a sphere no node covers: one
// mesh of one primitive per colour in world coordinates, nothing skinned or animated; the
// triangles are the frame's, in its order; every vertex carries (cell number, birth).
TEST(GlbWriter, ARunOfOneFrameIsOneStillMeshInWorldCoordinates) {
  SceneBuilder frame(3);
  frame.cell(7, "Ball", {1, 2, 0}, glm::dmat3(1.0), [](Geometry& g) { g.addSphere({1, 2, 0}, 0.5); });
  frame.cell(9, "F", {3, 0, 0}, turnedAboutZ(90), [](Geometry& g) {
    g.setMaterial(3);
    g.addSegment({3, 0, 0}, {3, 2, 0});
    g.setMaterial(0);
  });
  frame.scene.geometry.addSphere({-1, 0, 0}, 0.25);  // drawn between cells
  GlbAnimationWriter writer;
  writer.addFrame(frame.scene);
  EXPECT_EQ(writer.frameCount(), 1u);
  EXPECT_TRUE(writer.parts().joints().empty()) << "one frame is not taken apart";
  const Glb glb(written(writer));
  EXPECT_EQ(nodeNames(glb), (std::vector<std::string>{"still", "ontogen camera"}));
  EXPECT_FALSE(glb.json.contains("skins"));
  EXPECT_FALSE(glb.json.contains("animations"));
  ASSERT_EQ(glb.json["meshes"].size(), 1u);
  const auto& primitives = glb.json["meshes"][0]["primitives"];
  ASSERT_EQ(primitives.size(), 2u);
  // Colour 0: the frame's triangles, corner by corner.
  const Mesh& mesh = frame.scene.geometry.mesh();
  const auto& a = primitives[0]["attributes"];
  const std::vector<double> positions = glb.values(a["POSITION"].get<int>());
  const std::vector<double> cells = glb.values(a["TEXCOORD_1"].get<int>());
  const std::vector<double> indices = glb.values(primitives[0]["indices"].get<int>());
  ASSERT_EQ(indices.size(), 3 * mesh.triangles.size());
  const std::size_t ballTriangles = frame.scene.nodes[0].range.triangleCount;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(indices[3 * t + k]);
      const glm::dvec3 expected = mesh.positions[mesh.triangles[t].position[k]];
      for (int c = 0; c < 3; ++c) ASSERT_EQ(positions[3 * v + c], static_cast<float>(expected[c])) << t << " " << k;
      // The ball is cell 0, born at 1.75; the sphere between cells is the rest, cell 2.
      ASSERT_EQ(cells[2 * v], t < ballTriangles ? 0 : 2) << t;
      ASSERT_EQ(cells[2 * v + 1], t < ballTriangles ? 1.75 : 0) << t;
    }
  }
  EXPECT_EQ(glb.json["materials"][primitives[1]["material"].get<int>()]["name"], "ontogen_3");
  // Colour 3: the line as a tube of kTubeSides sides around x = 3, z = 0, from y = 0 to 2,
  // of radius kLineRadiusFraction of the frame's diagonal.
  const Box& box = frame.scene.geometry.bounds();
  const double radius = glm::length(box.max - box.min) * kLineRadiusFraction;
  const std::vector<double> tube = glb.values(primitives[1]["attributes"]["POSITION"].get<int>());
  ASSERT_EQ(tube.size(), 3u * 2 * kTubeSides);
  EXPECT_EQ(glb.values(primitives[1]["indices"].get<int>()).size(), 3u * 2 * kTubeSides);
  for (std::size_t v = 0; v < tube.size(); v += 3) {
    EXPECT_NEAR(std::hypot(tube[v] - 3, tube[v + 2]), radius, 1e-6) << v;
    EXPECT_NEAR(tube[v + 1], v % 6 == 0 ? 0 : 2, 1e-6) << v;
  }
  const std::vector<double> tubeCells = glb.values(primitives[1]["attributes"]["TEXCOORD_1"].get<int>());
  EXPECT_EQ(tubeCells[0], 1);
  EXPECT_EQ(tubeCells[1], 2.25);
}

// The tube's placement on a segment: its ends at the segment's, in every direction,
// straight down included.
TEST(GlbWriter, ATubeIsPlacedOnItsSegment) {
  const glm::dvec3 starts[] = {{0, 0, 0}, {1, 2, 3}, {0, 5, 0}, {-2, 1, 4}};
  const glm::dvec3 ends[] = {{0, 3, 0}, {4, -1, 3}, {0, 1, 0}, {-2, 1, -4}};
  for (int k = 0; k < 4; ++k) {
    const TubePlacement p = tubeOn(starts[k], ends[k], 0.1);
    EXPECT_NEAR(glm::length(p.rotation), 1, 1e-15);
    const glm::dvec3 top = p.translation + p.rotation * glm::dvec3(0, p.scale.y, 0);
    const glm::dvec3 bottom = p.translation + p.rotation * glm::dvec3(0, -p.scale.y, 0);
    EXPECT_NEAR(glm::length(top - ends[k]), 0, 1e-12) << k;
    EXPECT_NEAR(glm::length(bottom - starts[k]), 0, 1e-12) << k;
    EXPECT_EQ(p.scale.x, 0.1);
    EXPECT_EQ(p.scale.z, 0.1);
  }
}

// Past kMaxBakedLines segments, lines are instances of one tube (EXT_mesh_gpu_instancing):
// a node per colour, each instance on its segment, with its cell.
TEST(GlbWriter, ManyLinesAreInstancesOfOneTube) {
  Scene scene;
  const std::size_t count = kMaxBakedLines + 1;
  std::vector<std::pair<glm::dvec3, glm::dvec3>> drawn[2];
  for (std::size_t k = 0; k < count; ++k) {
    const uint32_t colour = k % 3 == 0 ? 2 : 0;
    const glm::dvec3 a(static_cast<double>(k % 128), static_cast<double>(k / 128), 0);
    const glm::dvec3 b = a + glm::dvec3(std::cos(0.1 * k), std::sin(0.1 * k), 0.5 * std::sin(0.7 * k));
    scene.geometry.setMaterial(colour);
    scene.geometry.addSegment(a, b);
    drawn[colour == 2].emplace_back(a, b);
  }
  GlbAnimationWriter writer;
  writer.addFrame(scene);
  const Glb glb(written(writer));
  EXPECT_EQ(nodeNames(glb), (std::vector<std::string>{"lines 0", "lines 2", "ontogen camera"}));
  EXPECT_NE(std::find(glb.json["extensionsUsed"].begin(), glb.json["extensionsUsed"].end(), "EXT_mesh_gpu_instancing"),
            glb.json["extensionsUsed"].end());
  const Box& box = scene.geometry.bounds();
  const double radius = glm::length(box.max - box.min) * kLineRadiusFraction;
  for (int n = 0; n < 2; ++n) {
    const auto& node = glb.json["nodes"][n];
    const auto& attributes = node["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
    const std::vector<double> t = glb.values(attributes["TRANSLATION"].get<int>());
    const std::vector<double> r = glb.values(attributes["ROTATION"].get<int>());
    const std::vector<double> sc = glb.values(attributes["SCALE"].get<int>());
    const std::vector<double> cell = glb.values(attributes["_CELL"].get<int>());
    ASSERT_EQ(t.size(), 3 * drawn[n].size());
    ASSERT_EQ(cell.size(), 2 * drawn[n].size());
    for (std::size_t i = 0; i < drawn[n].size(); ++i) {
      const glm::dquat q(r[4 * i + 3], r[4 * i], r[4 * i + 1], r[4 * i + 2]);
      const glm::dvec3 middle(t[3 * i], t[3 * i + 1], t[3 * i + 2]);
      const glm::dvec3 half = q * glm::dvec3(0, sc[3 * i + 1], 0);
      ASSERT_NEAR(glm::length(middle + half - drawn[n][i].second), 0, 1e-5) << n << " " << i;
      ASSERT_NEAR(glm::length(middle - half - drawn[n][i].first), 0, 1e-5) << n << " " << i;
      ASSERT_NEAR(sc[3 * i], radius, 1e-6 * radius);
      ASSERT_EQ(cell[2 * i], 0) << "no node: every segment is the rest's, cell 0";
    }
  }
  // One tube, shared by both colours' meshes.
  EXPECT_EQ(glb.json["meshes"][0]["primitives"][0]["attributes"], glb.json["meshes"][1]["primitives"][0]["attributes"]);
  EXPECT_EQ(glb.values(glb.json["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()).size(),
            3u * 2 * kTubeSides);
}

// Past kMaxBakedLines lines in parts that never move, the lines are instances of one
// tube: those of cells in both frames in a node "lines 0" shown throughout, those of
// cells new in the second frame in "lines 0 frames 1 to 1", shown (STEP scale) in it
// only; each instance on its segment in world coordinates. A ball that moves stays a
// joint, the only one: spans left without a surface are none.
TEST(GlbWriter, ManyLinesThatNeverMoveAreInstancesShownInTheirFrames) {
  const std::size_t perFrame = kMaxBakedLines / 2 + 1;
  auto lineOf = [](uint64_t id) {
    const glm::dvec3 a(static_cast<double>(id % 64), static_cast<double>(id / 64), 0);
    return std::pair{a, a + glm::dvec3(std::cos(0.1 * id), std::sin(0.1 * id), 0.25)};
  };
  GlbAnimationWriter writer;
  for (int f = 0; f < 2; ++f) {
    SceneBuilder frame(f);
    for (uint64_t id = 1; id <= perFrame * (f + 1); ++id) {
      const std::pair<glm::dvec3, glm::dvec3> line = lineOf(id);
      frame.cell(id, "F", line.first, glm::dmat3(1.0), [&](Geometry& g) { g.addSegment(line.first, line.second); });
    }
    frame.cell(9999, "Ball", {0, 0, 0}, glm::dmat3(1.0), [&](Geometry& g) { g.addSphere({f, 0, 0}, 0.5); });
    writer.addFrame(frame.scene);
  }
  const Glb glb(written(writer));
  EXPECT_EQ(nodeNames(glb), (std::vector<std::string>{"Ball 9999", "cells", "parts", "lines 0", "lines 0 frames 1 to 1",
                                                      "ontogen camera"}));
  ASSERT_EQ(glb.json["skins"].size(), 1u);
  EXPECT_EQ(glb.json["skins"][0]["joints"], nlohmann::json::array({0}));
  const double radius = glm::length(writer.parts().bounds().max - writer.parts().bounds().min) * kLineRadiusFraction;
  for (int n : {3, 4}) {
    const auto& attributes = glb.json["nodes"][n]["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
    const std::vector<double> cell = glb.values(attributes["_CELL"].get<int>());
    const std::vector<InstancedLine> drawn = instancedLines(glb, n);
    ASSERT_EQ(drawn.size(), perFrame) << n;
    for (std::size_t i = 0; i < perFrame; ++i) {
      const uint64_t id = (n == 3 ? 1 : perFrame + 1) + i;
      const auto [a, b] = lineOf(id);
      ASSERT_NEAR(glm::length(drawn[i].from - a), 0, 1e-5) << n << " " << i;
      ASSERT_NEAR(glm::length(drawn[i].to - b), 0, 1e-5) << n << " " << i;
      ASSERT_NEAR(drawn[i].radius, radius, 1e-6 * radius);
      ASSERT_EQ(cell[2 * i + 1], static_cast<float>(0.25 * static_cast<double>(id))) << "the cell's birth";
    }
  }
  EXPECT_TRUE(glb.channel(3, "scale").empty()) << "shown throughout";
  std::string interpolation;
  EXPECT_EQ(glb.channel(4, "scale", &interpolation), (std::vector<double>{0, 0, 0, 1, 1, 1}));
  EXPECT_EQ(interpolation, "STEP");
  EXPECT_EQ(glb.sample(4, "scale", 0), 0);
  EXPECT_EQ(glb.sample(4, "scale", 1), 1);
  EXPECT_FALSE(glb.json["nodes"][4].contains("scale")) << "its rest is the last frame, where it shows";
  EXPECT_FALSE(glb.channel(0, "translation").empty()) << "the ball moves";
}

}  // namespace
}  // namespace ontogen
