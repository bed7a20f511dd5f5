#include "interpreters/geometry/surface.h"

#include <glm/geometric.hpp>

namespace ontogen {

namespace {

// Above 256 x 256 cells a patch has more triangles than any drawing needs.
constexpr int kMaxPatchResolution = 256;

// Bernstein polynomials of degree 3 at t.
std::array<double, 4> bernstein(double t) {
  const double s = 1 - t;
  return {s * s * s, 3 * t * s * s, 3 * t * t * s, t * t * t};
}

}  // namespace

Surface bezierPatch(const PatchControls& controls, int resolution) {
  if (resolution < 1 || resolution > kMaxPatchResolution) {
    throw SurfaceError("a patch's resolution must be 1 to " + std::to_string(kMaxPatchResolution) + ", got " +
                       std::to_string(resolution));
  }
  Surface surface;
  const int n = resolution;
  for (int j = 0; j <= n; ++j) {
    const double v = static_cast<double>(j) / n;
    const auto bv = bernstein(v);
    for (int i = 0; i <= n; ++i) {
      const double u = static_cast<double>(i) / n;
      const auto bu = bernstein(u);
      glm::dvec3 p(0.0);
      for (int row = 0; row < 4; ++row) {
        for (int column = 0; column < 4; ++column) p += bv[row] * bu[column] * controls[4 * row + column];
      }
      surface.positions.push_back(p);
      surface.texcoords.emplace_back(u, v);
    }
  }
  const auto at = [n](int i, int j) { return static_cast<uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      surface.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      surface.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return surface;
}

Surface blendSurfaces(std::span<const Surface* const> surfaces, std::span<const double> weights) {
  if (surfaces.empty() || surfaces.size() != weights.size()) {
    throw SurfaceError("a blend needs one weight per surface and at least one surface");
  }
  double total = 0;
  for (double w : weights) total += w;
  if (total == 0) throw SurfaceError("the weights of a blend sum to 0");
  const Surface& first = *surfaces[0];
  for (std::size_t k = 1; k < surfaces.size(); ++k) {
    const Surface& other = *surfaces[k];
    if (other.positions.size() != first.positions.size() || other.triangles != first.triangles) {
      throw SurfaceError("surfaces 1 and " + std::to_string(k + 1) + " of the blend have different topologies (" +
                         std::to_string(first.positions.size()) + " and " + std::to_string(other.positions.size()) +
                         " vertices, " + std::to_string(first.triangles.size()) + " and " +
                         std::to_string(other.triangles.size()) + " triangles); a blend needs the same vertices "
                         "and triangles in every surface");
    }
  }
  Surface blend;
  blend.triangles = first.triangles;
  blend.positions.assign(first.positions.size(), glm::dvec3(0.0));
  bool textured = true;
  for (const Surface* s : surfaces) textured = textured && s->texcoords.size() == first.positions.size();
  if (textured) blend.texcoords.assign(first.positions.size(), glm::dvec2(0.0));
  for (std::size_t k = 0; k < surfaces.size(); ++k) {
    const double w = weights[k] / total;
    for (std::size_t i = 0; i < blend.positions.size(); ++i) {
      blend.positions[i] += w * surfaces[k]->positions[i];
      if (textured) blend.texcoords[i] += w * surfaces[k]->texcoords[i];
    }
  }
  return blend;
}

Mesh placeSurface(const Surface& surface, const SurfacePlacement& placement) {
  Mesh mesh;
  mesh.positions.reserve(surface.positions.size());
  for (const glm::dvec3& p : surface.positions) {
    mesh.positions.push_back(placement.origin +
                             placement.scale * (p.x * placement.right + p.y * placement.heading + p.z * placement.up));
  }
  mesh.normals.assign(mesh.positions.size(), glm::dvec3(0.0));
  for (const auto& t : surface.triangles) {
    // The cross product's length is twice the area: larger triangles weigh more.
    const glm::dvec3 n = glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]], mesh.positions[t[2]] - mesh.positions[t[0]]);
    for (uint32_t corner : t) mesh.normals[corner] += n;
  }
  for (glm::dvec3& n : mesh.normals) {
    const double size = glm::length(n);
    n = size > 0 ? n / size : placement.up;
  }
  // Geometry::addMesh keeps index 0 of its texcoords for (0, 0), so ours follow it.
  const bool textured = surface.texcoords.size() == surface.positions.size();
  if (textured) mesh.texcoords = surface.texcoords;
  for (const auto& t : surface.triangles) {
    Triangle triangle{};
    triangle.position = t;
    triangle.normal = t;
    if (textured) triangle.texcoord = t;
    mesh.triangles.push_back(triangle);
  }
  return mesh;
}

}  // namespace ontogen
