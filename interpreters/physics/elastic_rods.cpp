#include "interpreters/physics/elastic_rods.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

namespace ontogen {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// exp of the rotation vector v (Rodrigues).
Matrix3d rotation(const Vector3d& v) {
  const double angle = v.norm();
  if (angle < 1e-300) return Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, v / angle).toRotationMatrix();
}

// What a rod's rest shape and loads give each of its segments.
struct RodPlan {
  Vector3d direction;       // unit, at rest
  Vector3d offset;          // base - parent's tip, at rest
  double h = 0;             // segment length
  double compliance = 0;    // h / EI; 0: rigid
  Vector3d halfWeight;      // half a segment's weight, N
  int loadSegment = 0;      // where G acts: segment, and distance from its base along it
  double loadDistance = 0;
};

}  // namespace

ElasticSolution solveElasticRods(std::span<const Rod> rods, std::span<const int> leavesFirst, const ElasticDef& def) {
  if (def.segments < 1 || def.segments > 1024) throw std::invalid_argument("elastic rods take 1 to 1024 segments");
  if (!(def.tolerance > 0) || def.maxIterations < 1) throw std::invalid_argument("bad elastic tolerance or iterations");
  const size_t count = rods.size();
  const auto n = static_cast<size_t>(def.segments);
  std::vector<RodPlan> plan(count);
  for (size_t i = 0; i < count; ++i) {
    const Rod& rod = rods[i];
    RodPlan& p = plan[i];
    const double length = rod.length();
    p.direction = length > 0 ? Vector3d((rod.tip - rod.base) / length) : Vector3d(kWorldUp);
    p.offset = rod.parentIndex < 0 ? Vector3d::Zero() : Vector3d(rod.base - rods[static_cast<size_t>(rod.parentIndex)].tip);
    p.h = length / static_cast<double>(n);
    p.compliance = rod.stiffness > 0 ? p.h / rod.stiffness : 0;
    p.halfWeight = 0.5 * weightOf(rod, def.g) / static_cast<double>(n);
    const double along = std::clamp(rod.loadAt, 0.0, 1.0) * static_cast<double>(n);
    p.loadSegment = std::min(static_cast<int>(along), def.segments - 1);
    p.loadDistance = (along - p.loadSegment) * p.h;
  }

  const size_t total = count * n;
  std::vector<Vector3d> phi(total, Vector3d::Zero()), target(total, Vector3d::Zero());
  std::vector<Vector3d> xb(total), xm(total), xt(total), db(total), dt(total);
  std::vector<Matrix3d> tipRotation(count);
  std::vector<RodLoads> loads(count);
  std::vector<RodLoads> carried(count);  // children's force, and moment about the deflected tip

  auto shapePass = [&] {
    for (auto it = leavesFirst.rbegin(); it != leavesFirst.rend(); ++it) {
      const auto i = static_cast<size_t>(*it);
      const Rod& rod = rods[i];
      const RodPlan& p = plan[i];
      Matrix3d q = Matrix3d::Identity();
      Vector3d x = rod.base;
      if (rod.parentIndex >= 0) {
        const auto parent = static_cast<size_t>(rod.parentIndex);
        q = tipRotation[parent];
        x = xt[parent * n + n - 1] + q * p.offset;
      }
      for (size_t k = 0; k < n; ++k) {
        const size_t s = i * n + k;
        xb[s] = x;
        db[s] = q * p.direction;
        xm[s] = x + 0.5 * p.h * db[s];
        q = rotation(phi[s]) * q;
        dt[s] = q * p.direction;
        xt[s] = xm[s] + 0.5 * p.h * dt[s];
        x = xt[s];
      }
      tipRotation[i] = q;
    }
  };
  auto loadPass = [&] {
    for (RodLoads& c : carried) c = RodLoads{};
    for (int index : leavesFirst) {
      const auto i = static_cast<size_t>(index);
      const Rod& rod = rods[i];
      const RodPlan& p = plan[i];
      Vector3d force = carried[i].force, moment = carried[i].moment;  // about the rod's tip
      for (size_t k = n; k-- > 0;) {
        const size_t s = i * n + k;
        const bool loaded = static_cast<int>(k) == p.loadSegment;
        const double half = 0.5 * p.h;
        // The tip half: from its spring at xm to xt.
        Vector3d midForce = force + p.halfWeight;
        Vector3d midMoment = moment + (xt[s] - xm[s]).cross(force) + (0.5 * half * dt[s]).cross(p.halfWeight);
        if (loaded && p.loadDistance >= half) {
          midForce += rod.load;
          midMoment += ((p.loadDistance - half) * dt[s]).cross(rod.load);
        }
        target[s] = p.compliance * (midMoment - midMoment.dot(db[s]) * db[s]);
        // The base half: from xb to xm.
        force = midForce + p.halfWeight;
        moment = midMoment + (xm[s] - xb[s]).cross(midForce) + (0.5 * half * db[s]).cross(p.halfWeight);
        if (loaded && p.loadDistance < half) {
          force += rod.load;
          moment += (p.loadDistance * db[s]).cross(rod.load);
        }
      }
      loads[i] = {force, moment};
      if (rod.parentIndex >= 0) {
        const auto parent = static_cast<size_t>(rod.parentIndex);
        carried[parent].force += force;
        carried[parent].moment += (xb[i * n] - xt[parent * n + n - 1]).cross(force) + moment;
      }
    }
  };

  ElasticSolution solution;
  double relaxation = 1, previous = INFINITY;
  for (int iteration = 1; iteration <= def.maxIterations; ++iteration) {
    shapePass();
    loadPass();
    double residual = 0, largest = 0;
    for (size_t s = 0; s < total; ++s) {
      residual = std::max(residual, (target[s] - phi[s]).norm());
      largest = std::max(largest, phi[s].norm());
    }
    solution.iterations = iteration;
    solution.residual = residual;
    if (!std::isfinite(residual)) break;
    if (residual <= def.tolerance * std::max(1.0, largest)) {
      solution.converged = true;
      break;
    }
    if (residual > previous) relaxation = std::max(relaxation / 2, 1.0 / 1024);
    previous = residual;
    for (size_t s = 0; s < total; ++s) phi[s] += relaxation * (target[s] - phi[s]);
  }

  solution.segments = def.segments;
  solution.loads = std::move(loads);
  solution.base.resize(count);
  solution.tip.resize(count);
  solution.polyline.resize(count * (2 * n + 1));
  for (size_t i = 0; i < count; ++i) {
    solution.base[i] = xb[i * n];
    solution.tip[i] = xt[i * n + n - 1];
    Vector3d* points = &solution.polyline[i * (2 * n + 1)];
    for (size_t k = 0; k < n; ++k) {
      points[2 * k] = xb[i * n + k];
      points[2 * k + 1] = xm[i * n + k];
    }
    points[2 * n] = solution.tip[i];
  }
  return solution;
}

}  // namespace ontogen
