#pragma once
// Paper 003's two tables, keyed by the stable cell ids of the engine (core/parents.h):
// the relationship table (who is whose child: the paper's isChildOf and
// getIdOfLeftNeighbour) and the design-model table (per rod its geometry and attributes,
// the paper's treeTab, a row made by createTreeTableElement). A frame's rods are added in
// word order; a rod's parent is the rod of the nearest cell above it in the word's axial
// tree. The relationship graph (Boost.Graph, edges parent -> child) gives the order the
// solvers sweep in: leaves to root, a topological order.
//
// Rows are kept across frames: a rod keeps its row (and the time it first appeared)
// while its cell lives, and the row of a rod that is gone is dropped at the end of the
// frame. Units: metres, kilograms, newtons; positions in world coordinates (y up).

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

namespace ontogen {

/// Marks a rod with no parent rod: a root, fixed at its base.
inline constexpr uint64_t kNoParentRod = ~uint64_t{0};

/// One rod of a frame: a straight, uniform cylinder from its base (the end towards the
/// root, where the turtle stood) to its tip.
struct Rod {
  uint64_t id = 0;                   ///< the stable id of the cell that drew it (a second rod: derived)
  uint64_t parent = kNoParentRod;    ///< the parent rod's id
  int parentIndex = -1;              ///< its index in the frame's rods (set by RodTable::finish)
  Eigen::Vector3d base = Eigen::Vector3d::Zero();  ///< m
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();   ///< m, at rest
  Eigen::Vector3d side = Eigen::Vector3d::UnitX(); ///< the turtle's L as it drew (unit), for drawing
  double radius = 0;                 ///< m
  double density = 1;                ///< kg/m^3
  Eigen::Vector3d load = Eigen::Vector3d::Zero();  ///< external force G, N
  double loadAt = 1;                 ///< where G acts: fraction of the length from the base, 0..1
  double stiffness = 0;              ///< bending stiffness EI, N m^2; 0: rigid
  uint32_t material = 0;             ///< palette colour

  double length() const { return (tip - base).norm(); }
  /// density * pi r^2 * length, kg.
  double mass() const;
  /// The point G acts at, at rest.
  Eigen::Vector3d loadPoint() const { return base + loadAt * (tip - base); }
};

/// A row of the design-model table as it persists across frames.
struct RodRow {
  uint64_t parent = kNoParentRod;
  double since = 0;  ///< the time of the first frame the rod was in, s
  int index = -1;    ///< in the last finished frame's rods
};

class RodTable {
 public:
  /// Starts a frame at `time` (s): no rods yet; rows stay until finish().
  void beginFrame(double time);
  /// Adds a rod; returns its index in rods().
  int add(const Rod& rod);
  /// Ends the frame: links each rod to its parent rod by id (a parent that drew no rod
  /// makes a root), drops the rows of rods that are gone, builds the relationship graph
  /// and the sweep order.
  void finish();

  /// The frame's rods, in the order they were drawn.
  std::span<const Rod> rods() const { return rods_; }
  /// Rod indices leaves first: every rod comes after all of its children (a reverse
  /// topological order of the relationship graph).
  std::span<const int> leavesFirst() const { return order_; }
  /// The rows kept across frames, by rod id.
  const std::unordered_map<uint64_t, RodRow>& rows() const { return rows_; }
  /// The children of rod i (after finish()).
  std::span<const int> children(int i) const;

 private:
  double time_ = 0;
  std::vector<Rod> rods_;
  std::vector<int> order_;
  std::vector<int> childStart_, childList_;
  std::unordered_map<uint64_t, RodRow> rows_;
};

/// The sweep order of a rod tree given by parent indices (-1: a root), leaves first,
/// from a topological sort of the relationship graph (Boost.Graph); throws
/// std::logic_error if the parents form a cycle.
std::vector<int> leavesFirstOrder(std::span<const int> parentIndices);

}  // namespace ontogen
