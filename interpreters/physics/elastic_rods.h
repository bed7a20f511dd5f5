#pragma once
// The elastic design model: a rod tree that bends under the loads of the statics, with
// the geometry exact (large deflections, not only the small-slope formula).
//
// Each rod is cut into n straight segments, and each segment into two rigid halves
// joined at its midpoint by a rotational spring of compliance h / EI (h the segment's
// length): the midpoint rule for the curvature M / EI of a Kirchhoff rod, so a
// cantilever's tip deflection converges as 1 / (4 n^2) (a rod of 4 segments is within
// 2 %, of 40 within 0.02 %). The moment a spring carries is that of every load beyond
// it, taken in the deflected shape: the weights (half a segment's at each half's middle),
// the external forces where they act and, through the joints, the children. Rods are
// torsionally rigid (a moment about a rod's axis turns nothing), joints between rods
// rigid (they keep their rest angles), roots clamped at their bases; loads keep their
// direction as the tree bends (dead loads).
//
// The shape is the fixed point of shape -> moments -> spring rotations -> shape, found
// by relaxed iteration: each sweep (leaves to root for the moments, root to leaves for
// the shape) moves every spring's rotation a fraction w of the way to what its moment
// asks; w starts at 1 and halves whenever the largest change grows, which converges for
// the stable equilibria of a conservative system however large the load.

#include <span>
#include <vector>

#include <Eigen/Core>

#include "interpreters/physics/rigid_statics.h"
#include "interpreters/physics/rod_table.h"

namespace ontogen {

struct ElasticDef {
  int segments = 4;            ///< per rod, 1..1024
  double tolerance = 1e-12;    ///< on the springs' rotations, rad (relative beyond 1 rad)
  int maxIterations = 20000;   ///< sweeps before the solve gives up
  double g = kGravity;         ///< m/s^2, down kWorldUp
};

/// The deflected tree.
struct ElasticSolution {
  std::vector<RodLoads> loads;          ///< per rod, at its deflected base (moments in the deflected shape)
  std::vector<Eigen::Vector3d> base;    ///< per rod, deflected, m
  std::vector<Eigen::Vector3d> tip;     ///< per rod, deflected, m
  /// Per rod 2 n + 1 points from base to tip (segment bases and midpoints, then the tip).
  std::vector<Eigen::Vector3d> polyline;
  int segments = 0;
  int iterations = 0;
  bool converged = false;
  double residual = 0;  ///< the largest change of a spring's rotation in the last sweep, rad

  /// Rod i's polyline.
  std::span<const Eigen::Vector3d> shape(size_t i) const {
    const auto n = static_cast<size_t>(2 * segments + 1);
    return std::span<const Eigen::Vector3d>(polyline).subspan(i * n, n);
  }
};

/// Solves the elastic model; throws std::invalid_argument when def is out of range.
ElasticSolution solveElasticRods(std::span<const Rod> rods, std::span<const int> leavesFirst, const ElasticDef& def);

}  // namespace ontogen
