#include "interpreters/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace ontogen {

namespace {

// 1024 sides is already finer than any output resolution; more only costs memory.
constexpr int kMaxSides = 1024;

int checkSides(const char* field, int value, int min) {
  if (value < min || value > kMaxSides) {
    throw std::invalid_argument(std::string("MeshDef::") + field + " must be in " +
                                std::to_string(min) + ".." + std::to_string(kMaxSides) +
                                ", got " + std::to_string(value));
  }
  return value;
}

/// A unit vector perpendicular to the unit vector axis, as close to side as possible.
glm::dvec3 perpendicular(const glm::dvec3& axis, const glm::dvec3& side) {
  glm::dvec3 across = side - axis * glm::dot(axis, side);
  double length = glm::length(across);
  if (length > 1e-9) return across / length;
  // side is parallel to the axis: take the world axis least aligned with it.
  glm::dvec3 a = glm::abs(axis);
  glm::dvec3 pick = (a.x <= a.y && a.x <= a.z) ? glm::dvec3(1, 0, 0)
                    : (a.y <= a.z)             ? glm::dvec3(0, 1, 0)
                                               : glm::dvec3(0, 0, 1);
  return glm::normalize(pick - axis * glm::dot(axis, pick));
}

}  // namespace

detail::UnitCircle::UnitCircle(int sides) {
  for (int i = 0; i < sides; ++i) {
    double angle = 2.0 * std::numbers::pi * i / sides;
    cos.push_back(std::cos(angle));
    sin.push_back(std::sin(angle));
  }
}

void Box::add(const glm::dvec3& point) {
  if (empty) {
    min = max = point;
    empty = false;
    return;
  }
  min = glm::min(min, point);
  max = glm::max(max, point);
}

// checkSides runs before the circles are built (it returns the value it checked).
Geometry::Geometry(const MeshDef& def)
    : def_(def),
      cylinderCircle_(checkSides("cylinderSides", def.cylinderSides, 3)),
      discCircle_(checkSides("discSides", def.discSides, 3)),
      sphereCircle_(checkSides("sphereSlices", def.sphereSlices, 3)) {
  checkSides("sphereStacks", def.sphereStacks, 2);
}

namespace {
// Coordinates past ±1e30 model units are not drawn: the 32-bit floats of glTF, PLY and the
// renderer hold up to 3.4e38, and the extent of a frame and the differences its writers
// take must stay finite too.
constexpr double kMaxCoordinate = 1e30;

bool drawable(double value) { return std::abs(value) <= kMaxCoordinate; }  // false for NaN
bool drawable(const glm::dvec3& p) { return drawable(p.x) && drawable(p.y) && drawable(p.z); }
}  // namespace

void Geometry::clear() {
  dropped_ = 0;
  segments_.clear();
  cylinders_.clear();
  discs_.clear();
  spheres_.clear();
  // Cleared, not replaced: the next frame reuses the memory.
  mesh_.positions.clear();
  mesh_.normals.clear();
  mesh_.texcoords.clear();
  mesh_.triangles.clear();
  bounds_ = Box{};
  material_ = 0;
}

void Geometry::checkIndexSpace(std::size_t positions, std::size_t normals) const {
  constexpr std::size_t kMax = std::numeric_limits<uint32_t>::max();
  if (mesh_.positions.size() + positions > kMax || mesh_.normals.size() + normals > kMax) {
    throw std::length_error("geometry: a frame's mesh cannot hold more than 2^32 - 1 vertices");
  }
}

uint32_t Geometry::addPosition(const glm::dvec3& position) {
  bounds_.add(position);
  mesh_.positions.push_back(position);
  return static_cast<uint32_t>(mesh_.positions.size() - 1);
}

uint32_t Geometry::addNormal(const glm::dvec3& normal) {
  mesh_.normals.push_back(normal);
  return static_cast<uint32_t>(mesh_.normals.size() - 1);
}

void Geometry::addTriangle(std::array<uint32_t, 3> positions, std::array<uint32_t, 3> normals) {
  if (mesh_.texcoords.empty()) mesh_.texcoords.emplace_back(0.0, 0.0);
  mesh_.triangles.push_back({positions, normals, {0, 0, 0}, material_});
}

void Geometry::addMesh(const Mesh& part, bool keepMaterials) {
  if (part.triangles.empty()) return;
  const bool finite =
      std::all_of(part.positions.begin(), part.positions.end(), [](const glm::dvec3& p) { return drawable(p); }) &&
      std::all_of(part.normals.begin(), part.normals.end(), [](const glm::dvec3& n) { return drawable(n); }) &&
      std::all_of(part.texcoords.begin(), part.texcoords.end(),
                  [](const glm::dvec2& t) { return drawable(t.x) && drawable(t.y); });
  if (!finite) {
    ++dropped_;
    return;
  }
  checkIndexSpace(part.positions.size(), part.normals.size());
  const auto positionBase = static_cast<uint32_t>(mesh_.positions.size());
  const auto normalBase = static_cast<uint32_t>(mesh_.normals.size());
  if (mesh_.texcoords.empty()) mesh_.texcoords.emplace_back(0.0, 0.0);
  const auto texcoordBase = static_cast<uint32_t>(mesh_.texcoords.size());
  for (const glm::dvec3& p : part.positions) addPosition(p);
  mesh_.normals.insert(mesh_.normals.end(), part.normals.begin(), part.normals.end());
  mesh_.texcoords.insert(mesh_.texcoords.end(), part.texcoords.begin(), part.texcoords.end());
  for (const Triangle& t : part.triangles) {
    Triangle shifted{};
    for (int k = 0; k < 3; ++k) {
      shifted.position[k] = t.position[k] + positionBase;
      shifted.normal[k] = t.normal[k] + normalBase;
      shifted.texcoord[k] = part.texcoords.empty() ? 0 : t.texcoord[k] + texcoordBase;
    }
    shifted.material = keepMaterials ? t.material : material_;
    mesh_.triangles.push_back(shifted);
  }
}

void Geometry::append(const Geometry& other) {
  dropped_ += other.dropped_;
  addMesh(other.mesh_, /*keepMaterials=*/true);
  segments_.insert(segments_.end(), other.segments_.begin(), other.segments_.end());
  cylinders_.insert(cylinders_.end(), other.cylinders_.begin(), other.cylinders_.end());
  discs_.insert(discs_.end(), other.discs_.begin(), other.discs_.end());
  spheres_.insert(spheres_.end(), other.spheres_.begin(), other.spheres_.end());
  if (!other.bounds_.empty) {
    bounds_.add(other.bounds_.min);
    bounds_.add(other.bounds_.max);
  }
}

void Geometry::append(Geometry&& other) {
  dropped_ += other.dropped_;
  addMesh(other.mesh_, /*keepMaterials=*/true);
  auto take = [](auto& into, auto& from) {
    if (into.empty())
      into.swap(from);
    else
      into.insert(into.end(), from.begin(), from.end());
  };
  take(segments_, other.segments_);
  take(cylinders_, other.cylinders_);
  take(discs_, other.discs_);
  take(spheres_, other.spheres_);
  if (!other.bounds_.empty) {
    bounds_.add(other.bounds_.min);
    bounds_.add(other.bounds_.max);
  }
}

void Geometry::addSegment(const glm::dvec3& start, const glm::dvec3& end) {
  if (start == end) return;
  if (!drawable(start) || !drawable(end)) {
    ++dropped_;
    return;
  }
  segments_.push_back({start, end, material_});
  bounds_.add(start);
  bounds_.add(end);
}

void Geometry::addCylinder(const glm::dvec3& start, const glm::dvec3& end, double radius,
                           bool capped, const glm::dvec3& side) {
  if (!drawable(start) || !drawable(end) || !drawable(radius) || !drawable(side)) {
    ++dropped_;
    return;
  }
  double length = glm::length(end - start);
  if (!(radius > 0) || !(length > 0)) return;
  const int n = def_.cylinderSides;
  checkIndexSpace(2 * n + 2, n + 2);
  cylinders_.push_back({start, end, radius, capped});
  const detail::UnitCircle& circle = cylinderCircle_;

  glm::dvec3 axis = (end - start) / length;
  glm::dvec3 a = perpendicular(axis, side);
  glm::dvec3 b = glm::cross(axis, a);  // a, b, axis is right-handed: rings run anticlockwise

  uint32_t firstStart = static_cast<uint32_t>(mesh_.positions.size());
  uint32_t firstNormal = static_cast<uint32_t>(mesh_.normals.size());
  for (int i = 0; i < n; ++i) {
    glm::dvec3 radial = a * circle.cos[i] + b * circle.sin[i];
    addPosition(start + radius * radial);
    addNormal(radial);
  }
  uint32_t firstEnd = static_cast<uint32_t>(mesh_.positions.size());
  for (int i = 0; i < n; ++i) addPosition(end + radius * (a * circle.cos[i] + b * circle.sin[i]));

  for (uint32_t i = 0; i < static_cast<uint32_t>(n); ++i) {
    uint32_t j = (i + 1) % n;
    addTriangle({firstStart + i, firstStart + j, firstEnd + j},
                {firstNormal + i, firstNormal + j, firstNormal + j});
    addTriangle({firstStart + i, firstEnd + j, firstEnd + i},
                {firstNormal + i, firstNormal + j, firstNormal + i});
  }
  if (!capped) return;
  uint32_t startCentre = addPosition(start);
  uint32_t endCentre = addPosition(end);
  uint32_t down = addNormal(-axis);
  uint32_t up = addNormal(axis);
  for (uint32_t i = 0; i < static_cast<uint32_t>(n); ++i) {
    uint32_t j = (i + 1) % n;
    addTriangle({startCentre, firstStart + j, firstStart + i}, {down, down, down});
    addTriangle({endCentre, firstEnd + i, firstEnd + j}, {up, up, up});
  }
}

void Geometry::addDisc(const glm::dvec3& centre, const glm::dvec3& axisA,
                       const glm::dvec3& axisB, double inner, double outer) {
  if (!drawable(centre) || !drawable(axisA) || !drawable(axisB) || !drawable(inner) || !drawable(outer)) {
    ++dropped_;
    return;
  }
  inner = std::max(inner, 0.0);
  if (!(outer > inner)) return;
  const int n = def_.discSides;
  checkIndexSpace(2 * n, 1);
  discs_.push_back({centre, axisA, axisB, inner, outer});
  const detail::UnitCircle& circle = discCircle_;

  uint32_t normal = addNormal(glm::normalize(glm::cross(axisA, axisB)));
  const std::array<uint32_t, 3> normals{normal, normal, normal};
  uint32_t firstOuter = static_cast<uint32_t>(mesh_.positions.size());
  for (int i = 0; i < n; ++i) {
    addPosition(centre + outer * (axisA * circle.cos[i] + axisB * circle.sin[i]));
  }
  if (inner == 0) {
    uint32_t middle = addPosition(centre);
    for (uint32_t i = 0; i < static_cast<uint32_t>(n); ++i) {
      addTriangle({middle, firstOuter + i, firstOuter + (i + 1) % n}, normals);
    }
    return;
  }
  uint32_t firstInner = static_cast<uint32_t>(mesh_.positions.size());
  for (int i = 0; i < n; ++i) {
    addPosition(centre + inner * (axisA * circle.cos[i] + axisB * circle.sin[i]));
  }
  for (uint32_t i = 0; i < static_cast<uint32_t>(n); ++i) {
    uint32_t j = (i + 1) % n;
    addTriangle({firstInner + i, firstOuter + i, firstOuter + j}, normals);
    addTriangle({firstInner + i, firstOuter + j, firstInner + j}, normals);
  }
}

void Geometry::addSphere(const glm::dvec3& centre, double radius) {
  if (!drawable(centre) || !drawable(radius)) {
    ++dropped_;
    return;
  }
  if (!(radius > 0)) return;
  const int slices = def_.sphereSlices;
  const int stacks = def_.sphereStacks;
  const std::size_t count = 2 + static_cast<std::size_t>(stacks - 1) * slices;
  checkIndexSpace(count, count);
  spheres_.push_back({centre, radius});
  const detail::UnitCircle& circle = sphereCircle_;

  // Every vertex gets its own normal, added in step with the positions.
  const uint32_t firstPosition = static_cast<uint32_t>(mesh_.positions.size());
  const uint32_t firstNormal = static_cast<uint32_t>(mesh_.normals.size());
  auto add = [&](const glm::dvec3& unit) {
    addNormal(unit);
    return addPosition(centre + radius * unit);
  };
  uint32_t north = add({0, 0, 1});
  uint32_t firstRing = north + 1;
  for (int k = 1; k < stacks; ++k) {
    double polar = std::numbers::pi * k / stacks;
    double rho = std::sin(polar);
    double z = std::cos(polar);
    for (int i = 0; i < slices; ++i) add({rho * circle.cos[i], rho * circle.sin[i], z});
  }
  uint32_t south = add({0, 0, -1});
  auto normalOf = [&](uint32_t position) { return position - firstPosition + firstNormal; };
  auto triangle = [&](uint32_t p0, uint32_t p1, uint32_t p2) {
    addTriangle({p0, p1, p2}, {normalOf(p0), normalOf(p1), normalOf(p2)});
  };
  const auto s = static_cast<uint32_t>(slices);
  for (uint32_t i = 0; i < s; ++i) triangle(north, firstRing + i, firstRing + (i + 1) % s);
  for (uint32_t k = 0; k + 1 < static_cast<uint32_t>(stacks - 1); ++k) {
    uint32_t upper = firstRing + k * s;
    uint32_t lower = upper + s;
    for (uint32_t i = 0; i < s; ++i) {
      uint32_t j = (i + 1) % s;
      triangle(upper + i, lower + i, lower + j);
      triangle(upper + i, lower + j, upper + j);
    }
  }
  uint32_t lastRing = firstRing + static_cast<uint32_t>(stacks - 2) * s;
  for (uint32_t i = 0; i < s; ++i) triangle(south, lastRing + (i + 1) % s, lastRing + i);
}

}  // namespace ontogen
