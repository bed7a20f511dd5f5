#include "interpreters/geometry/turtle.h"

#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "interpreters/geometry.h"
#include "interpreters/geometry/turtle_commands.h"

namespace ontogen {
namespace {

constexpr double kTolerance = 1e-9;

/// One instruction of a test word: a command and its arguments.
struct Instruction {
  std::string command;
  std::vector<double> args;
};

/// Runs a word of one-character commands without arguments.
void runSymbols(Turtle& turtle, Geometry& geometry, const std::string& word) {
  for (char c : word) ASSERT_TRUE(turtle.execute(std::string(1, c), {}, geometry)) << c;
}

void run(Turtle& turtle, Geometry& geometry, const std::vector<Instruction>& word) {
  for (const Instruction& i : word) ASSERT_TRUE(turtle.execute(i.command, i.args, geometry));
}

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance = kTolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

void expectOrthonormal(const TurtleState& s, double tolerance = kTolerance) {
  EXPECT_NEAR(glm::length(s.heading), 1.0, tolerance);
  EXPECT_NEAR(glm::length(s.left), 1.0, tolerance);
  EXPECT_NEAR(glm::length(s.up), 1.0, tolerance);
  EXPECT_LT(std::abs(glm::dot(s.heading, s.left)), tolerance);
  EXPECT_LT(std::abs(glm::dot(s.heading, s.up)), tolerance);
  EXPECT_LT(std::abs(glm::dot(s.left, s.up)), tolerance);
  // Right-handed: H x L = U.
  expectNear(glm::cross(s.heading, s.left), s.up, tolerance);
}

/// Applies D0L rules (symbol -> word) n times to word.
std::string rewrite(std::string word, char symbol, const std::string& successor, int n) {
  for (int step = 0; step < n; ++step) {
    std::string next;
    for (char c : word) next += c == symbol ? successor : std::string(1, c);
    word = next;
  }
  return word;
}

TEST(TurtleTest, StartsInAbopFrameAtOrigin) {
  Turtle turtle;
  expectNear(turtle.state().position, {0, 0, 0});
  expectNear(turtle.state().heading, {0, 1, 0});
  expectNear(turtle.state().left, {-1, 0, 0});
  expectNear(turtle.state().up, {0, 0, 1});
  EXPECT_EQ(turtle.state().radius, 0);
}

// Query modules are read by the turtle environment (interpreters/geometry/turtle_queries.h);
// the turtle itself neither moves nor draws at them.
TEST(TurtleTest, QueryModulesDrawNothingAndLeaveTheTurtleWhereItIs) {
  Turtle turtle;
  Geometry geometry;
  const double args[] = {5, 6, 7};
  for (const char* query : {"?P", "?H", "?L", "?U"}) EXPECT_TRUE(turtle.execute(query, args, geometry));
  expectNear(turtle.state().position, {0, 0, 0});
  expectNear(turtle.state().heading, {0, 1, 0});
  EXPECT_EQ(geometry.segmentCount(), 0u);
  EXPECT_EQ(turtle.warnings().badArguments, 0);
}

TEST(TurtleTest, PlusTurnsHeadingTowardsLeft) {
  Turtle turtle;
  Geometry geometry;
  runSymbols(turtle, geometry, "+");
  expectNear(turtle.state().heading, {-1, 0, 0});
  expectNear(turtle.state().left, {0, -1, 0});
  expectNear(turtle.state().up, {0, 0, 1});
}

TEST(TurtleTest, MinusTurnsHeadingAwayFromLeft) {
  Turtle turtle;
  Geometry geometry;
  runSymbols(turtle, geometry, "-");
  expectNear(turtle.state().heading, {1, 0, 0});
  expectNear(turtle.state().left, {0, 1, 0});
  expectNear(turtle.state().up, {0, 0, 1});
}

TEST(TurtleTest, PitchDownTurnsHeadingTowardsMinusUp) {
  Turtle turtle;
  Geometry geometry;
  runSymbols(turtle, geometry, "&");
  expectNear(turtle.state().heading, {0, 0, -1});
  expectNear(turtle.state().left, {-1, 0, 0});
  expectNear(turtle.state().up, {0, 1, 0});
  runSymbols(turtle, geometry, "^^");
  expectNear(turtle.state().heading, {0, 0, 1});
  expectNear(turtle.state().up, {0, -1, 0});
}

TEST(TurtleTest, RollLeftTurnsLeftTowardsMinusUp) {
  Turtle turtle;
  Geometry geometry;
  runSymbols(turtle, geometry, "\\");
  expectNear(turtle.state().heading, {0, 1, 0});
  expectNear(turtle.state().left, {0, 0, -1});
  expectNear(turtle.state().up, {-1, 0, 0});
  runSymbols(turtle, geometry, "//");
  expectNear(turtle.state().left, {0, 0, 1});
  expectNear(turtle.state().up, {1, 0, 0});
}

TEST(TurtleTest, YawUsesYawAngleByDefaultAndTurnsLikePlusAndMinus) {
  Turtle turtle(TurtleDef{.angle = 90, .yawAngle = 30});
  Geometry geometry;
  runSymbols(turtle, geometry, "<");
  const double s = std::sin(std::numbers::pi / 6);
  const double c = std::cos(std::numbers::pi / 6);
  expectNear(turtle.state().heading, {-s, c, 0});
  runSymbols(turtle, geometry, ">>");
  expectNear(turtle.state().heading, {s, c, 0});
  turtle.reset();
  const double args[] = {90};
  ASSERT_TRUE(turtle.execute("<", args, geometry));
  expectNear(turtle.state().heading, {-1, 0, 0});
}

TEST(TurtleTest, TurnAroundReversesHeadingAndKeepsUp) {
  Turtle turtle;
  Geometry geometry;
  runSymbols(turtle, geometry, "&|");
  expectNear(turtle.state().heading, {0, 0, 1});
  expectNear(turtle.state().left, {1, 0, 0});
  expectNear(turtle.state().up, {0, 1, 0});
  expectOrthonormal(turtle.state());
}

TEST(TurtleTest, SquareWithLeftTurnsReturnsToOrigin) {
  Turtle turtle;
  Geometry geometry;
  runSymbols(turtle, geometry, "F+F+F+F");
  expectNear(turtle.state().position, {0, 0, 0});
  ASSERT_EQ(geometry.segmentCount(), 4u);
  const glm::dvec3 ends[] = {{0, 1, 0}, {-1, 1, 0}, {-1, 0, 0}, {0, 0, 0}};
  for (int i = 0; i < 4; ++i) expectNear(geometry.segments()[i].end, ends[i]);
  expectNear(geometry.segments()[0].start, {0, 0, 0});
  EXPECT_EQ(geometry.triangleCount(), 0u);
}

TEST(TurtleTest, SquareWithRightTurnsGoesClockwise) {
  Turtle turtle;
  Geometry geometry;
  runSymbols(turtle, geometry, "F-F-F-F");
  ASSERT_EQ(geometry.segmentCount(), 4u);
  const glm::dvec3 ends[] = {{0, 1, 0}, {1, 1, 0}, {1, 0, 0}, {0, 0, 0}};
  for (int i = 0; i < 4; ++i) expectNear(geometry.segments()[i].end, ends[i]);
}

TEST(TurtleTest, QuadraticKochCurveEndsThreeToTheNAhead) {
  // F -> F+F-F-F+F: each F becomes five unit segments whose net step is 3 along H.
  const std::string word = rewrite("F", 'F', "F+F-F-F+F", 4);
  Turtle turtle;
  Geometry geometry;
  runSymbols(turtle, geometry, word);
  EXPECT_EQ(geometry.segmentCount(), 625u);
  expectNear(turtle.state().position, {0, 81, 0}, 1e-9);
  expectNear(turtle.state().heading, {0, 1, 0});
  // The curve never crosses to the right of its base line (x > 0 side is right).
  for (const Segment& s : geometry.segments()) EXPECT_LE(s.end.x, 1e-9);
  // Exactly reachable lattice points: every end is an integer point.
  for (const Segment& s : geometry.segments()) {
    EXPECT_NEAR(s.end.x, std::round(s.end.x), 1e-9);
    EXPECT_NEAR(s.end.y, std::round(s.end.y), 1e-9);
  }
}

TEST(TurtleTest, FrameStaysOrthonormalOverAMillionRandomRotations) {
  Turtle turtle;
  Geometry geometry;
  std::mt19937_64 random(12345);
  const std::string commands[] = {"+", "-", "&", "^", "\\", "/", "<", ">"};
  std::uniform_int_distribution<int> pick(0, 7);
  std::uniform_real_distribution<double> angle(-180.0, 180.0);
  for (int i = 0; i < 1'000'000; ++i) {
    const double args[] = {angle(random)};
    turtle.execute(commands[pick(random)], args, geometry);
  }
  // Plain rotations drift by about 1e-13 over a million steps, far inside 1e-9; the
  // re-orthonormalised frame stays within a few ulps, so the bound is 1e-15.
  const TurtleState& s = turtle.state();
  EXPECT_NEAR(glm::length(s.heading), 1.0, 1e-15);
  EXPECT_NEAR(glm::length(s.left), 1.0, 1e-15);
  EXPECT_NEAR(glm::length(s.up), 1.0, 1e-15);
  EXPECT_LT(std::abs(glm::dot(s.heading, s.left)), 1e-15);
  EXPECT_LT(std::abs(glm::dot(s.heading, s.up)), 1e-15);
  EXPECT_LT(std::abs(glm::dot(s.left, s.up)), 1e-15);
  expectNear(glm::cross(s.heading, s.left), s.up, 1e-15);
  EXPECT_EQ(turtle.warnings().badArguments, 0);
}

TEST(TurtleTest, BracketsRestorePositionFrameAndRadius) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"F", {2}}, {"&", {30}}, {"!", {0.5}}});
  const TurtleState before = turtle.state();
  run(turtle, geometry,
      {{"[", {}}, {"+", {45}}, {"/", {10}}, {"!", {2}}, {"F", {3}}, {"^", {70}}, {"]", {}}});
  EXPECT_EQ(turtle.depth(), 0u);
  expectNear(turtle.state().position, before.position, 0);
  expectNear(turtle.state().heading, before.heading, 0);
  expectNear(turtle.state().left, before.left, 0);
  expectNear(turtle.state().up, before.up, 0);
  EXPECT_EQ(turtle.state().radius, 0.5);
}

TEST(TurtleTest, UnmatchedPopIsIgnoredAndCounted) {
  Turtle turtle;
  Geometry geometry;
  runSymbols(turtle, geometry, "F]]F");
  EXPECT_EQ(turtle.warnings().unmatchedPops, 2);
  expectNear(turtle.state().position, {0, 2, 0});
  turtle.reset();
  EXPECT_EQ(turtle.warnings().unmatchedPops, 0);
}

TEST(TurtleTest, RadiusThreeForwardTenDrawsCylinderOfRadiusThreeAndLengthTen) {
  // McCormack 2004, section 4: "!(3)F(10) draws a cylinder of radius 3 units and length 10".
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"!", {3}}, {"F", {10}}});
  EXPECT_EQ(geometry.segmentCount(), 0u);
  ASSERT_EQ(geometry.cylinders().size(), 1u);
  EXPECT_EQ(geometry.cylinders()[0].radius, 3);
  EXPECT_FALSE(geometry.cylinders()[0].capped);
  expectNear(turtle.state().position, {0, 10, 0});

  const Mesh& mesh = geometry.mesh();
  ASSERT_EQ(mesh.positions.size(), 24u);  // two rings of 12
  EXPECT_EQ(geometry.triangleCount(), 24u);
  int atStart = 0;
  int atEnd = 0;
  for (const glm::dvec3& p : mesh.positions) {
    // The axis is the y axis: distance from it is the radius, y is 0 or 10.
    EXPECT_NEAR(std::hypot(p.x, p.z), 3.0, 1e-12);
    if (std::abs(p.y) < 1e-12) ++atStart;
    if (std::abs(p.y - 10) < 1e-12) ++atEnd;
  }
  EXPECT_EQ(atStart, 12);
  EXPECT_EQ(atEnd, 12);
  expectNear(geometry.bounds().min, {-3, 0, -3}, 1e-12);
  expectNear(geometry.bounds().max, {3, 10, 3}, 1e-12);
}

TEST(TurtleTest, CylinderCommandDrawsACappedCylinderAndMoves) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"!", {10}}, {"cC", {60, 1}}, {"!", {0}}, {"cC", {5}}});
  expectNear(turtle.state().position, {0, 65, 0}, 1e-12);
  ASSERT_EQ(geometry.cylinders().size(), 1u);
  EXPECT_TRUE(geometry.cylinders()[0].capped);
  expectNear(geometry.cylinders()[0].end, {0, 60, 0});
  EXPECT_EQ(geometry.triangleCount(), 48u);  // 24 side + 2 caps of 12
  // With radius 0 cC draws a line.
  ASSERT_EQ(geometry.segmentCount(), 1u);
  expectNear(geometry.segments()[0].start, {0, 60, 0});
  expectNear(geometry.segments()[0].end, {0, 65, 0});
}

TEST(TurtleTest, PistonWordOfTableOneDrawsTwoRodsAndTheWheel) {
  // McCormack 2004, Table 1, t = 0.04, with mov = f, bend = +, turn = - and radians:
  // !(10) cC(60,TRUE) +(0) !(2) cC(200,TRUE) -(0) f(50) +(1.57) [disc(0,50)]
  Turtle turtle(TurtleDef{.radians = true});
  Geometry geometry;
  run(turtle, geometry,
      {{"f", {0}}, {"!", {10}}, {"cC", {60, 1}}, {"+", {0}}, {"!", {2}}, {"cC", {200, 1}},
       {"-", {0}}, {"f", {50}}, {"+", {1.57}}, {"[", {}}, {"disc", {0, 50}}, {"]", {}}});
  ASSERT_EQ(geometry.cylinders().size(), 2u);
  EXPECT_EQ(geometry.cylinders()[0].radius, 10);
  EXPECT_EQ(geometry.cylinders()[1].radius, 2);
  expectNear(geometry.cylinders()[1].start, {0, 60, 0});
  expectNear(geometry.cylinders()[1].end, {0, 260, 0});
  ASSERT_EQ(geometry.discs().size(), 1u);
  expectNear(geometry.discs()[0].centre, {0, 310, 0});
  EXPECT_EQ(geometry.discs()[0].outer, 50);
  EXPECT_EQ(turtle.warnings().badArguments, 0);
}

TEST(TurtleTest, DiscLiesInHeadingLeftPlaneFacingUp) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"f", {4}}, {"&", {30}}, {"\\", {50}}, {"disc", {0, 5}}});
  const TurtleState& s = turtle.state();
  expectNear(s.position, {0, 4, 0});  // disc does not move the turtle
  ASSERT_EQ(geometry.discs().size(), 1u);
  const Mesh& mesh = geometry.mesh();
  ASSERT_EQ(mesh.positions.size(), 33u);  // rim of 32 and the centre
  int onRim = 0;
  for (const glm::dvec3& p : mesh.positions) {
    EXPECT_NEAR(glm::dot(p - s.position, s.up), 0.0, 1e-12);
    double r = glm::length(p - s.position);
    EXPECT_LE(r, 5 + 1e-12);
    if (std::abs(r - 5) < 1e-12) ++onRim;
  }
  EXPECT_EQ(onRim, 32);
  ASSERT_EQ(mesh.normals.size(), 1u);
  expectNear(mesh.normals[0], s.up, 1e-12);
  // Triangles wind anticlockwise seen from U.
  for (const Triangle& t : mesh.triangles) {
    glm::dvec3 n = glm::cross(mesh.positions[t.position[1]] - mesh.positions[t.position[0]],
                              mesh.positions[t.position[2]] - mesh.positions[t.position[0]]);
    EXPECT_GT(glm::dot(n, s.up), 0);
  }
}

TEST(TurtleTest, AnnulusHasInnerAndOuterRings) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"disc", {2, 3}}});
  const Mesh& mesh = geometry.mesh();
  ASSERT_EQ(mesh.positions.size(), 64u);
  std::set<long> radii;
  for (const glm::dvec3& p : mesh.positions) {
    EXPECT_EQ(p.z, 0);
    radii.insert(std::lround(glm::length(p) * 1e6));
  }
  EXPECT_EQ(radii, (std::set<long>{2'000'000, 3'000'000}));
  EXPECT_EQ(geometry.triangleCount(), 64u);
}

TEST(TurtleTest, SphereIsCentredAtTheTurtleWithOutwardTriangles) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"f", {7}}, {"sphere", {2}}});
  ASSERT_EQ(geometry.spheres().size(), 1u);
  const glm::dvec3 centre{0, 7, 0};
  const Mesh& mesh = geometry.mesh();
  for (const glm::dvec3& p : mesh.positions) EXPECT_NEAR(glm::length(p - centre), 2, 1e-12);
  EXPECT_EQ(geometry.triangleCount(), 2u * 12 + 2u * 12 * 4);
  for (const Triangle& t : mesh.triangles) {
    const glm::dvec3& a = mesh.positions[t.position[0]];
    glm::dvec3 n = glm::cross(mesh.positions[t.position[1]] - a, mesh.positions[t.position[2]] - a);
    EXPECT_GT(glm::dot(n, a - centre), 0);
    for (uint32_t k : t.normal) EXPECT_GT(glm::dot(n, mesh.normals[k]), 0);
  }
}

TEST(TurtleTest, CappedCylinderTrianglesFaceTheirNormalsAndOutwards) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"+", {20}}, {"&", {35}}, {"!", {1.5}}, {"cC", {4, 1}}});
  const CylinderPrimitive& c = geometry.cylinders().at(0);
  const glm::dvec3 middle = 0.5 * (c.start + c.end);
  const Mesh& mesh = geometry.mesh();
  for (const Triangle& t : mesh.triangles) {
    const glm::dvec3& a = mesh.positions[t.position[0]];
    const glm::dvec3& b = mesh.positions[t.position[1]];
    const glm::dvec3& d = mesh.positions[t.position[2]];
    glm::dvec3 n = glm::cross(b - a, d - a);
    EXPECT_GT(glm::dot(n, (a + b + d) / 3.0 - middle), 0);
    for (uint32_t k : t.normal) {
      EXPECT_GT(glm::dot(n, mesh.normals[k]), 0);
      EXPECT_NEAR(glm::length(mesh.normals[k]), 1.0, 1e-12);
    }
  }
}

TEST(TurtleTest, RadiansModeTakesArgumentsAndDefaultsInRadians) {
  Turtle turtle(TurtleDef{.angle = std::numbers::pi / 2, .radians = true});
  Geometry geometry;
  runSymbols(turtle, geometry, "+");
  expectNear(turtle.state().heading, {-1, 0, 0});
  const double args[] = {std::numbers::pi};
  ASSERT_TRUE(turtle.execute("-", args, geometry));
  expectNear(turtle.state().heading, {1, 0, 0});
}

TEST(TurtleTest, StepAndRadiusDefaultsComeFromTheDef) {
  Turtle turtle(TurtleDef{.step = 2.5, .radius = 0.25});
  Geometry geometry;
  runSymbols(turtle, geometry, "Ff");
  expectNear(turtle.state().position, {0, 5, 0});
  ASSERT_EQ(geometry.cylinders().size(), 1u);
  EXPECT_EQ(geometry.cylinders()[0].radius, 0.25);
}

TEST(TurtleTest, RollHorizontalMakesLeftHorizontal) {
  Turtle turtle;
  Geometry geometry;
  run(turtle, geometry, {{"&", {60}}, {"\\", {37}}, {"+", {20}}});
  const glm::dvec3 heading = turtle.state().heading;
  runSymbols(turtle, geometry, "$");
  expectNear(turtle.state().heading, heading, 0);
  EXPECT_NEAR(turtle.state().left.y, 0, 1e-12);
  EXPECT_GT(turtle.state().up.y, 0);  // upright, not upside down
  expectOrthonormal(turtle.state());
}

TEST(TurtleTest, RollHorizontalIsIgnoredWhenHeadingIsVertical) {
  Turtle turtle;
  Geometry geometry;
  runSymbols(turtle, geometry, "$");
  expectNear(turtle.state().left, {-1, 0, 0}, 0);
  expectNear(turtle.state().up, {0, 0, 1}, 0);
}

TEST(TurtleTest, UnknownCommandsReturnFalseAndBadArgumentsAreCounted) {
  Turtle turtle;
  Geometry geometry;
  EXPECT_FALSE(turtle.execute("X", {}, geometry));
  EXPECT_FALSE(turtle.execute("", {}, geometry));
  const double two[] = {1, 2};
  const double nan[] = {std::nan("")};
  const double negative[] = {-1};
  EXPECT_TRUE(turtle.execute("F", two, geometry));   // too many arguments
  EXPECT_TRUE(turtle.execute("!", {}, geometry));    // too few
  EXPECT_TRUE(turtle.execute("F", nan, geometry));   // not finite
  EXPECT_TRUE(turtle.execute("!", negative, geometry));
  EXPECT_TRUE(turtle.execute("disc", std::vector<double>{3, 2}, geometry));  // outer < inner
  EXPECT_EQ(turtle.warnings().badArguments, 5);
  expectNear(turtle.state().position, {0, 0, 0}, 0);
  EXPECT_TRUE(geometry.empty());
}

TEST(TurtleTest, InvalidDefIsRejected) {
  EXPECT_THROW(Turtle(TurtleDef{.radius = -1}), std::invalid_argument);
  EXPECT_THROW(Turtle(TurtleDef{.step = INFINITY}), std::invalid_argument);
  EXPECT_THROW(Geometry(MeshDef{.cylinderSides = 2}), std::invalid_argument);
}

TEST(TurtleCommandsTest, TableIsCompleteAndConsistent) {
  std::set<std::string_view> names;
  for (const TurtleCommand& c : turtleCommands()) {
    EXPECT_TRUE(names.insert(c.name).second) << "duplicate " << c.name;
    EXPECT_LE(c.minArity, c.maxArity) << c.name;
    EXPECT_FALSE(c.doc.empty()) << c.name;
    EXPECT_EQ(c.signature.substr(0, c.name.size()), c.name);
    EXPECT_EQ(findTurtleCommand(c.name), &c);
  }
  for (std::string_view name : {"F", "f", "+", "-", "&", "^", "\\", "/", "<", ">", "|", "[", "]",
                                "!", "cC", "disc", "sphere", "$", "color", "tropism", "circle", "section",
                                "point", "endsection", "usesection", "gcbegin", "gcend", "ceiling", "ground",
                                "obstaclesphere", "obstaclebox", "attractor", "repeller", "maxlength",
                                "maxdepth", "surface", "blend", "patch", "patchpoint", "endpatch", "plate",
                                "endplate", "gapfilter", "?P", "?H", "?L", "?U"}) {
    EXPECT_NE(findTurtleCommand(name), nullptr) << name;
  }
  EXPECT_EQ(names.size(), 47u);
  EXPECT_EQ(findTurtleCommand("c"), nullptr);
}

}  // namespace
}  // namespace ontogen
