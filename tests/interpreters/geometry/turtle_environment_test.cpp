// The turtle commands added for colour, tropism, generalized cylinders and the
// environment of paper 004 section VI.
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "interpreters/geometry.h"
#include "interpreters/geometry/turtle.h"
#include "interpreters/geometry/turtle_commands.h"

namespace ontogen {
namespace {

struct Step {
  std::string command;
  std::vector<double> args;
};

void run(Turtle& turtle, Geometry& geometry, const std::vector<Step>& word, int repeat = 1) {
  for (int r = 0; r < repeat; ++r) {
    for (const Step& s : word) ASSERT_TRUE(turtle.execute(s.command, s.args, geometry)) << s.command;
  }
}

TEST(TurtleEnvironmentTest, FrameStaysOrthonormalOverAHundredThousandRandomCommands) {
  Turtle turtle;
  Geometry geometry;
  std::mt19937_64 random(7);
  const std::vector<std::string> commands = {"F", "+", "-", "&", "^", "\\", "/", "<", ">", "|", "$", "[", "]"};
  run(turtle, geometry, {{"tropism", {0.3, -1, 0.2, 0.1}}, {"attractor", {5, 5, 5, 0.2, 3}}, {"ceiling", {50}}});
  for (int i = 0; i < 100000; ++i) {
    const std::string& c = commands[random() % commands.size()];
    std::vector<double> args;
    if (c != "|" && c != "$" && c != "[" && c != "]" && random() % 2) args.push_back(std::uniform_real_distribution<>(-180, 180)(random));
    if (c == "F" && !args.empty()) args[0] = std::abs(args[0]) / 100;
    turtle.execute(c, args, geometry);
  }
  const TurtleState& s = turtle.state();
  EXPECT_NEAR(glm::length(s.heading), 1.0, 1e-12);
  EXPECT_NEAR(glm::length(s.left), 1.0, 1e-12);
  EXPECT_NEAR(glm::dot(s.heading, s.left), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(glm::cross(s.heading, s.left) - s.up), 0.0, 1e-12);
  EXPECT_LE(geometry.bounds().max.y, 50 + 1e-9);  // the ceiling held through it all
}

TEST(TurtleEnvironmentTest, ColorSelectsPaletteIndexForTrianglesAndLines) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"color", {3}}, {"F", {}}, {"color", {}}, {"!", {1}}, {"F", {}}, {"color", {18}}, {"sphere", {1}}});
  ASSERT_EQ(geometry.segments().size(), 1u);
  EXPECT_EQ(geometry.segments()[0].material, 3u);
  std::map<uint32_t, int> materials;
  for (const Triangle& t : geometry.mesh().triangles) ++materials[t.material];
  EXPECT_EQ(materials.size(), 2u);
  EXPECT_EQ(materials[4], 24);  // the cylinder: 12 sides, 2 triangles each
  EXPECT_GT(materials[2], 0);   // 18 mod 16
}

TEST(TurtleEnvironmentTest, TropismBendsHeadingByStrengthTimesSine) {
  Turtle turtle;
  Geometry geometry;
  // H = +y, T = +x: |H x T| = 1, so the first F turns H by e = 0.2 rad towards +x.
  run(turtle, geometry, {{"tropism", {1, 0, 0, 0.2}}, {"F", {1}}});
  EXPECT_NEAR(turtle.state().heading.x, std::sin(0.2), 1e-12);
  EXPECT_NEAR(turtle.state().heading.y, std::cos(0.2), 1e-12);
  EXPECT_NEAR(turtle.state().position.x, std::sin(0.2), 1e-12);
  // Many steps converge on T and never pass it.
  run(turtle, geometry, {{"F", {1}}}, 200);
  EXPECT_NEAR(turtle.state().heading.x, 1.0, 1e-6);
  run(turtle, geometry, {{"tropism", {0, 0, 0, 0}}, {"+", {90}}, {"F", {1}}});
  EXPECT_NEAR(glm::length(turtle.state().heading - glm::dvec3(0, 1, 0)), 0.0, 1e-6);
}

// ABOP 2.4: H turns by e |H x T| with T as given, so T's length scales the bend. With
// H = +y and e = 0.1: T = (3, 0, 0) gives |H x T| = 3, a turn of 0.3 rad; T = (1, 0, 0)
// 0.1 rad; T = (2, 2, 0), 45 degrees from H, |H x T| = 2 and 0.2 rad.
TEST(TurtleEnvironmentTest, TropismBendsByTAsGivenNotByItsDirection) {
  for (const auto& [t, radians] : {std::pair{glm::dvec3(3, 0, 0), 0.3}, std::pair{glm::dvec3(1, 0, 0), 0.1},
                                   std::pair{glm::dvec3(2, 2, 0), 0.2}}) {
    Turtle turtle;
    Geometry geometry;
    run(turtle, geometry, {{"tropism", {t.x, t.y, t.z, 0.1}}, {"F", {2}}});
    EXPECT_NEAR(turtle.state().heading.x, std::sin(radians), 1e-12) << t.x << "," << t.y;
    EXPECT_NEAR(turtle.state().heading.y, std::cos(radians), 1e-12) << t.x << "," << t.y;
    // The segment is drawn along the bent heading: it ends 2 (sin, cos) from the origin.
    EXPECT_NEAR(turtle.state().position.x, 2 * std::sin(radians), 1e-12);
    EXPECT_NEAR(turtle.state().position.y, 2 * std::cos(radians), 1e-12);
  }
}

TEST(TurtleEnvironmentTest, GeneralizedCylinderReplacesCylindersWithOneTube) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"!", {1}}, {"gcbegin", {}}, {"F", {2}}, {"+", {30}}, {"!", {0.5}}, {"F", {2}}, {"gcend", {1}}});
  EXPECT_TRUE(geometry.cylinders().empty());
  EXPECT_FALSE(geometry.mesh().triangles.empty());
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const Triangle& t : geometry.mesh().triangles) {
    for (int k = 0; k < 3; ++k) {
      uint32_t a = t.position[k], b = t.position[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  for (const auto& [edge, count] : uses) EXPECT_EQ(count, 2);
}

TEST(TurtleEnvironmentTest, BranchesDoNotExtendTheParentTubeAndOpenTubesEndAtFinish) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"!", {1}}, {"gcbegin", {}}, {"F", {}}, {"[", {}}, {"+", {}}, {"F", {}}, {"]", {}}, {"F", {}}});
  EXPECT_EQ(geometry.cylinders().size(), 1u);  // the branch drew an ordinary cylinder
  const std::size_t before = geometry.triangleCount();
  turtle.finish(geometry);
  EXPECT_GT(geometry.triangleCount(), before);  // the open tube was meshed
}

TEST(TurtleEnvironmentTest, SectionsAreDefinedAndUsed) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"section", {2}}, {"point", {1, 0}}, {"point", {0, 1}}, {"point", {-1, 0}}, {"endsection", {}},
                         {"usesection", {2}}, {"!", {1}}, {"gcbegin", {}}, {"F", {}}, {"gcend", {0}}});
  // A triangle section of 3 points: 2 rings of ... the mesher uses 3 points per ring.
  EXPECT_EQ(geometry.mesh().positions.size(), 9u * 3u);  // 8 samples + 1 rings, no caps
  EXPECT_EQ(turtle.warnings().badArguments, 0);
  run(turtle, geometry, {{"usesection", {7}}, {"circle", {2}}});
  EXPECT_EQ(turtle.warnings().badArguments, 2);
}

TEST(TurtleEnvironmentTest, CeilingIsNeverCrossedAndSegmentsKeepTheirLength) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"ceiling", {3.5}}, {"-", {20}}});
  run(turtle, geometry, {{"F", {1}}}, 10);
  ASSERT_EQ(geometry.segments().size(), 10u);
  for (const Segment& s : geometry.segments()) {
    EXPECT_LE(s.end.y, 3.5 + 1e-9);
    EXPECT_NEAR(glm::length(s.end - s.start), 1.0, 1e-12);
  }
  // Head-on: straight up into the ceiling goes sideways along L.
  Turtle up;
  Geometry g2;
  run(up, g2, {{"ceiling", {0.5}}, {"F", {1}}});
  EXPECT_NEAR(up.state().position.y, 0.0, 1e-12);
  EXPECT_NEAR(glm::length(up.state().position), 1.0, 1e-12);
}

TEST(TurtleEnvironmentTest, GroundIsNeverCrossed) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"ground", {-2}}, {"+", {150}}});
  run(turtle, geometry, {{"F", {1}}, {"+", {5}}}, 40);
  for (const Segment& s : geometry.segments()) EXPECT_GE(s.end.y, -2 - 1e-9);
}

TEST(TurtleEnvironmentTest, ObstaclesAreGoneAround) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"obstaclesphere", {0, 5, 0, 2}}, {"+", {1}}});
  run(turtle, geometry, {{"F", {0.5}}}, 30);
  for (const Segment& s : geometry.segments()) {
    for (double t = 0; t <= 1; t += 0.05) EXPECT_GE(glm::length(s.start + (s.end - s.start) * t - glm::dvec3(0, 5, 0)), 2 - 1e-9);
  }
  Turtle boxed;
  Geometry g2;
  run(boxed, g2, {{"obstaclebox", {-1, 3, -1, 1, 4, 1}}});
  run(boxed, g2, {{"F", {1}}}, 6);
  for (const Segment& s : g2.segments()) EXPECT_TRUE(s.end.y <= 3 + 1e-9 || std::abs(s.end.x) >= 1 - 1e-9);
}

TEST(TurtleEnvironmentTest, AttractorBendsGrowthTowardsItAndRepellerAway) {
  auto tip = [](const std::vector<Step>& environment) {
    Turtle turtle;
    Geometry geometry;
    run(turtle, geometry, environment);
    run(turtle, geometry, {{"F", {1}}}, 10);
    return turtle.state().position;
  };
  const glm::dvec3 point(6, 6, 0);
  glm::dvec3 free = tip({});
  glm::dvec3 attracted = tip({{"attractor", {6, 6, 0, 0.5, 5}}});
  glm::dvec3 repelled = tip({{"repeller", {6, 6, 0, 0.5, 5}}});
  EXPECT_LT(glm::length(attracted - point), glm::length(free - point) - 2);
  EXPECT_GT(glm::length(repelled - point), glm::length(free - point) + 2);
  // The first segment turns by strength |H x D| / (1 + (d / falloff)^2): d = 6 sqrt 2.
  Turtle one;
  Geometry g;
  run(one, g, {{"attractor", {6, 6, 0, 0.5, 5}}, {"F", {1}}});
  double d = 6 * std::sqrt(2.0);
  double expected = 0.5 * std::sin(std::numbers::pi / 4) / (1 + (d / 5) * (d / 5));
  EXPECT_NEAR(std::atan2(one.state().heading.x, one.state().heading.y), expected, 1e-12);
}

TEST(TurtleEnvironmentTest, ResourceAndGenerationLimitsStopGrowthWhereStated) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"maxlength", {7.5}}});
  run(turtle, geometry, {{"F", {1}}, {"[", {}}, {"+", {}}, {"F", {1}}, {"]", {}}}, 10);
  double drawn = 0;
  for (const Segment& s : geometry.segments()) drawn += glm::length(s.end - s.start);
  EXPECT_NEAR(drawn, 7.5, 1e-12);
  EXPECT_EQ(geometry.segments().size(), 8u);

  Turtle deep;
  Geometry g2;
  run(deep, g2, {{"maxdepth", {3}}});
  run(deep, g2, {{"F", {1}}, {"[", {}}, {"+", {}}, {"F", {1}}, {"F", {1}}, {"F", {1}}, {"]", {}}}, 5);
  // Path depths: main stem 1..5, each branch continues from its base's depth.
  for (const Segment& s : g2.segments()) EXPECT_LE(glm::length(s.end), 3 + 1e-9);
  EXPECT_EQ(g2.segments().size(), 3u + 2u + 1u);  // stem 3, branch at 1: 2 more, at 2: 1 more
}

}  // namespace
}  // namespace ontogen
