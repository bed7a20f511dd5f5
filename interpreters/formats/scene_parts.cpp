#include "interpreters/formats/scene_parts.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

namespace ontogen {

namespace {

// Rounding steps of a shape's key (scene_parts.h): coordinates in [-1, 1] to 2^-18,
// unit normals to 2^-14, texture coordinates to 2^-16.
constexpr double kPositionSteps = 1 << 18;
constexpr double kNormalSteps = 1 << 14;
constexpr double kTexcoordSteps = 1 << 16;

int32_t rounded(double value, double steps) { return static_cast<int32_t>(std::lround(value * steps)); }

// The rounded coordinates and colours of a shape's batches, and their hash.
std::vector<int32_t> keyOf(const std::vector<MeshBatch>& batches) {
  std::vector<int32_t> key;
  for (const MeshBatch& batch : batches) {
    key.push_back(static_cast<int32_t>(batch.material));
    key.push_back(static_cast<int32_t>(batch.positions.size()));
    key.push_back(static_cast<int32_t>(batch.indices.size()));
    key.push_back(static_cast<int32_t>(batch.lines.size()));
    for (std::size_t v = 0; v < batch.positions.size(); ++v) {
      for (int k = 0; k < 3; ++k) key.push_back(rounded(batch.positions[v][k], kPositionSteps));
      for (int k = 0; k < 3; ++k) key.push_back(rounded(batch.normals[v][k], kNormalSteps));
      for (int k = 0; k < 2; ++k) key.push_back(rounded(batch.texcoords[v][k], kTexcoordSteps));
    }
    for (uint32_t index : batch.indices) key.push_back(static_cast<int32_t>(index));
    for (const glm::vec3& point : batch.lines)
      for (int k = 0; k < 3; ++k) key.push_back(rounded(point[k], kPositionSteps));
  }
  return key;
}

uint64_t hashOf(const std::vector<int32_t>& key) {
  uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a over the 32-bit words
  for (int32_t word : key) {
    h ^= static_cast<uint32_t>(word);
    h *= 0x100000001b3ull;
  }
  return h;
}

uint64_t batchBytes(const std::vector<MeshBatch>& batches) {
  uint64_t bytes = 0;
  for (const MeshBatch& b : batches)
    bytes += b.positions.size() * (2 * sizeof(glm::vec3) + sizeof(glm::vec2)) + b.indices.size() * sizeof(uint32_t) +
             b.lines.size() * sizeof(glm::vec3);
  return bytes;
}

}  // namespace

void SceneParts::clear() {
  shapes_.clear();
  keys_.clear();
  byHash_.clear();
  joints_.clear();
  jointsOfCell_.clear();
  cellNumbers_.clear();
  frames_.clear();
  bounds_ = Box{};
  heldBytes_ = 0;
}

std::vector<std::vector<uint32_t>> SceneParts::jointsByShape() const {
  std::vector<std::vector<uint32_t>> out(shapes_.size());
  for (uint32_t j = 0; j < joints_.size(); ++j) out[joints_[j].shape].push_back(j);
  return out;
}

uint32_t SceneParts::shapeOf(std::vector<MeshBatch>&& batches) {
  std::vector<int32_t> key = keyOf(batches);
  const uint64_t hash = hashOf(key);
  auto [first, last] = byHash_.equal_range(hash);
  for (auto it = first; it != last; ++it)
    if (keys_[it->second] == key) return it->second;
  const auto index = static_cast<uint32_t>(shapes_.size());
  heldBytes_ += batchBytes(batches) + key.size() * sizeof(int32_t);
  shapes_.push_back({std::move(batches), 0, 0});
  keys_.push_back(std::move(key));
  byHash_.emplace(hash, index);
  return index;
}

void SceneParts::addFrame(const Scene& scene) {
  const Geometry& geometry = scene.geometry;
  if (!geometry.bounds().empty) {
    bounds_.add(geometry.bounds().min);
    bounds_.add(geometry.bounds().max);
  }
  PartFrame frame;
  frame.time = scene.time;
  std::vector<char> coveredTriangles(geometry.triangleCount(), 0);
  std::vector<char> coveredSegments(geometry.segmentCount(), 0);
  std::vector<uint32_t> triangles, segments;
  for (const SceneNode& node : scene.nodes) {
    triangles.clear();
    segments.clear();
    const GeometryRange& r = node.range;
    for (uint64_t t = r.firstTriangle; t < uint64_t{r.firstTriangle} + r.triangleCount && t < coveredTriangles.size(); ++t) {
      coveredTriangles[t] = 1;
      triangles.push_back(static_cast<uint32_t>(t));
    }
    for (uint64_t s = r.firstSegment; s < uint64_t{r.firstSegment} + r.segmentCount && s < coveredSegments.size(); ++s) {
      coveredSegments[s] = 1;
      segments.push_back(static_cast<uint32_t>(s));
    }
    addPart(scene, node, triangles, segments, frame);
  }
  triangles.clear();
  segments.clear();
  for (uint32_t t = 0; t < coveredTriangles.size(); ++t)
    if (!coveredTriangles[t]) triangles.push_back(t);
  for (uint32_t s = 0; s < coveredSegments.size(); ++s)
    if (!coveredSegments[s]) segments.push_back(s);
  if (!triangles.empty() || !segments.empty()) {
    SceneNode rest;
    rest.id = kRestPart;
    addPart(scene, rest, triangles, segments, frame);
  }
  heldBytes_ += sizeof(PartFrame) + frame.placements.size() * sizeof(PartPlacement);
  frames_.push_back(std::move(frame));
}

void SceneParts::addPart(const Scene& scene, const SceneNode& node, const std::vector<uint32_t>& triangles,
                         const std::vector<uint32_t>& segments, PartFrame& frame) {
  if (triangles.empty() && segments.empty()) return;
  const Mesh& mesh = scene.geometry.mesh();
  const auto& lines = scene.geometry.segments();
  // The node's frame made exactly orthonormal, so that going into it and back is exact.
  const glm::dquat rotation = glm::normalize(glm::quat_cast(node.orientation));
  const glm::dmat3 frameAxes = glm::mat3_cast(rotation);
  const glm::dmat3 inverse = glm::transpose(frameAxes);
  auto local = [&](const glm::dvec3& p) { return inverse * (p - node.position); };

  Box box;
  for (uint32_t t : triangles)
    for (int k = 0; k < 3; ++k) box.add(local(mesh.positions[mesh.triangles[t].position[k]]));
  for (uint32_t s : segments) {
    box.add(local(lines[s].start));
    box.add(local(lines[s].end));
  }
  const glm::dvec3 centre = (box.min + box.max) * 0.5;
  const glm::dvec3 half = (box.max - box.min) * 0.5;
  double scale = std::max({half.x, half.y, half.z});
  if (!(scale > 0) || !std::isfinite(scale)) scale = 1;  // a point: nothing to scale

  // The part in its shape's coordinates, each corner's position, normal and texture
  // coordinate taken once.
  Mesh part;
  std::unordered_map<uint32_t, uint32_t> positions, normals, texcoords;
  part.texcoords.emplace_back(0.0, 0.0);
  for (uint32_t t : triangles) {
    const Triangle& source = mesh.triangles[t];
    Triangle copy = source;
    for (int k = 0; k < 3; ++k) {
      auto [p, newPosition] = positions.try_emplace(source.position[k], static_cast<uint32_t>(part.positions.size()));
      if (newPosition) part.positions.push_back((local(mesh.positions[source.position[k]]) - centre) / scale);
      auto [n, newNormal] = normals.try_emplace(source.normal[k], static_cast<uint32_t>(part.normals.size()));
      if (newNormal) part.normals.push_back(inverse * mesh.normals[source.normal[k]]);
      uint32_t texcoord = 0;
      if (source.texcoord[k] < mesh.texcoords.size()) {
        auto [c, newTexcoord] = texcoords.try_emplace(source.texcoord[k], static_cast<uint32_t>(part.texcoords.size()));
        if (newTexcoord) part.texcoords.push_back(mesh.texcoords[source.texcoord[k]]);
        texcoord = c->second;
      }
      copy.position[k] = p->second;
      copy.normal[k] = n->second;
      copy.texcoord[k] = texcoord;
    }
    part.triangles.push_back(copy);
  }
  scratch_.clear();
  scratch_.addMesh(part, /*keepMaterials=*/true);
  for (uint32_t s : segments) {
    scratch_.setMaterial(lines[s].material);
    scratch_.addSegment((local(lines[s].start) - centre) / scale, (local(lines[s].end) - centre) / scale);
  }
  if (scratch_.empty()) return;
  const uint32_t shape = shapeOf(batchByMaterial(scratch_));
  shapes_[shape].scaleSum += scale;
  ++shapes_[shape].placementCount;

  // The joint: this cell drawing this shape.
  std::vector<uint32_t>& ofCell = jointsOfCell_[node.id];
  uint32_t joint = 0;
  auto found = std::find_if(ofCell.begin(), ofCell.end(), [&](uint32_t j) { return joints_[j].shape == shape; });
  if (found != ofCell.end()) {
    joint = *found;
  } else {
    joint = static_cast<uint32_t>(joints_.size());
    const auto [number, added] = cellNumbers_.try_emplace(node.id, static_cast<uint32_t>(cellNumbers_.size()));
    joints_.push_back({node.id, node.parent, node.label, node.birth, shape, number->second,
                       static_cast<uint32_t>(ofCell.size())});
    ofCell.push_back(joint);
    heldBytes_ += sizeof(PartJoint) + node.label.size();
  }
  frame.placements.push_back({joint, node.position + frameAxes * centre, rotation, scale});
}

std::vector<MeshBatch> shapeWithTubes(const PartShape& shape, double radius, int sides) {
  std::vector<MeshBatch> out;
  MeshDef def;
  def.cylinderSides = sides;
  Geometry tubes(def);
  for (const MeshBatch& batch : shape.batches) {
    out.push_back(batch);
    out.back().lines.clear();
    if (batch.lines.empty()) continue;
    tubes.clear();
    for (std::size_t k = 0; k + 1 < batch.lines.size(); k += 2) {
      // Any direction across the axis fixes where the tube's first side lies.
      const glm::dvec3 a(batch.lines[k]), b(batch.lines[k + 1]);
      const glm::dvec3 axis = b - a;
      const glm::dvec3 across = std::abs(axis.z) < 0.9 * glm::length(axis) ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0);
      tubes.addCylinder(a, b, radius, /*capped=*/false, glm::cross(axis, across));
    }
    for (MeshBatch& tube : batchByMaterial(tubes)) {
      MeshBatch& into = out.back();
      const auto base = static_cast<uint32_t>(into.positions.size());
      into.positions.insert(into.positions.end(), tube.positions.begin(), tube.positions.end());
      into.normals.insert(into.normals.end(), tube.normals.begin(), tube.normals.end());
      into.texcoords.insert(into.texcoords.end(), tube.texcoords.begin(), tube.texcoords.end());
      for (uint32_t index : tube.indices) into.indices.push_back(base + index);
    }
  }
  return out;
}

}  // namespace ontogen
