// The physics design models on a binary rod tree of 2^20 - 1 = 1,048,575 rods (20
// generations, each rod 0.8 as long as its parent, branches 30 degrees either way in
// alternating planes): the rigid statics (Eq. 1, Eq. 2) with the relationship graph's
// sweep order, and the elastic solve (one segment a rod, stiff enough to converge in a
// few sweeps); against the same rigid statics written by hand over plain arrays, where
// the order is the rods' own (parents before children) and no graph is built.

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "interpreters/physics/elastic_rods.h"
#include "interpreters/physics/rigid_statics.h"
#include "interpreters/physics/rod_table.h"

namespace ontogen::bench {
namespace {

constexpr int kGenerations = 20;

// Rods in breadth-first order: rod i's children are 2i + 1 and 2i + 2.
std::vector<Rod> binaryRodTree() {
  const size_t count = (size_t{1} << kGenerations) - 1;
  std::vector<Rod> rods(count);
  std::vector<Eigen::Vector3d> heading(count);
  const Eigen::Vector3d axes[2] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX()};
  for (size_t i = 0; i < count; ++i) {
    Rod& rod = rods[i];
    rod.id = i;
    int level = 0;
    for (size_t k = i + 1; k > 1; k >>= 1) ++level;
    const double length = 5 * std::pow(0.8, level);
    if (i == 0) {
      heading[i] = Eigen::Vector3d::UnitY();
      rod.base = Eigen::Vector3d::Zero();
    } else {
      const size_t parent = (i - 1) / 2;
      rod.parent = parent;
      rod.parentIndex = static_cast<int>(parent);
      const double angle = (i % 2 ? 1 : -1) * std::numbers::pi / 6;
      heading[i] = Eigen::AngleAxisd(angle, axes[level % 2]) * heading[parent];
      rod.base = rods[parent].tip;
    }
    rod.tip = rod.base + length * heading[i];
    rod.radius = length / 20;
    rod.density = 700;
    rod.stiffness = 1e10 * std::numbers::pi * std::pow(rod.radius, 4) / 4;
  }
  return rods;
}

const std::vector<Rod>& tree() {
  static const std::vector<Rod> rods = binaryRodTree();
  return rods;
}

std::vector<int> parentIndices(const std::vector<Rod>& rods) {
  std::vector<int> parents(rods.size());
  for (size_t i = 0; i < rods.size(); ++i) parents[i] = rods[i].parentIndex;
  return parents;
}

void BM_RigidStatics(benchmark::State& state) {
  const std::vector<Rod>& rods = tree();
  const std::vector<int> parents = parentIndices(rods);
  double mass = 0;
  for (const Rod& rod : rods) mass += rod.mass();
  double rootForce = 0;
  for (auto _ : state) {
    const std::vector<int> order = leavesFirstOrder(parents);  // the relationship graph's sort
    std::vector<RodLoads> loads = solveRigidStatics(rods, order);
    rootForce = loads[0].force.y();
    benchmark::DoNotOptimize(loads.data());
  }
  if (std::abs(rootForce / (-kGravity * mass) - 1) > 1e-9) state.SkipWithError("the root does not carry the tree's weight");
  state.counters["rods/s"] = benchmark::Counter(static_cast<double>(rods.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_RigidStatics)->Unit(benchmark::kMillisecond);

void BM_RigidStaticsSweepOnly(benchmark::State& state) {
  const std::vector<Rod>& rods = tree();
  const std::vector<int> order = leavesFirstOrder(parentIndices(rods));
  for (auto _ : state) {
    std::vector<RodLoads> loads = solveRigidStatics(rods, order);
    benchmark::DoNotOptimize(loads.data());
  }
  state.counters["rods/s"] = benchmark::Counter(static_cast<double>(rods.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_RigidStaticsSweepOnly)->Unit(benchmark::kMillisecond);

// The same Eq. 1 and Eq. 2 by hand: structure-of-arrays, the reverse of the rods' order.
void BM_RigidStaticsHandWritten(benchmark::State& state) {
  const std::vector<Rod>& rods = tree();
  const size_t n = rods.size();
  std::vector<double> base(3 * n), tip(3 * n), mass(n);
  std::vector<int> parent(n);
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      base[3 * i + k] = rods[i].base[k];
      tip[3 * i + k] = rods[i].tip[k];
    }
    mass[i] = rods[i].mass();
    parent[i] = rods[i].parentIndex;
  }
  std::vector<double> force(3 * n), moment(3 * n);
  for (auto _ : state) {
    for (size_t i = 0; i < n; ++i) {
      const double w = -mass[i] * kGravity;  // along y
      const double hx = 0.5 * (tip[3 * i] - base[3 * i]), hz = 0.5 * (tip[3 * i + 2] - base[3 * i + 2]);
      force[3 * i] = 0, force[3 * i + 1] = w, force[3 * i + 2] = 0;
      moment[3 * i] = -hz * w, moment[3 * i + 1] = 0, moment[3 * i + 2] = hx * w;
    }
    for (size_t i = n; i-- > 1;) {
      const auto p = static_cast<size_t>(parent[i]);
      const double* f = &force[3 * i];
      const double lx = base[3 * i] - base[3 * p], ly = base[3 * i + 1] - base[3 * p + 1],
                   lz = base[3 * i + 2] - base[3 * p + 2];
      force[3 * p] += f[0], force[3 * p + 1] += f[1], force[3 * p + 2] += f[2];
      moment[3 * p] += ly * f[2] - lz * f[1] + moment[3 * i];
      moment[3 * p + 1] += lz * f[0] - lx * f[2] + moment[3 * i + 1];
      moment[3 * p + 2] += lx * f[1] - ly * f[0] + moment[3 * i + 2];
    }
    benchmark::DoNotOptimize(force.data());
    benchmark::DoNotOptimize(moment.data());
  }
  state.counters["rods/s"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_RigidStaticsHandWritten)->Unit(benchmark::kMillisecond);

void BM_ElasticRods(benchmark::State& state) {
  const std::vector<Rod>& rods = tree();
  const std::vector<int> order = leavesFirstOrder(parentIndices(rods));
  ElasticDef def;
  def.segments = 1;
  def.tolerance = 1e-10;
  int iterations = 0;
  for (auto _ : state) {
    ElasticSolution solution = solveElasticRods(rods, order, def);
    if (!solution.converged) state.SkipWithError("the elastic solve did not converge");
    iterations = solution.iterations;
    benchmark::DoNotOptimize(solution.tip.data());
  }
  state.counters["rods/s"] = benchmark::Counter(static_cast<double>(rods.size()), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["sweeps"] = iterations;
  state.counters["rod sweeps/s"] =
      benchmark::Counter(static_cast<double>(rods.size()) * iterations, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_ElasticRods)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ontogen::bench
