#include "interpreters/physics/force_arrows.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace ontogen {

namespace {

constexpr int kConeSides = 12;  // as round as the shaft's cylinder (MeshDef::cylinderSides)

// A cone with its base centred at `base`, its apex at base + axis, closed by a disc.
Mesh cone(const glm::dvec3& base, const glm::dvec3& axis, double radius) {
  Mesh mesh;
  const double height = glm::length(axis);
  const glm::dvec3 h = axis / height;
  const glm::dvec3 other = std::abs(h.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(h, other));
  const glm::dvec3 v = glm::cross(h, u);
  mesh.positions.push_back(base + axis);  // 0: apex
  mesh.positions.push_back(base);         // 1: base centre
  const double slope = radius / height;
  for (int i = 0; i < kConeSides; ++i) {
    const double a = 2 * std::numbers::pi * i / kConeSides;
    const glm::dvec3 out = std::cos(a) * u + std::sin(a) * v;
    mesh.positions.push_back(base + radius * out);
    mesh.normals.push_back(glm::normalize(out + slope * h));
  }
  mesh.normals.push_back(-h);
  const auto down = static_cast<uint32_t>(kConeSides);
  for (uint32_t i = 0; i < static_cast<uint32_t>(kConeSides); ++i) {
    const uint32_t j = (i + 1) % kConeSides;
    Triangle side{};
    side.position = {2 + i, 2 + j, 0};
    side.normal = {i, j, i};
    mesh.triangles.push_back(side);
    Triangle cap{};
    cap.position = {1, 2 + j, 2 + i};
    cap.normal = {down, down, down};
    mesh.triangles.push_back(cap);
  }
  return mesh;
}

}  // namespace

void addArrow(Geometry& geometry, const glm::dvec3& start, const glm::dvec3& vector, const ArrowStyle& style) {
  const double length = glm::length(vector);
  if (!(length > 0) || !std::isfinite(length)) return;
  const glm::dvec3 h = vector / length;
  const double head = std::min(style.headLength, 0.4 * length);
  const double headRadius = 2.5 * style.shaftRadius;
  const int heads = std::clamp(style.heads, 1, 2);
  const double shaft = length - heads * head;
  const uint32_t before = geometry.material();
  geometry.setMaterial(style.material);
  geometry.addCylinder(start, start + shaft * h, style.shaftRadius, /*capped=*/true);
  for (int k = 0; k < heads; ++k) geometry.addMesh(cone(start + (shaft + k * head) * h, head * h, headRadius));
  geometry.setMaterial(before);
}

}  // namespace ontogen
