#include "interpreters/physics/rigid_statics.h"

#include <Eigen/Geometry>

namespace ontogen {

Eigen::Vector3d weightOf(const Rod& rod, double g) { return -rod.mass() * g * kWorldUp; }

std::vector<RodLoads> solveRigidStatics(std::span<const Rod> rods, std::span<const int> leavesFirst, double g) {
  std::vector<RodLoads> loads(rods.size());
  // Each rod starts with its own terms; when the sweep reaches it its children have
  // added theirs, and it adds itself to its parent.
  for (size_t i = 0; i < rods.size(); ++i) {
    const Rod& rod = rods[i];
    const Eigen::Vector3d weight = weightOf(rod, g);
    loads[i].force = weight + rod.load;
    loads[i].moment = (0.5 * (rod.tip - rod.base)).cross(weight) + (rod.loadPoint() - rod.base).cross(rod.load);
  }
  for (int i : leavesFirst) {
    const Rod& rod = rods[static_cast<size_t>(i)];
    if (rod.parentIndex < 0) continue;
    const Rod& parent = rods[static_cast<size_t>(rod.parentIndex)];
    RodLoads& up = loads[static_cast<size_t>(rod.parentIndex)];
    const RodLoads& own = loads[static_cast<size_t>(i)];
    up.force += own.force;
    up.moment += (rod.base - parent.base).cross(own.force) + own.moment;
  }
  return loads;
}

}  // namespace ontogen
