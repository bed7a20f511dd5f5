#pragma once
// What a frame of the geometry is, as sets produce it and the output stage writes it: the
// frame's Geometry (every line and surface, in world coordinates) and a graph of nodes
// over it, one per cell that drew something, keyed by the cell's stable id, each with its
// parent's id (core/parents.h), where the turtle stood when the cell began (position and
// frame), and the ranges of the Geometry it drew. Ids persist across frames, so a node
// can be followed over time: the joints of a creature, the rods of a physics model.
// Several sets draw into one scene (arrows beside the geometry, a skeleton beside its
// skin); writers read the Geometry and, where a format has nodes, the graph.

#include <cstdint>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "interpreters/geometry.h"

namespace ontogen {

/// The id a node has when it hangs from nothing (as core/parents.h's kNoParent).
inline constexpr uint64_t kNoParentNode = ~uint64_t{0};

/// The stretch of one node in the scene's Geometry: triangles, segments (contiguous).
struct GeometryRange {
  uint32_t firstTriangle = 0;
  uint32_t triangleCount = 0;
  uint32_t firstSegment = 0;
  uint32_t segmentCount = 0;
  bool empty() const { return triangleCount == 0 && segmentCount == 0; }
};

/// A cell's part of the scene.
struct SceneNode {
  uint64_t id = 0;                   ///< the cell's stable id (64 bits)
  uint64_t parent = kNoParentNode;   ///< its parent's id (it may have drawn nothing)
  glm::dvec3 position{0.0};          ///< where the turtle stood as the cell began, model units
  /// The turtle's frame then, columns H, L, U (unit, right-handed): the node's orientation.
  glm::dmat3 orientation{1.0};
  GeometryRange range;               ///< what it drew
  std::string label;                 ///< its master's label ("" for a node no cell drew)
  double birth = 0;                  ///< global time at which the cell had age 0, seconds
};

/// Which side of its body a limb is on.
enum class BodySide { None, Left, Right };

/// A joint of an articulated body (interpreters/creature/): where it is in the frame and
/// what hangs from it. Its id persists across frames, like a node's.
struct SceneJoint {
  uint64_t id = 0;        ///< the joint cell's stable id (a second joint of one cell: derived from it)
  int parent = -1;        ///< index in Skeleton::joints of the joint it hangs from; -1: a root
  std::string name;       ///< the cell's label and the joint's index, unique in the skeleton
  glm::dvec3 position{0.0};         ///< world position, model units
  glm::dmat3 orientation{1.0};      ///< world frame, columns H, L, U (unit, right-handed)
  bool foot = false;                ///< the end of a leg
  BodySide side = BodySide::None;   ///< of a leg's joints
  int segment = -1;                 ///< body segment (from the head, 0), -1: none
};

/// A stretch of the scene's triangles that moves rigidly with one joint.
struct SkinRange {
  uint32_t firstTriangle = 0;
  uint32_t triangleCount = 0;
  int joint = 0;  ///< index in Skeleton::joints
};

/// The articulated bodies of a frame: joints in an order where parents come first, and
/// which triangles of the scene each one carries.
struct Skeleton {
  std::vector<SceneJoint> joints;
  std::vector<SkinRange> skin;
  /// True when a simulation posed the joints (the dynamics set): `contacts` is then known.
  bool simulated = false;
  /// Indices in `joints` of the joints whose limbs touch the ground, ascending.
  std::vector<int> contacts;
  bool empty() const { return joints.empty(); }
};

struct Scene {
  double time = 0;  ///< seconds of developmental time
  Geometry geometry;
  std::vector<SceneNode> nodes;  ///< in the order the cells were drawn
  Skeleton skeleton;             ///< empty unless a set draws articulated bodies

  /// The node of a cell, or null.
  const SceneNode* find(uint64_t id) const;
  /// Empties the scene for the next frame, keeping the tessellation settings.
  void clear();
  /// Appends another scene's geometry and nodes (their ranges shifted to match).
  void append(const Scene& other);
  /// The same, taking other's nodes and geometry buffers where this scene has none of
  /// its own instead of copying them; other is left valid but unspecified (clear it).
  void append(Scene&& other);
};

}  // namespace ontogen
