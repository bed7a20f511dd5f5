#include "interpreters/geometry/gap_filter.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "interpreters/palette.h"

namespace ontogen {

namespace {

glm::dvec3 faceNormal(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  glm::dvec3 n = glm::cross(b - a, c - a);
  double size = glm::length(n);
  return size > 0 ? n / size : glm::dvec3(0.0, 0.0, 1.0);
}

// Union-find over corner indices, with path halving.
struct Groups {
  explicit Groups(std::size_t count) : parent(count) { std::iota(parent.begin(), parent.end(), std::size_t{0}); }
  std::size_t find(std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
  std::vector<std::size_t> parent;
};

struct CellKey {
  int64_t x, y, z;
  bool operator==(const CellKey&) const = default;
};

struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    // Unsigned: the products may wrap, which signed arithmetic may not.
    return static_cast<std::size_t>(static_cast<uint64_t>(k.x) * 73856093u ^ static_cast<uint64_t>(k.y) * 19349663u ^
                                    static_cast<uint64_t>(k.z) * 83492791u);
  }
};

}  // namespace

Mesh platesAsMesh(std::span<const Plate> plates) {
  Mesh mesh;
  for (const Plate& plate : plates) {
    if (plate.corners.size() < 3) continue;
    const auto base = static_cast<uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), plate.corners.begin(), plate.corners.end());
    for (std::size_t k = 1; k + 1 < plate.corners.size(); ++k) {
      Triangle t{};
      t.position = {base, base + static_cast<uint32_t>(k), base + static_cast<uint32_t>(k + 1)};
      const auto normal = static_cast<uint32_t>(mesh.normals.size());
      mesh.normals.push_back(faceNormal(plate.corners[0], plate.corners[k], plate.corners[k + 1]));
      t.normal = {normal, normal, normal};
      t.material = plate.material;
      mesh.triangles.push_back(t);
    }
  }
  return mesh;
}

JoinedPlates joinPlates(std::span<const Plate> plates, double tolerance) {
  std::vector<glm::dvec3> corners;
  for (const Plate& plate : plates) {
    if (plate.corners.size() >= 3) corners.insert(corners.end(), plate.corners.begin(), plate.corners.end());
  }
  Groups groups(corners.size());
  if (tolerance > 0) {
    // Buckets one tolerance wide: partners lie in the same or a neighbouring bucket.
    std::unordered_map<CellKey, std::vector<std::size_t>, CellHash> buckets;
    auto keyOf = [&](const glm::dvec3& p) {
      return CellKey{static_cast<int64_t>(std::floor(p.x / tolerance)), static_cast<int64_t>(std::floor(p.y / tolerance)),
                     static_cast<int64_t>(std::floor(p.z / tolerance))};
    };
    for (std::size_t i = 0; i < corners.size(); ++i) buckets[keyOf(corners[i])].push_back(i);
    for (std::size_t i = 0; i < corners.size(); ++i) {
      const CellKey key = keyOf(corners[i]);
      for (int64_t dx = -1; dx <= 1; ++dx) {
        for (int64_t dy = -1; dy <= 1; ++dy) {
          for (int64_t dz = -1; dz <= 1; ++dz) {
            auto found = buckets.find({key.x + dx, key.y + dy, key.z + dz});
            if (found == buckets.end()) continue;
            for (std::size_t j : found->second) {
              if (j > i && glm::length(corners[i] - corners[j]) <= tolerance) groups.join(i, j);
            }
          }
        }
      }
    }
  }
  // One position per group, at the mean of its corners.
  JoinedPlates result;
  std::vector<uint32_t> positionOf(corners.size());
  std::unordered_map<std::size_t, uint32_t> groupPosition;
  std::vector<double> members;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    auto [it, inserted] = groupPosition.try_emplace(groups.find(i), static_cast<uint32_t>(result.mesh.positions.size()));
    if (inserted) {
      result.mesh.positions.push_back(glm::dvec3(0.0));
      members.push_back(0);
    }
    positionOf[i] = it->second;
    result.mesh.positions[it->second] += corners[i];
    members[it->second] += 1;
  }
  for (std::size_t p = 0; p < result.mesh.positions.size(); ++p) result.mesh.positions[p] /= members[p];

  // Stretch per plate, then triangles coloured by it.
  std::vector<double> plateStretch;
  std::size_t first = 0;
  for (const Plate& plate : plates) {
    if (plate.corners.size() < 3) continue;
    double stretch = 0;
    const std::size_t n = plate.corners.size();
    for (std::size_t k = 0; k < n; ++k) {
      const double before = glm::length(plate.corners[(k + 1) % n] - plate.corners[k]);
      if (!(before > 0)) continue;
      const double after = glm::length(result.mesh.positions[positionOf[first + (k + 1) % n]] -
                                       result.mesh.positions[positionOf[first + k]]);
      stretch = std::max(stretch, std::abs(after / before - 1));
    }
    plateStretch.push_back(stretch);
    result.maxStretch = std::max(result.maxStretch, stretch);
    first += n;
  }
  first = 0;
  std::size_t index = 0;
  for (const Plate& plate : plates) {
    if (plate.corners.size() < 3) continue;
    const double stretch = plateStretch[index++];
    const uint32_t material = stressMaterial(result.maxStretch > 0 ? stretch / result.maxStretch : 0);
    for (std::size_t k = 1; k + 1 < plate.corners.size(); ++k) {
      std::array<uint32_t, 3> p = {positionOf[first], positionOf[first + k], positionOf[first + k + 1]};
      if (p[0] == p[1] || p[1] == p[2] || p[0] == p[2]) continue;
      Triangle t{};
      t.position = p;
      const auto normal = static_cast<uint32_t>(result.mesh.normals.size());
      result.mesh.normals.push_back(
          faceNormal(result.mesh.positions[p[0]], result.mesh.positions[p[1]], result.mesh.positions[p[2]]));
      t.normal = {normal, normal, normal};
      t.material = material;
      result.mesh.triangles.push_back(t);
      result.stretch.push_back(stretch);
    }
    first += plate.corners.size();
  }
  return result;
}

}  // namespace ontogen
