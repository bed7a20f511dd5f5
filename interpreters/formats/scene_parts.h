#pragma once
// A run's frames as persistent parts: the shapes cells drew, each kept once, and where
// each cell's shape stood in every frame.
//
// A cell's part of a frame (the scene's node: the triangles and segments it drew) is
// taken into its own frame (the node's position and orientation), then centred on its
// bounding box and divided by its largest half-extent: its shape, which lies in
// [-1, 1]^3. Shapes are kept once for the whole run: a part that differs from one
// already kept only by a uniform scale and a shift in its cell's frame (a sphere that
// grows, the same tube drawn by a thousand cells) takes that shape. Each frame then
// holds, for every part, its joint (the cell and the shape it takes) and the transform
// that places the shape: translation, rotation, uniform scale. A cell whose part changes
// beyond that (a surface that blends between heads, a colour that changes) takes a new
// shape, so a new joint; it switches between them over the frames.
//
// Equality is taken after rounding the shape's coordinates to 2^-18 of its size (4 ppm:
// far below a pixel at any picture size), normals to 2^-14 and texture coordinates to
// 2^-16; a part takes the first such shape's exact values.
//
// What the scene's nodes do not cover (a set that records no nodes, geometry drawn
// between cells) is one part of its own, of the node id kRestPart, in the world's frame.

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>

#include "interpreters/formats/mesh_batches.h"
#include "interpreters/geometry.h"
#include "interpreters/scene.h"

namespace ontogen {

/// The node id of the part that no node covers.
inline constexpr uint64_t kRestPart = kNoParentNode;

/// A shape: batches by colour, centred and scaled into [-1, 1]^3 (segments as pairs of
/// points in MeshBatch::lines, not yet tubes).
struct PartShape {
  std::vector<MeshBatch> batches;
  double scaleSum = 0;         ///< the sum of the scales it was placed at, model units
  uint64_t placementCount = 0; ///< how many times it was placed
  /// The mean scale it was placed at (model units per shape unit); 1 if never placed.
  double meanScale() const { return placementCount > 0 ? scaleSum / static_cast<double>(placementCount) : 1.0; }
};

/// A cell drawing one shape: what a glTF joint or node stands for.
struct PartJoint {
  uint64_t cell = 0;                 ///< the cell's stable id (kRestPart: the uncovered rest)
  uint64_t parent = kNoParentNode;   ///< its parent's id when it first appeared
  std::string label;                 ///< its master's label
  double birth = 0;                  ///< when it had age 0, seconds
  uint32_t shape = 0;                ///< index in shapes()
  uint32_t cellNumber = 0;           ///< index of its cell among cells in order of appearance
  uint32_t variant = 0;              ///< 0 for the cell's first shape, 1 for its second, ...
};

/// Where a joint's shape stands in a frame: world = translation + rotation (scale p).
struct PartPlacement {
  uint32_t joint = 0;
  glm::dvec3 translation{0.0};         ///< model units
  glm::dquat rotation{1, 0, 0, 0};     ///< unit
  double scale = 1;                    ///< model units per shape unit, > 0
};

struct PartFrame {
  double time = 0;                          ///< seconds of developmental time
  std::vector<PartPlacement> placements;    ///< in the order the scene's nodes came
};

class SceneParts {
 public:
  /// Takes a frame's scene apart (its geometry and nodes).
  void addFrame(const Scene& scene);
  void clear();

  const std::vector<PartShape>& shapes() const { return shapes_; }
  const std::vector<PartJoint>& joints() const { return joints_; }
  const std::vector<PartFrame>& frames() const { return frames_; }
  /// The number of distinct cells (PartJoint::cellNumber is below it).
  std::size_t cellCount() const { return cellNumbers_.size(); }
  /// Every frame's geometry together, model units.
  const Box& bounds() const { return bounds_; }
  /// The bytes held, near enough for a memory limit.
  uint64_t heldBytes() const { return heldBytes_; }
  /// The joints of each shape (its instances), by shape index.
  std::vector<std::vector<uint32_t>> jointsByShape() const;

 private:
  struct Key;
  uint32_t shapeOf(std::vector<MeshBatch>&& batches);
  void addPart(const Scene& scene, const SceneNode& node, const std::vector<uint32_t>& triangles,
               const std::vector<uint32_t>& segments, PartFrame& frame);

  std::vector<PartShape> shapes_;
  std::vector<std::vector<int32_t>> keys_;  // each shape's rounded coordinates and colours
  std::unordered_multimap<uint64_t, uint32_t> byHash_;
  std::vector<PartJoint> joints_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> jointsOfCell_;  // cell id -> joints
  std::unordered_map<uint64_t, uint32_t> cellNumbers_;
  std::vector<PartFrame> frames_;
  Box bounds_;
  uint64_t heldBytes_ = 0;
  Geometry scratch_;  // a part in its shape's coordinates, regrouped by batchByMaterial
};

/// The part of a shape's batches as triangles only: its segments made tubes of `radius`
/// (shape units) with `sides` sides, in the batch of their colour.
std::vector<MeshBatch> shapeWithTubes(const PartShape& shape, double radius, int sides);

}  // namespace ontogen
