#include "interpreters/formats/still_glb.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "interpreters/formats/glb_writer.h"
#include "interpreters/palette.h"

namespace ontogen {

namespace {

// One colour's vertices, each with the cell that drew it.
struct StillBatch {
  MeshBatch mesh;
  std::vector<glm::vec2> cells;
};

// The unit tube: kTubeSides columns of two vertices (y = -1, 1), radial normals,
// anticlockwise from outside.
struct Tube {
  std::vector<glm::dvec3> positions, normals;
  std::vector<glm::vec2> texcoords;
  std::vector<uint32_t> indices;
};

Tube unitTube() {
  Tube tube;
  const auto sides = static_cast<uint32_t>(kTubeSides);
  for (uint32_t k = 0; k < sides; ++k) {
    const double a = 2 * std::numbers::pi * k / sides;
    const glm::dvec3 radial(std::cos(a), 0, std::sin(a));
    for (double y : {-1.0, 1.0}) {
      tube.positions.emplace_back(radial.x, y, radial.z);
      tube.normals.push_back(radial);
      tube.texcoords.emplace_back(static_cast<float>(k) / static_cast<float>(sides), y < 0 ? 0.0f : 1.0f);
    }
  }
  for (uint32_t k = 0; k < sides; ++k) {
    const uint32_t bottom = 2 * k, top = 2 * k + 1, nextBottom = 2 * ((k + 1) % sides), nextTop = nextBottom + 1;
    tube.indices.insert(tube.indices.end(), {bottom, top, nextBottom, nextBottom, top, nextTop});
  }
  return tube;
}

// The cell number of every triangle and segment, and each cell's birth: cells numbered
// in the order their nodes come, what no node covers last (as formats/scene_parts.h).
struct Cells {
  std::vector<uint32_t> ofTriangle, ofSegment;
  std::vector<float> birth;
};

Cells cellsOf(const Scene& scene) {
  const Geometry& g = scene.geometry;
  constexpr uint32_t kUncovered = ~uint32_t{0};
  Cells cells;
  cells.ofTriangle.assign(g.triangleCount(), kUncovered);
  cells.ofSegment.assign(g.segmentCount(), kUncovered);
  // The nodes that drew, and for each the first node of its cell: by sorting (id, node)
  // pairs, which for a million nodes is several times faster than a hash table.
  auto ends = [&](const SceneNode& node) {
    const GeometryRange& r = node.range;
    return std::pair<uint64_t, uint64_t>{
        std::min<uint64_t>(uint64_t{r.firstTriangle} + r.triangleCount, g.triangleCount()),
        std::min<uint64_t>(uint64_t{r.firstSegment} + r.segmentCount, g.segmentCount())};
  };
  std::vector<std::pair<uint64_t, uint32_t>> byId;
  byId.reserve(scene.nodes.size());
  for (uint32_t n = 0; n < scene.nodes.size(); ++n) {
    const SceneNode& node = scene.nodes[n];
    const auto [triangleEnd, segmentEnd] = ends(node);
    if (triangleEnd > node.range.firstTriangle || segmentEnd > node.range.firstSegment) byId.emplace_back(node.id, n);
  }
  std::sort(byId.begin(), byId.end());
  std::vector<uint32_t> firstOf(scene.nodes.size(), 0);
  for (std::size_t k = 0; k < byId.size(); ++k)
    firstOf[byId[k].second] = k > 0 && byId[k].first == byId[k - 1].first ? firstOf[byId[k - 1].second] : byId[k].second;
  std::vector<uint32_t> number(scene.nodes.size(), 0);
  for (uint32_t n = 0; n < scene.nodes.size(); ++n) {
    const SceneNode& node = scene.nodes[n];
    const auto [triangleEnd, segmentEnd] = ends(node);
    if (triangleEnd <= node.range.firstTriangle && segmentEnd <= node.range.firstSegment) continue;
    if (firstOf[n] == n) {
      number[n] = static_cast<uint32_t>(cells.birth.size());
      cells.birth.push_back(static_cast<float>(node.birth));
    } else {
      number[n] = number[firstOf[n]];
    }
    for (uint64_t t = node.range.firstTriangle; t < triangleEnd; ++t) cells.ofTriangle[t] = number[n];
    for (uint64_t s = node.range.firstSegment; s < segmentEnd; ++s) cells.ofSegment[s] = number[n];
  }
  const auto rest = static_cast<uint32_t>(cells.birth.size());
  bool uncovered = false;
  for (std::vector<uint32_t>* of : {&cells.ofTriangle, &cells.ofSegment}) {
    for (uint32_t& c : *of) {
      if (c != kUncovered) continue;
      c = rest;
      uncovered = true;
    }
  }
  if (uncovered) cells.birth.push_back(0.0f);
  return cells;
}

glm::vec2 cellValue(const Cells& cells, uint32_t cell) { return {static_cast<float>(cell), cells.birth[cell]}; }

}  // namespace

TubePlacement tubeOn(const glm::dvec3& a, const glm::dvec3& b, double radius) {
  TubePlacement p;
  const glm::dvec3 axis = b - a;
  const double length = glm::length(axis);
  const glm::dvec3 d = axis / length;
  p.translation = (a + b) * 0.5;
  // The shortest turn from +y to d: (1 + y.d, y x d) normalized; half a turn about x
  // when d is -y.
  if (1 + d.y > 1e-12)
    p.rotation = glm::normalize(glm::dquat(1 + d.y, d.z, 0, -d.x));
  else
    p.rotation = glm::dquat(0, 1, 0, 0);
  p.scale = {radius, length / 2, radius};
  return p;
}

void addStillScene(gltf::Builder& b, const Scene& scene, double lineRadius, nlohmann::json& sceneNodes) {
  const Geometry& g = scene.geometry;
  if (g.empty()) return;
  const Mesh& mesh = g.mesh();
  const Cells cells = cellsOf(scene);
  std::map<uint32_t, StillBatch> still;  // by palette colour

  // Surfaces as the frame holds them.
  std::map<uint32_t, std::unordered_map<CornerKey, uint32_t, CornerHash>> corners;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Triangle& triangle = mesh.triangles[t];
    const uint32_t material = triangle.material % kPaletteSize;
    StillBatch& batch = still[material];
    auto& seen = corners[material];
    for (int k = 0; k < 3; ++k) {
      const CornerKey key{triangle.position[k], triangle.normal[k], triangle.texcoord[k], cells.ofTriangle[t]};
      const auto [it, added] = seen.try_emplace(key, static_cast<uint32_t>(batch.mesh.positions.size()));
      if (added) {
        batch.mesh.positions.emplace_back(mesh.positions[key.position]);
        batch.mesh.normals.emplace_back(mesh.normals[key.normal]);
        batch.mesh.texcoords.emplace_back(key.texcoord < mesh.texcoords.size() ? glm::vec2(mesh.texcoords[key.texcoord])
                                                                               : glm::vec2(0.0f));
        batch.cells.push_back(cellValue(cells, key.cell));
      }
      batch.mesh.indices.push_back(it->second);
    }
  }
  corners.clear();

  // Lines as tubes: baked into the still mesh, or instances of one tube.
  const Tube tube = unitTube();
  const auto& segments = g.segments();
  const bool instanced = segments.size() > kMaxBakedLines;
  std::map<uint32_t, TubeInstances> instances;  // by palette colour
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const Segment& segment = segments[s];
    if (segment.start == segment.end) continue;  // draws nothing
    const uint32_t material = segment.material % kPaletteSize;
    if (instanced) {
      instances[material].add(segment.start, segment.end, lineRadius, cellValue(cells, cells.ofSegment[s]));
      continue;
    }
    const TubePlacement p = tubeOn(segment.start, segment.end, lineRadius);
    StillBatch& batch = still[material];
    const auto base = static_cast<uint32_t>(batch.mesh.positions.size());
    const glm::dmat3 rotation = glm::mat3_cast(p.rotation);
    for (std::size_t v = 0; v < tube.positions.size(); ++v) {
      batch.mesh.positions.emplace_back(p.translation + rotation * (tube.positions[v] * p.scale));
      batch.mesh.normals.emplace_back(rotation * tube.normals[v]);
      batch.mesh.texcoords.push_back(tube.texcoords[v]);
      batch.cells.push_back(cellValue(cells, cells.ofSegment[s]));
    }
    for (uint32_t index : tube.indices) batch.mesh.indices.push_back(base + index);
  }

  if (!still.empty()) {
    nlohmann::json primitives = nlohmann::json::array();
    for (const auto& [material, batch] : still)
      primitives.push_back(gltf::trianglePrimitive(b, batch.mesh, material, &batch.cells));
    b.gltf["meshes"].push_back({{"name", "still"}, {"primitives", primitives}});
    b.gltf["nodes"].push_back({{"name", "still"}, {"mesh", b.gltf["meshes"].size() - 1}});
    sceneNodes.push_back(b.gltf["nodes"].size() - 1);
  }

  TubeInstancer instancer(b);
  for (const auto& [material, into] : instances)
    sceneNodes.push_back(instancer.addNode(material, into, "lines " + std::to_string(material)));
}

void TubeInstances::add(const glm::dvec3& a, const glm::dvec3& b, double radius, const glm::vec2& cell) {
  const TubePlacement p = tubeOn(a, b, radius);
  translations.emplace_back(p.translation);
  scales.emplace_back(p.scale);
  rotations.insert(rotations.end(), {static_cast<float>(p.rotation.x), static_cast<float>(p.rotation.y),
                                     static_cast<float>(p.rotation.z), static_cast<float>(p.rotation.w)});
  cells.insert(cells.end(), {cell.x, cell.y});
}

// The tube once, drawn in each colour by a mesh of its own (the primitive's accessors
// shared, its material the colour's).
std::size_t TubeInstancer::addNode(uint32_t material, const TubeInstances& instances, const std::string& name) {
  gltf::Builder& b = builder_;
  if (primitive_.is_null()) {
    const Tube tube = unitTube();
    MeshBatch unit;
    unit.positions.assign(tube.positions.begin(), tube.positions.end());
    unit.normals.assign(tube.normals.begin(), tube.normals.end());
    unit.texcoords = tube.texcoords;
    unit.indices = tube.indices;
    primitive_ = gltf::trianglePrimitive(b, unit, material);
    b.useExtension("EXT_mesh_gpu_instancing");
  }
  nlohmann::json primitive = primitive_;
  primitive["material"] = b.materialOf(material);
  b.gltf["meshes"].push_back({{"name", name}, {"primitives", nlohmann::json::array({primitive})}});
  const nlohmann::json instancing = {{"attributes",
                                      {{"TRANSLATION", b.addVec3(instances.translations, 0, false)},
                                       {"ROTATION", b.addFloats(instances.rotations, "VEC4", instances.size(), 0)},
                                       {"SCALE", b.addVec3(instances.scales, 0, false)},
                                       {"_CELL", b.addFloats(instances.cells, "VEC2", instances.size(), 0)}}}};
  b.gltf["nodes"].push_back({{"name", name},
                             {"mesh", b.gltf["meshes"].size() - 1},
                             {"extensions", {{"EXT_mesh_gpu_instancing", instancing}}}});
  return b.gltf["nodes"].size() - 1;
}

}  // namespace ontogen
