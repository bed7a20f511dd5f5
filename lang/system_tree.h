#pragma once
// Which systems contain which (paper 002, section 2.2): system S contains system T when
// T's cell can appear in S's pool, through S's axiom, its placements or any successor
// of a cell that can live there. The containment must be a tree; this class finds a
// cycle if there is one (Boost.Graph's depth-first search) and answers the questions the
// compiler asks of the tree.

#include <vector>

#include "lang/program.h"

namespace ontogen {

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

 private:
  const Program& program_;
  std::vector<std::vector<bool>> holds_;  ///< per system, per master
};

}  // namespace ontogen
