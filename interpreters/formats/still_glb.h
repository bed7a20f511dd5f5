#pragma once
// The still part of a .glb: what never moves over a run's frames (all of a run of one
// frame) written as merged meshes in world coordinates, not as a skinned joint per cell
// (formats/glb_writer.h), so that the file grows with what it shows.
//
// - Surfaces and, up to kMaxBakedLines segments, lines (as tubes, like the animated
//   parts) go into one mesh, "still", of one primitive per colour. Each vertex carries
//   TEXCOORD_1 = (cell number, birth in seconds), as the animated parts do: the cell that
//   drew it, numbered in order of appearance (the nodes' order, then whatever no node
//   covers), so a reader still tells the cells apart.
// - Beyond kMaxBakedLines segments, the lines are instances of one tube (radius 1 from
//   y = -1 to 1, kTubeSides sides) by EXT_mesh_gpu_instancing: a node per colour,
//   "lines <palette index>", whose instances each place the tube on a segment
//   (TRANSLATION its midpoint, ROTATION taking +y to its direction, SCALE (r, half its
//   length, r)) and carry _CELL = (cell number, birth). 48 bytes a segment where a baked
//   tube takes 832; importers that lack the extension (Blender 3.4) show one tube.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "interpreters/formats/gltf_builder.h"
#include "interpreters/geometry.h"
#include "interpreters/scene.h"

namespace ontogen {

/// Segments written as baked tubes in the still mesh; more are instanced. A baked tube
/// takes 832 bytes (16 vertices, 16 triangles) where its segment takes about 50 in an
/// OBJ: 4,096 of them are 3.3 MiB, which every importer reads (Koch's curve up to
/// n = 5); beyond, the file would pass the OBJ's size many times over.
inline constexpr std::size_t kMaxBakedLines = 4096;

/// Where a tube of radius `radius` stands on the segment a -> b: the unit tube (radius 1,
/// y from -1 to 1) rotated by `rotation` and scaled by `scale`, then moved to `translation`.
struct TubePlacement {
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1, 0, 0, 0};  ///< unit; takes +y to the segment's direction
  glm::dvec3 scale{1.0};            ///< (radius, half the length, radius)
};

/// The placement of the tube on a -> b (a != b).
TubePlacement tubeOn(const glm::dvec3& a, const glm::dvec3& b, double radius);

/// Lines of one palette colour as instances of the unit tube (EXT_mesh_gpu_instancing):
/// per instance its placement (TRANSLATION, ROTATION, SCALE) and its cell (_CELL).
struct TubeInstances {
  std::vector<glm::vec3> translations, scales;
  std::vector<float> rotations;  ///< x, y, z, w per instance
  std::vector<float> cells;      ///< cell number, birth (seconds) per instance
  std::size_t size() const { return translations.size(); }
  /// Adds the tube of `radius` on a -> b (a != b), drawn by `cell`.
  void add(const glm::dvec3& a, const glm::dvec3& b, double radius, const glm::vec2& cell);
};

/// Writes nodes of instanced tubes into a builder, the unit tube's accessors once for all.
class TubeInstancer {
 public:
  explicit TubeInstancer(gltf::Builder& builder) : builder_(builder) {}
  /// Adds a mesh of the tube in colour `material` and a node `name` that instances it;
  /// returns the node's index.
  std::size_t addNode(uint32_t material, const TubeInstances& instances, const std::string& name);

 private:
  gltf::Builder& builder_;
  nlohmann::json primitive_;  // the unit tube's, made at the first node
};

/// Adds the still mesh (and the instanced lines) of a scene's geometry to the builder,
/// their nodes to sceneNodes; lines become tubes of `lineRadius` (model units).
void addStillScene(gltf::Builder& builder, const Scene& scene, double lineRadius, nlohmann::json& sceneNodes);

}  // namespace ontogen
