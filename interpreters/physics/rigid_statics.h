#pragma once
// The statics of a rigid rod tree with a fixed root and free leaves (paper 003, section 3,
// Eq. 1 and Eq. 2), solved in one sweep from the leaves to the root:
//
//   F_i = f_i + G_i + sum_k F_k
//   M_i = r_i x f_i + (x_i - P_i) x G_i + sum_k [ (P_k - P_i) x F_k + M_k ]
//
// for rod i with base P_i, weight f_i = -m_i g up acting at its midpoint (r_i = l_i / 2),
// external force G_i acting at x_i, and children k. F_i is the force the part of the tree
// above rod i's base (the rod and everything it carries) puts on the joint at that base,
// M_i its moment about the base. A child whose base is the parent's tip has
// P_k - P_i = l_i, the paper's lever; Fig. 6's pseudo-code uses r_i there, which is wrong,
// and prints g = 9.91. The root's F and M are what its fixed support must resist.

#include <span>
#include <vector>

#include <Eigen/Core>

#include "interpreters/physics/rod_table.h"

namespace ontogen {

/// Standard gravity, m/s^2.
inline constexpr double kGravity = 9.81;
/// The world's up axis: the turtle grows along +y and the renderer looks down -y.
inline const Eigen::Vector3d kWorldUp = Eigen::Vector3d::UnitY();

/// The force and moment at a rod's base joint.
struct RodLoads {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   ///< N
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  ///< N m, about the rod's base
};

/// Eq. 1 and Eq. 2 for every rod, in the rods' order. `leavesFirst` lists every rod after
/// its children (RodTable::leavesFirst); g in m/s^2 pulls down kWorldUp.
std::vector<RodLoads> solveRigidStatics(std::span<const Rod> rods, std::span<const int> leavesFirst,
                                        double g = kGravity);

/// The weight of a rod, N (a vector down the up axis).
Eigen::Vector3d weightOf(const Rod& rod, double g);

}  // namespace ontogen
