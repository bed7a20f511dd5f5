#include "interpreters/geometry/gc_mesher.h"

#include <cmath>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace ontogen {
namespace {

/// How many faces use each undirected edge (by position index).
std::map<std::pair<uint32_t, uint32_t>, int> edgeUses(const Mesh& mesh) {
  std::map<std::pair<uint32_t, uint32_t>, int> uses;
  for (const Triangle& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      uint32_t a = t.position[k], b = t.position[(k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  return uses;
}

/// A bent path of control points with changing radius, like the horn of paper 000 Fig. 3.
std::vector<GcControlPoint> horn(int count) {
  std::vector<GcControlPoint> points;
  glm::dvec3 p(0.0);
  glm::dvec3 h(0, 1, 0);
  for (int i = 0; i < count; ++i) {
    points.push_back({p, {-1, 0, 0}, 1.0 - 0.9 * i / (count - 1), nullptr});
    double turn = 0.3;
    h = glm::normalize(glm::dvec3(h.x * std::cos(turn) - h.y * std::sin(turn), h.x * std::sin(turn) + h.y * std::cos(turn),
                                  0.2 * std::sin(i)));
    p += h;
  }
  return points;
}

TEST(GcMesherTest, ClosedTubeIsWatertight) {
  Mesh mesh = meshGeneralizedCylinder(horn(12), GcDef{.samplesPerSpan = 6, .caps = true});
  ASSERT_FALSE(mesh.triangles.empty());
  for (const auto& [edge, uses] : edgeUses(mesh)) {
    EXPECT_EQ(uses, 2) << edge.first << "-" << edge.second;
  }
  // 11 spans of 6 rings plus the last ring, 12 points each, plus two cap centres.
  EXPECT_EQ(mesh.positions.size(), (11u * 6u + 1u) * 12u + 2u);
  // Every ring joins the next: 2 triangles per quad, 2 caps of 12.
  EXPECT_EQ(mesh.triangles.size(), (11u * 6u) * 12u * 2u + 24u);
}

TEST(GcMesherTest, OpenTubeHasBoundaryOnlyAtItsEnds) {
  Mesh mesh = meshGeneralizedCylinder(horn(5), GcDef{.samplesPerSpan = 4, .caps = false});
  int boundary = 0;
  for (const auto& [edge, uses] : edgeUses(mesh)) {
    EXPECT_LE(uses, 2);
    if (uses == 1) ++boundary;
  }
  EXPECT_EQ(boundary, 2 * 12);  // the two end rings
}

TEST(GcMesherTest, NormalsAreUnitAndPointOutwards) {
  std::vector<GcControlPoint> points = horn(8);
  Mesh mesh = meshGeneralizedCylinder(points, GcDef{.samplesPerSpan = 8, .caps = false});
  for (const glm::dvec3& n : mesh.normals) EXPECT_NEAR(glm::length(n), 1.0, 1e-12);
  // Each triangle's geometric normal agrees with its corners' normals (outward winding).
  for (const Triangle& t : mesh.triangles) {
    glm::dvec3 a = mesh.positions[t.position[0]], b = mesh.positions[t.position[1]], c = mesh.positions[t.position[2]];
    glm::dvec3 face = glm::cross(b - a, c - a);
    if (glm::length(face) < 1e-12) continue;
    EXPECT_GT(glm::dot(face, mesh.normals[t.normal[0]]), 0);
  }
}

TEST(GcMesherTest, PassesThroughEveryControlPointWithItsRadius) {
  std::vector<GcControlPoint> points = horn(6);
  const int perSpan = 5;
  Mesh mesh = meshGeneralizedCylinder(points, GcDef{.samplesPerSpan = perSpan, .caps = false});
  const std::size_t n = 12;
  for (std::size_t i = 0; i < points.size(); ++i) {
    std::size_t ring = i * perSpan;
    glm::dvec3 centre(0.0);
    for (std::size_t k = 0; k < n; ++k) centre += mesh.positions[ring * n + k];
    centre /= static_cast<double>(n);
    EXPECT_NEAR(glm::length(centre - points[i].position), 0.0, 1e-9) << i;
    EXPECT_NEAR(glm::length(mesh.positions[ring * n] - points[i].position), points[i].radius, 1e-9) << i;
  }
}

TEST(GcMesherTest, NoTwistBetweenConsecutiveRings) {
  // A helix: the rotation-minimising frame turns only as much as the curve bends.
  std::vector<GcControlPoint> points;
  for (int i = 0; i < 40; ++i) {
    double a = i * 0.4;
    points.push_back({{3 * std::cos(a), 0.5 * i, 3 * std::sin(a)}, {-1, 0, 0}, 0.5, nullptr});
  }
  const int perSpan = 8;
  Mesh mesh = meshGeneralizedCylinder(points, GcDef{.samplesPerSpan = perSpan, .caps = false});
  const std::size_t n = 12;
  const std::size_t rings = mesh.positions.size() / n;
  double worst = 0;
  for (std::size_t a = 0; a + 1 < rings; ++a) {
    glm::dvec3 c0(0.0), c1(0.0);
    for (std::size_t k = 0; k < n; ++k) {
      c0 += mesh.positions[a * n + k];
      c1 += mesh.positions[(a + 1) * n + k];
    }
    c0 /= double(n);
    c1 /= double(n);
    glm::dvec3 r0 = glm::normalize(mesh.positions[a * n] - c0);
    glm::dvec3 r1 = glm::normalize(mesh.positions[(a + 1) * n] - c1);
    worst = std::max(worst, std::acos(std::clamp(glm::dot(r0, r1), -1.0, 1.0)));
  }
  // The curve turns by about 0.4 / 8 rad per ring plus the climb; a twist would add more.
  EXPECT_LT(worst, 0.1);
}

TEST(GcMesherTest, SectionsAreResampledAndBlended) {
  GcSection square{{{1, 0}, {0, 1}, {-1, 0}, {0, -1}}};
  std::vector<GcControlPoint> points = {{{0, 0, 0}, {-1, 0, 0}, 1, &square}, {{0, 4, 0}, {-1, 0, 0}, 1, nullptr}};
  Mesh mesh = meshGeneralizedCylinder(points, GcDef{.samplesPerSpan = 4, .caps = true});
  // 12 points per ring (the circle's), the first ring on the square's edges.
  const glm::dvec3 corner = mesh.positions[0];
  EXPECT_NEAR(std::abs(corner.x) + std::abs(corner.z), 1.0, 1e-12);
  const glm::dvec3 mid = mesh.positions[1];  // 1/12 of the way round the square's perimeter
  EXPECT_NEAR(std::abs(mid.x) + std::abs(mid.z), 1.0, 1e-12);
  for (const auto& [edge, uses] : edgeUses(mesh)) EXPECT_EQ(uses, 2);
}

TEST(GcMesherTest, TooFewPointsGiveNothingAndBadDefsThrow) {
  EXPECT_TRUE(meshGeneralizedCylinder(std::vector<GcControlPoint>{{}}).triangles.empty());
  EXPECT_THROW(meshGeneralizedCylinder(horn(3), GcDef{.samplesPerSpan = 0}), std::invalid_argument);
  GcSection line{{{0, 0}, {1, 0}}};
  std::vector<GcControlPoint> points = horn(3);
  points[0].section = &line;
  EXPECT_THROW(meshGeneralizedCylinder(points), std::invalid_argument);
}

}  // namespace
}  // namespace ontogen
