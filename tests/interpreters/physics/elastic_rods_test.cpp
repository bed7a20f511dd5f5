// The elastic design model by value: a cantilever's tip sinks by P L^3 / (3 EI) under a
// small tip load and by w L^4 / (8 EI) under its own weight, and under large loads it
// follows the elastica, computed here by a shooting method; rods without stiffness stay
// rigid; the discretisation converges as the rods are cut finer.

#include "interpreters/physics/elastic_rods.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "tests/interpreters/physics/physics_support.h"

namespace ontogen {
namespace {

using testing_support::solveModel;
using testing_support::solveText;

// The tip of a cantilever of length L clamped horizontally, under a dead vertical tip
// load P: theta(s) the slope below the horizontal, EI theta'' = -P cos(theta),
// theta(0) = 0, theta'(L) = 0. Shooting on theta'(0) by bisection, RK4 in s.
struct ElasticaTip {
  double drop = 0;       // downward deflection of the tip
  double shortening = 0;  // L minus the tip's horizontal distance from the clamp
};

ElasticaTip elasticaTip(double L, double P, double EI) {
  const double k = P / EI;
  const int steps = 4000;
  const double h = L / steps;
  auto shoot = [&](double slope, ElasticaTip* tip) {
    double theta = 0, omega = slope, x = 0, y = 0;
    auto f = [k](double th) { return -k * std::cos(th); };
    for (int i = 0; i < steps; ++i) {
      // theta' = omega, omega' = f(theta), x' = cos(theta), y' = sin(theta)
      const double t1 = omega, o1 = f(theta), x1 = std::cos(theta), y1 = std::sin(theta);
      const double th2 = theta + 0.5 * h * t1, t2 = omega + 0.5 * h * o1, o2 = f(th2);
      const double x2 = std::cos(th2), y2 = std::sin(th2);
      const double th3 = theta + 0.5 * h * t2, t3 = omega + 0.5 * h * o2, o3 = f(th3);
      const double x3 = std::cos(th3), y3 = std::sin(th3);
      const double th4 = theta + h * t3, t4 = omega + h * o3, o4 = f(th4);
      const double x4 = std::cos(th4), y4 = std::sin(th4);
      theta += h / 6 * (t1 + 2 * t2 + 2 * t3 + t4);
      omega += h / 6 * (o1 + 2 * o2 + 2 * o3 + o4);
      x += h / 6 * (x1 + 2 * x2 + 2 * x3 + x4);
      y += h / 6 * (y1 + 2 * y2 + 2 * y3 + y4);
    }
    if (tip) *tip = {y, L - x};
    return omega;  // theta'(L): zero at the solution
  };
  double lo = 0, hi = k * L;  // theta'(0) = P x_tip / EI lies between
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (shoot(mid, nullptr) < 0 ? lo : hi) = mid;
  }
  ElasticaTip tip;
  shoot(0.5 * (lo + hi), &tip);
  return tip;
}

// The cantilever model's tip, as the physics set solves it.
struct Tip {
  double drop = 0, shortening = 0;
  bool converged = false;
  int iterations = 0;
};

Tip cantileverTip(double L, double P, double EI, int rods = 10) {
  const auto solved = solveModel("cantilever.cell", {{"L", L}, {"P", P}, {"EI", EI}, {"RODS", rods}});
  const PhysicsFrame& frame = solved.frame();
  EXPECT_TRUE(frame.elastic);
  if (frame.rods.empty()) return {};
  const RodResult& last = frame.rods.back();
  return {last.restTip.y() - last.tip.y(), last.restTip.x() - last.tip.x(), frame.converged, frame.iterations};
}

TEST(ElasticRods, ACantileversTipSinksByPL3Over3EIUnderASmallLoad) {
  for (double L : {1.0, 2.5}) {
    for (int rods : {5, 10}) {  // 20 and 40 segments: within 0.1 %
      const double P = 0.01, EI = 1000;
      const Tip tip = cantileverTip(L, P, EI, rods);
      const double expected = P * L * L * L / (3 * EI);
      EXPECT_TRUE(tip.converged);
      EXPECT_NEAR(tip.drop, expected, 0.01 * expected) << "L " << L << ", " << rods << " rods";
    }
  }
}

TEST(ElasticRods, ACantileversTipSinksByWL4Over8EIUnderItsOwnWeight) {
  // Horizontal, 20 rods of density RHO, radius R; weight per length w = RHO pi R^2 g.
  const std::string text =
      "#define RHO 7800\n#define R 0.01\n#define EI 2000\n"
      "lsystem a { axiom -(90) stiffness(EI) elastic(4) B(20)\n"
      "  B(n) : n > 0 -> rod(0.1, R, RHO) B(n - 1) }\n";
  const auto solved = solveText(text, 20);
  const PhysicsFrame& frame = solved.frame();
  ASSERT_EQ(frame.rods.size(), 20u);
  const double w = 7800 * std::numbers::pi * 0.01 * 0.01 * kGravity, L = 2, EI = 2000;
  const double expected = w * std::pow(L, 4) / (8 * EI);
  const RodResult& last = frame.rods.back();
  EXPECT_NEAR(last.restTip.y() - last.tip.y(), expected, 0.01 * expected);
  EXPECT_NEAR(last.tip.z(), 0, 1e-12) << "it stays in its plane";
}

TEST(ElasticRods, LargeDeflectionsFollowTheElastica) {
  const double L = 1, EI = 1000;
  for (double load : {0.5, 2.0, 5.0}) {  // P L^2 / EI
    const double P = load * EI / (L * L);
    const ElasticaTip reference = elasticaTip(L, P, EI);
    const Tip tip = cantileverTip(L, P, EI);
    EXPECT_TRUE(tip.converged) << load;
    EXPECT_NEAR(tip.drop, reference.drop, 0.01 * reference.drop) << "PL^2/EI = " << load;
    EXPECT_NEAR(tip.shortening, reference.shortening, 0.01 * reference.shortening) << "PL^2/EI = " << load;
    // Far from the small-slope formula: the large deflection is the exact one.
    if (load >= 2) {
      EXPECT_LT(tip.drop, 0.8 * P * L * L * L / (3 * EI));
    }
  }
}

TEST(ElasticRods, TheDeflectionConvergesAsTheRodsAreCutFiner) {
  const double P = 0.01, EI = 1000, expected = P / (3 * EI);
  double previous = INFINITY;
  for (int rods : {1, 2, 4, 8}) {
    const double error = std::abs(cantileverTip(1, P, EI, rods).drop - expected);
    EXPECT_LT(error, previous) << rods;
    previous = error;
  }
}

TEST(ElasticRods, RodsWithoutStiffnessStayRigid) {
  const auto solved = solveText("lsystem a { axiom elastic(4) rod(1, 0.1, 50) +(60) rod(1, 0.1, 50) }\n", 0);
  const PhysicsFrame& frame = solved.frame();
  ASSERT_EQ(frame.rods.size(), 2u);
  for (const RodResult& rod : frame.rods) EXPECT_LT((rod.tip - rod.restTip).norm(), 1e-12);
  EXPECT_NEAR(frame.rods[0].moment.norm(), solveText("lsystem a { axiom rod(1, 0.1, 50) +(60) rod(1, 0.1, 50) }\n", 0)
                                               .frame()
                                               .rods[0]
                                               .moment.norm(),
              1e-9);
}

TEST(ElasticRods, ABranchedTreeSagsAndKeepsItsLoads) {
  const auto solved = solveText(
      "lsystem a { axiom young(2e8) elastic(8) rod(1, 0.05, 500) [ +(45) rod(0.8, 0.04, 500) ] "
      "[ -(60) load(0, 0, 2, 0.5) rod(0.8, 0.04, 500) ] }\n",
      0);
  const PhysicsFrame& frame = solved.frame();
  ASSERT_EQ(frame.rods.size(), 3u);
  EXPECT_TRUE(frame.converged);
  double mass = 0;
  for (const RodResult& rod : frame.rods) mass += rod.mass;
  EXPECT_LT((frame.rods[0].force - (-kGravity * mass * kWorldUp + Eigen::Vector3d(0, 0, 2))).norm(), 1e-9)
      << "dead loads: the root carries them whatever the shape";
  for (size_t i = 1; i < 3; ++i) {
    EXPECT_LT(frame.rods[i].tip.y(), frame.rods[i].restTip.y()) << "a branch sags";
    EXPECT_NEAR((frame.rods[i].tip - frame.rods[i].base).norm(), frame.rods[i].length, 1e-3 * frame.rods[i].length)
        << "inextensible, to the chord of a bent rod";
  }
  EXPECT_GT(frame.rods[2].tip.z(), 1e-6) << "the load along z pushes the branch out of its plane";
}

}  // namespace
}  // namespace ontogen
