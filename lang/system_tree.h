#pragma once
// Which systems contain which (paper 002, section 2.2): system S contains system T when
// T's cell can appear in S's pool, through S's axiom, its placements or any successor
// of a cell that can live there. The containment must be a tree; this class finds a
// cycle if there is one (Boost.Graph's depth-first search) and answers the questions the
// compiler asks of the tree.

#include <vector>

#include "model/program.h"

namespace ontogen {

/// Most systems in one program. The compiler's whole-program passes weigh every system
/// against every cell, so their cost grows with the square of the count (30,000 systems
/// took minutes and gigabytes); the models have three at most, generated programs a few
/// hundred.
inline constexpr size_t kMaxSystems = 1024;
/// Most systems nested inside each other, the root counting as one. Paper 002's
/// hierarchies are a few levels deep (an orchard of trees of branches is three); the
/// engine steps and captures nested pools recursively, so depth costs stack.
inline constexpr int kMaxSystemDepth = 64;

class SystemTree {
 public:
  explicit SystemTree(const Program& program);

  /// The masters a system's pool can hold: its axiom and placements, and every
  /// successor of their rules, transitively (not the cells of nested systems' pools).
  static std::vector<bool> reachableMasters(const Program& program, const SystemDefinition& system);

  /// A cycle of containment as system indices, first system repeated at the end
  /// (a contains b contains a), or empty if the systems form a tree.
  std::vector<int> findCycle() const;
  /// The systems whose pools can hold system s's cell.
  std::vector<int> containers(int s) const;
  /// The systems whose pools can hold cells of this master.
  std::vector<int> systemsHolding(MasterId master) const;
  /// The longest chain of containment that ends at each system, from a system no other
  /// contains (1 for such a system), with the system above it on that chain (-1 for
  /// none). Only for a tree (findCycle() empty).
  struct Depths {
    std::vector<int> depth;
    std::vector<int> above;
  };
  Depths depths() const;

 private:
  const Program& program_;
  std::vector<std::vector<bool>> holds_;  ///< per system, per master
};

}  // namespace ontogen
