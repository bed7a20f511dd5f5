#pragma once
// What the physics set solved in a frame: per rod its place in the tree, its rest and
// deflected shape and the force and moment at its base joint; what `ontogen statics`
// prints and the arrows are drawn from. World coordinates, SI units.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "interpreters/physics/rigid_statics.h"
#include "interpreters/physics/rod_table.h"

namespace ontogen {

struct RodResult {
  uint64_t id = 0;
  uint64_t parent = kNoParentRod;
  Eigen::Vector3d base = Eigen::Vector3d::Zero();     ///< m (deflected where the elastic model is on)
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();      ///< m (deflected where the elastic model is on)
  Eigen::Vector3d restTip = Eigen::Vector3d::Zero();  ///< m, before bending
  double length = 0;                                  ///< m
  double mass = 0;                                    ///< kg
  Eigen::Vector3d force = Eigen::Vector3d::Zero();    ///< N, Eq. 1: what the rod and all it carries put on its base
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();   ///< N m about its base, Eq. 2 (in the deflected shape)
  Eigen::Vector3d load = Eigen::Vector3d::Zero();     ///< the external force on it, N
  Eigen::Vector3d loadPoint = Eigen::Vector3d::Zero();  ///< where it acts, m
};

struct PhysicsFrame {
  double time = 0;   ///< s
  double g = kGravity;
  bool elastic = false;   ///< the elastic model solved the frame
  int segments = 0;       ///< of each rod, when elastic
  int iterations = 0;     ///< of the elastic solve
  bool converged = true;  ///< false when the elastic solve gave up (the rigid shape is kept)
  std::vector<RodResult> rods;  ///< in the order they were drawn
};

}  // namespace ontogen
