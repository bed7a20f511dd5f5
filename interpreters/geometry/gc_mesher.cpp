#include "interpreters/geometry/gc_mesher.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace ontogen {

namespace {

constexpr int kMaxSamplesPerSpan = 256;  // finer than any picture; more only costs memory
constexpr int kMaxSectionPoints = 1024;  // as MeshDef's sides
constexpr int kDefaultCirclePoints = 12;
// Below this squared length two points are the same for the frame reflections.
constexpr double kTiny = 1e-24;

/// The section resampled to n points equally spaced by arc length, from its first point.
std::vector<glm::dvec2> resample(const GcSection& section, int n) {
  const auto& p = section.points;
  const std::size_t m = p.size();
  std::vector<double> cumulative(m + 1, 0.0);
  for (std::size_t i = 0; i < m; ++i) cumulative[i + 1] = cumulative[i] + glm::length(p[(i + 1) % m] - p[i]);
  const double total = cumulative[m];
  std::vector<glm::dvec2> out;
  out.reserve(n);
  if (m == static_cast<std::size_t>(n) || !(total > 0)) {
    for (int k = 0; k < n; ++k) out.push_back(p[k % m]);
    return out;
  }
  std::size_t edge = 0;
  for (int k = 0; k < n; ++k) {
    double s = total * k / n;
    while (edge + 1 < m && cumulative[edge + 1] <= s) ++edge;
    double length = cumulative[edge + 1] - cumulative[edge];
    double t = length > 0 ? (s - cumulative[edge]) / length : 0.0;
    out.push_back(p[edge] + (p[(edge + 1) % m] - p[edge]) * t);
  }
  return out;
}

/// A unit vector perpendicular to the unit vector axis, as close to side as possible.
glm::dvec3 perpendicularTo(const glm::dvec3& axis, const glm::dvec3& side) {
  glm::dvec3 across = side - axis * glm::dot(axis, side);
  if (glm::dot(across, across) > 1e-18) return glm::normalize(across);
  glm::dvec3 a = glm::abs(axis);
  glm::dvec3 pick = (a.x <= a.y && a.x <= a.z) ? glm::dvec3(1, 0, 0)
                    : (a.y <= a.z)             ? glm::dvec3(0, 1, 0)
                                               : glm::dvec3(0, 0, 1);
  return glm::normalize(pick - axis * glm::dot(axis, pick));
}

struct Sample {
  glm::dvec3 centre;
  glm::dvec3 tangent;  // unit
  double radius;
  std::size_t span;    // control point before
  double t;            // 0..1 along the span
};

}  // namespace

GcSection circleSection(int points) {
  GcSection section;
  for (int i = 0; i < points; ++i) {
    double angle = 2.0 * std::numbers::pi * i / points;
    section.points.emplace_back(std::cos(angle), std::sin(angle));
  }
  return section;
}

Mesh meshGeneralizedCylinder(std::span<const GcControlPoint> input, const GcDef& def) {
  if (def.samplesPerSpan < 1 || def.samplesPerSpan > kMaxSamplesPerSpan) {
    throw std::invalid_argument("GcDef::samplesPerSpan must be in 1.." + std::to_string(kMaxSamplesPerSpan));
  }
  if (def.sectionPoints != 0 && (def.sectionPoints < 3 || def.sectionPoints > kMaxSectionPoints)) {
    throw std::invalid_argument("GcDef::sectionPoints must be 0 or in 3.." + std::to_string(kMaxSectionPoints));
  }
  // Repeated positions (f(0), a turn between two points) would give a zero chord.
  std::vector<GcControlPoint> points;
  for (const GcControlPoint& p : input) {
    if (p.section != nullptr && p.section->points.size() < 3) {
      throw std::invalid_argument("a generalized cylinder section needs at least 3 points");
    }
    if (!points.empty() && glm::dot(p.position - points.back().position, p.position - points.back().position) < kTiny) {
      points.back().radius = p.radius;
      points.back().section = p.section;
      continue;
    }
    points.push_back(p);
  }
  Mesh mesh;
  if (points.size() < 2) return mesh;

  static const GcSection kDefaultCircle = circleSection(kDefaultCirclePoints);
  int n = def.sectionPoints;
  if (n == 0) {
    for (const GcControlPoint& p : points) {
      n = std::max<int>(n, static_cast<int>((p.section ? *p.section : kDefaultCircle).points.size()));
    }
    n = std::min(n, kMaxSectionPoints);
  }
  std::vector<std::vector<glm::dvec2>> rings;
  rings.reserve(points.size());
  for (const GcControlPoint& p : points) rings.push_back(resample(p.section ? *p.section : kDefaultCircle, n));

  // Hermite spline with Catmull-Rom tangents.
  const std::size_t count = points.size();
  std::vector<glm::dvec3> tangents(count);
  for (std::size_t i = 0; i < count; ++i) {
    const glm::dvec3& before = points[i == 0 ? 0 : i - 1].position;
    const glm::dvec3& after = points[i + 1 == count ? i : i + 1].position;
    tangents[i] = (i == 0 || i + 1 == count) ? after - before : (after - before) * 0.5;
  }
  std::vector<Sample> samples;
  const int perSpan = def.samplesPerSpan;
  for (std::size_t span = 0; span + 1 < count; ++span) {
    const glm::dvec3& p0 = points[span].position;
    const glm::dvec3& p1 = points[span + 1].position;
    const glm::dvec3& m0 = tangents[span];
    const glm::dvec3& m1 = tangents[span + 1];
    const int last = span + 2 == count ? perSpan : perSpan - 1;
    for (int k = 0; k <= last; ++k) {
      double t = static_cast<double>(k) / perSpan;
      double t2 = t * t, t3 = t2 * t;
      glm::dvec3 c = (2 * t3 - 3 * t2 + 1) * p0 + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * p1 + (t3 - t2) * m1;
      glm::dvec3 d = (6 * t2 - 6 * t) * p0 + (3 * t2 - 4 * t + 1) * m0 + (-6 * t2 + 6 * t) * p1 + (3 * t2 - 2 * t) * m1;
      if (glm::dot(d, d) < kTiny) d = p1 - p0;
      double radius = points[span].radius + (points[span + 1].radius - points[span].radius) * t;
      samples.push_back({c, glm::normalize(d), std::max(radius, 0.0), span, t});
    }
  }

  // Rotation-minimising frames by double reflection.
  const std::size_t ringCount = samples.size();
  std::vector<glm::dvec3> sides(ringCount);
  sides[0] = perpendicularTo(samples[0].tangent, points[0].side);
  for (std::size_t i = 0; i + 1 < ringCount; ++i) {
    glm::dvec3 v1 = samples[i + 1].centre - samples[i].centre;
    double c1 = glm::dot(v1, v1);
    glm::dvec3 r = sides[i];
    glm::dvec3 t = samples[i].tangent;
    if (c1 > kTiny) {
      r -= (2.0 / c1) * glm::dot(v1, r) * v1;
      t -= (2.0 / c1) * glm::dot(v1, t) * v1;
    }
    glm::dvec3 v2 = samples[i + 1].tangent - t;
    double c2 = glm::dot(v2, v2);
    if (c2 > kTiny) r -= (2.0 / c2) * glm::dot(v2, r) * v2;
    sides[i + 1] = perpendicularTo(samples[i + 1].tangent, r);
  }

  // Positions: ring a, point k at index a * n + k.
  mesh.positions.reserve(ringCount * n + 2);
  std::vector<double> arc(ringCount, 0.0);
  for (std::size_t a = 0; a < ringCount; ++a) {
    const Sample& s = samples[a];
    glm::dvec3 x = sides[a];
    glm::dvec3 y = glm::cross(s.tangent, x);  // x, y, tangent right-handed: rings anticlockwise
    const auto& from = rings[s.span];
    const auto& to = rings[std::min(s.span + 1, count - 1)];
    for (int k = 0; k < n; ++k) {
      glm::dvec2 q = from[k] + (to[k] - from[k]) * s.t;
      mesh.positions.push_back(s.centre + s.radius * (q.x * x + q.y * y));
    }
    if (a > 0) arc[a] = arc[a - 1] + glm::length(s.centre - samples[a - 1].centre);
  }
  // Smooth normals from the grid of positions; where the ring has collapsed (radius 0)
  // the section's own outward normal is used.
  mesh.normals.reserve(ringCount * n + 2);
  for (std::size_t a = 0; a < ringCount; ++a) {
    std::size_t before = a == 0 ? 0 : a - 1;
    std::size_t after = a + 1 == ringCount ? a : a + 1;
    for (int k = 0; k < n; ++k) {
      const glm::dvec3 along = mesh.positions[after * n + k] - mesh.positions[before * n + k];
      const glm::dvec3 around = mesh.positions[a * n + (k + 1) % n] - mesh.positions[a * n + (k + n - 1) % n];
      glm::dvec3 normal = glm::cross(around, along);
      if (glm::dot(normal, normal) < kTiny) {
        glm::dvec3 x = sides[a];
        glm::dvec3 y = glm::cross(samples[a].tangent, x);
        const auto& ring = rings[samples[a].span];
        glm::dvec2 d = ring[(k + 1) % n] - ring[(k + n - 1) % n];
        normal = d.y * x - d.x * y;
        if (glm::dot(normal, normal) < kTiny) normal = x;
      }
      mesh.normals.push_back(glm::normalize(normal));
    }
  }
  // Texture coordinates: u around (n + 1 columns, the seam repeated), v along by arc length.
  const double total = arc.back() > 0 ? arc.back() : 1.0;
  for (std::size_t a = 0; a < ringCount; ++a) {
    for (int k = 0; k <= n; ++k) mesh.texcoords.emplace_back(static_cast<double>(k) / n, arc[a] / total);
  }
  const auto un = static_cast<uint32_t>(n);
  for (uint32_t a = 0; a + 1 < ringCount; ++a) {
    for (uint32_t k = 0; k < un; ++k) {
      uint32_t j = (k + 1) % un;
      uint32_t i0 = a * un + k, i1 = a * un + j, i2 = (a + 1) * un + j, i3 = (a + 1) * un + k;
      uint32_t t0 = a * (un + 1) + k, t1 = t0 + 1, t2 = (a + 1) * (un + 1) + k + 1, t3 = t2 - 1;
      mesh.triangles.push_back({{i0, i1, i2}, {i0, i1, i2}, {t0, t1, t2}, 0});
      mesh.triangles.push_back({{i0, i2, i3}, {i0, i2, i3}, {t0, t2, t3}, 0});
    }
  }
  if (def.caps) {
    const uint32_t lastRing = static_cast<uint32_t>(ringCount - 1) * un;
    const auto startCentre = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.push_back(samples.front().centre);
    mesh.positions.push_back(samples.back().centre);
    const auto down = static_cast<uint32_t>(mesh.normals.size());
    mesh.normals.push_back(-samples.front().tangent);
    mesh.normals.push_back(samples.back().tangent);
    const auto centreUv = static_cast<uint32_t>(mesh.texcoords.size());
    mesh.texcoords.emplace_back(0.5, 0.0);
    mesh.texcoords.emplace_back(0.5, 1.0);
    for (uint32_t k = 0; k < un; ++k) {
      uint32_t j = (k + 1) % un;
      mesh.triangles.push_back({{startCentre, j, k}, {down, down, down}, {centreUv, j, k}, 0});
      mesh.triangles.push_back({{startCentre + 1, lastRing + k, lastRing + j},
                                {down + 1, down + 1, down + 1},
                                {centreUv + 1, (static_cast<uint32_t>(ringCount) - 1) * (un + 1) + k,
                                 (static_cast<uint32_t>(ringCount) - 1) * (un + 1) + k + 1},
                                0});
    }
  }
  return mesh;
}

}  // namespace ontogen
