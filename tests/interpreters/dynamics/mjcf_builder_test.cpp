#include "interpreters/dynamics/mjcf_builder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "interpreters/dynamics/mujoco_model.h"

namespace ontogen {
namespace {

// The creature set's frame before any gait: H along x, L along -z, U along y.
const glm::dmat3 kLevel(glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0));

// One rod of length l and radius r from a joint at the origin along `along`.
BodyPlan rod(JointKind kind, double l, double r, const glm::dvec3& along) {
  PlanBody body;
  body.id = 7;
  body.kind = kind;
  body.base = body.orientation = kLevel;
  body.limbs.push_back({glm::dvec3(0.0), l * along, r});
  return {{body}};
}

TEST(MjcfBuilder, ABodyFallsFreelyAsGTSquaredOverTwo) {
  PhysicsDef def;
  def.ground = -100;  // no contact
  def.rungeKutta = true;
  def.timestep = 0.001;
  MujocoModel sim(mjcfOf(rod(JointKind::Free, 1, 0.1, {1, 0, 0}), def, "fall"));
  ASSERT_EQ(sim.model()->nq, 7);
  const double y0 = sim.data()->qpos[1];
  for (int n = 1; n <= 500; ++n) {
    sim.step();
    const double t = n * def.timestep;
    ASSERT_NEAR(sim.data()->qpos[1], y0 - def.gravity * t * t / 2, 1e-6) << t;
  }
}

// Times at which the angle crosses 0 going down, interpolated linearly.
std::vector<double> downCrossings(MujocoModel& sim, double seconds) {
  std::vector<double> times;
  const double h = sim.model()->opt.timestep;
  double before = sim.data()->qpos[0];
  for (int n = 1; n * h <= seconds; ++n) {
    sim.step();
    const double now = sim.data()->qpos[0];
    if (before > 0 && now <= 0) times.push_back((n - 1) * h + h * before / (before - now));
    before = now;
  }
  return times;
}

TEST(MjcfBuilder, ARodSwingsWithTheCompoundPendulumsPeriod) {
  PhysicsDef def;
  def.ground = -100;
  def.rungeKutta = true;
  def.timestep = 0.001;
  def.kp = 0;
  def.kd = 0;
  const double l = 1, r = 0.002;
  MujocoModel sim(mjcfOf(rod(JointKind::Hinge, l, r, {0, -1, 0}), def, "pendulum"));
  ASSERT_EQ(sim.model()->nq, 1);
  ASSERT_EQ(sim.model()->nu, 0);
  sim.data()->qpos[0] = 0.02;  // small: the period's amplitude term is 1 + 0.02^2 / 16
  const std::vector<double> crossings = downCrossings(sim, 10);
  ASSERT_GE(crossings.size(), 5u);
  const double period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  // A uniform rod about its end: I = m l^2 / 3, its centre l / 2 below.
  const double expected = 2 * std::numbers::pi * std::sqrt(2 * l / (3 * def.gravity));
  EXPECT_NEAR(period / expected, 1, 0.005);
}

TEST(MjcfBuilder, AServoAtItsRangesEndHoldsItThere) {
  PhysicsDef def;
  def.ground = -100;
  BodyPlan plan = rod(JointKind::Hinge, 1, 0.05, {1, 0, 0});
  plan.bodies[0].ranges[0] = {true, -0.3, 0.3};
  MujocoModel sim(mjcfOf(plan, def, "held"));
  ASSERT_EQ(sim.model()->nu, 1);
  sim.data()->ctrl[0] = -0.3;  // gravity pulls the horizontal rod further down
  double lowest = 0;
  for (int n = 0; n < 2000; ++n) {
    sim.step();
    lowest = std::min(lowest, sim.data()->qpos[0]);
  }
  EXPECT_GE(lowest, -0.3 - std::numbers::pi / 180);
  EXPECT_NEAR(sim.data()->qpos[0], -0.3, std::numbers::pi / 180);
}

TEST(MjcfBuilder, ABodyAtRestOnTheGroundStaysWithinAMillimetre) {
  PhysicsDef def;
  BodyPlan plan = rod(JointKind::Free, 1, 0.1, {1, 0, 0});
  plan.bodies[0].position = plan.bodies[0].limbs[0].start = {0, 0.1, 0};
  plan.bodies[0].limbs[0].end = {1, 0.1, 0};
  MujocoModel sim(mjcfOf(plan, def, "rest"));
  const double x0 = sim.data()->qpos[0], y0 = sim.data()->qpos[1], z0 = sim.data()->qpos[2];
  for (int n = 0; n < 5000; ++n) sim.step();  // 10 s
  EXPECT_NEAR(sim.data()->qpos[0], x0, 1e-3);
  EXPECT_NEAR(sim.data()->qpos[1], y0, 1e-3);
  EXPECT_NEAR(sim.data()->qpos[2], z0, 1e-3);
}

// The text on disk, through MuJoCo's own loader, is the model: both step to the same bits.
TEST(MjcfBuilder, TheWrittenModelLoadsInMujocoAndStepsTheSame) {
  PhysicsDef def;
  PlanBody root;
  root.id = 1;
  root.kind = JointKind::Free;
  root.position = {0, 0.8, 0};
  root.base = root.orientation = kLevel;
  root.limbs.push_back({{-0.5, 0.8, 0}, {0.5, 0.8, 0}, 0.2});
  PlanBody leg;
  leg.id = 2;
  leg.parent = 0;
  leg.kind = JointKind::Hip;
  leg.position = {0.3, 0.8, -0.2};
  leg.base = kLevel;
  leg.orientation = turned(JointKind::Hip, kLevel, {0.2, -1.2, 0.1});
  leg.ranges[1] = {true, -1.5, 0.5};
  leg.limbs.push_back({leg.position, leg.position + 0.9 * leg.orientation[0], 0.08});
  const BodyPlan plan{{root, leg}};
  const std::string text = mjcfOf(plan, def, "walker & co");
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "ontogen_dynamics_test_model.xml";
  std::ofstream(path) << text;
  char error[1000] = "";
  mjModel* loaded = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
  std::filesystem::remove(path);
  ASSERT_NE(loaded, nullptr) << error;
  mjData* data = mj_makeData(loaded);
  MujocoModel sim(text);
  ASSERT_EQ(loaded->nq, sim.model()->nq);
  ASSERT_EQ(loaded->nu, 3);
  for (int n = 0; n < 400; ++n) {
    for (int u = 0; u < 3; ++u) data->ctrl[u] = sim.data()->ctrl[u] = 0.1 * u;
    mj_step(loaded, data);
    sim.step();
  }
  for (int i = 0; i < loaded->nq; ++i) EXPECT_EQ(data->qpos[i], sim.data()->qpos[i]) << i;
  EXPECT_LT(sim.data()->qpos[1], 0.8);  // it fell and the leg pushed: it moved
  mj_deleteData(data);
  mj_deleteModel(loaded);
}

// Sets each hinge of the plan at `angles` (per plan body), by its name.
void setAngles(MujocoModel& sim, const BodyPlan& plan, const std::vector<std::array<double, 3>>& angles) {
  for (std::size_t b = 0; b < plan.bodies.size(); ++b)
    for (int dof = 0; dof < hingeCount(plan.bodies[b].kind); ++dof) {
      const int joint = mj_name2id(sim.model(), mjOBJ_JOINT, hingeName(static_cast<int>(b), dof).c_str());
      ASSERT_GE(joint, 0) << b << " " << dof;
      sim.data()->qpos[sim.model()->jnt_qposadr[joint]] = angles[b][static_cast<std::size_t>(dof)];
    }
}

// Whether the plan's bodies stand where the simulation has them (by name), within `tolerance`.
void expectBodiesWhereThePlanHasThem(MujocoModel& sim, const BodyPlan& plan, double tolerance) {
  const mjData* d = sim.data();
  for (std::size_t b = 0; b < plan.bodies.size(); ++b) {
    const PlanBody& body = plan.bodies[b];
    const int id = mj_name2id(sim.model(), mjOBJ_BODY, bodyName(static_cast<int>(b)).c_str());
    ASSERT_GE(id, 0);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(d->xpos[3 * id + k], body.position[k], tolerance) << b;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(d->xmat[9 * id + 3 * k + c], body.orientation[c][k], tolerance) << b;
    }
  }
}

// A free root, a bend behind it and a knee on the bend: the bend is the centre, the root
// hangs from it the other way round. Written either way, at the kinematic angles every
// body stands where its joint does, turned as the plan has it.
TEST(MjcfBuilder, AtTheKinematicAnglesEveryBodyStandsWhereItsJointDoes) {
  PlanBody root;
  root.id = 1;
  root.kind = JointKind::Free;
  root.position = {0.1, 0.8, 0.3};
  root.base = root.orientation = turned(JointKind::Hip, kLevel, {0.4, 0.1, -0.2});
  root.limbs.push_back({root.position, root.position + 0.3 * root.orientation[0], 0.1});
  PlanBody bend;
  bend.id = 2;
  bend.parent = 0;
  bend.kind = JointKind::Bend;
  bend.position = root.position - 0.5 * root.orientation[0];
  bend.base = root.orientation * glm::dmat3(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1));
  const std::array<double, 3> bendAngles{0.2, -0.05, 0};
  bend.orientation = turned(JointKind::Bend, bend.base, bendAngles);
  PlanBody knee;
  knee.id = 3;
  knee.parent = 1;
  knee.kind = JointKind::Knee;
  knee.position = bend.position + 0.7 * bend.orientation[0];
  knee.base = bend.orientation;
  const std::array<double, 3> kneeAngles{0.9, 0, 0};
  knee.orientation = turned(JointKind::Knee, knee.base, kneeAngles);
  const BodyPlan plan{{root, bend, knee}};
  for (const bool centred : {false, true}) {
    const Nesting nesting = nestingOf(plan, centred);
    EXPECT_EQ(nesting.parent, (centred ? std::vector<int>{1, -1, 1} : std::vector<int>{-1, 0, 1})) << centred;
    EXPECT_EQ(nesting.hinges, (centred ? std::vector<int>{1, -1, 2} : std::vector<int>{0, 1, 2})) << centred;
    MujocoModel sim(mjcfOf(plan, PhysicsDef{}, "pose", usualRoom(plan), nesting));
    setAngles(sim, plan, {{}, bendAngles, kneeAngles});
    mj_kinematics(sim.model(), sim.data());
    expectBodiesWhereThePlanHasThem(sim, plan, 1e-12);
  }
}

// A creature of `segments` bends in a chain behind a free head, each bend with a leg: a
// 3-DOF hip, a knee, a welded foot. Angles of every hinge in `angles`.
BodyPlan centipede(int segments, std::vector<std::array<double, 3>>& angles) {
  BodyPlan plan;
  auto add = [&](int parent, JointKind kind, const glm::dvec3& offset, const glm::dmat3& turn,
                 const std::array<double, 3>& turns) {
    PlanBody body;
    body.id = static_cast<uint64_t>(100 + plan.bodies.size());
    body.parent = parent;
    body.kind = kind;
    const PlanBody* holder = parent >= 0 ? &plan.bodies[static_cast<std::size_t>(parent)] : nullptr;
    body.position = holder ? holder->position + holder->orientation * offset : offset;
    body.base = holder ? holder->orientation * turn : turn;
    body.orientation = turned(kind, body.base, turns);
    body.limbs.push_back({body.position, body.position + 0.4 * body.orientation[0], 0.06});
    if (kind == JointKind::Weld) body.limbs.clear();
    plan.bodies.push_back(body);
    angles.push_back(turns);
    return static_cast<int>(plan.bodies.size()) - 1;
  };
  const glm::dmat3 back(glm::dvec3(-1, 0, 0), glm::dvec3(0, -1, 0), glm::dvec3(0, 0, 1));
  int at = add(-1, JointKind::Free, {0, 2, 0}, kLevel, {});
  for (int s = 0; s < segments; ++s) {
    at = add(at, JointKind::Bend, s == 0 ? glm::dvec3(-0.1, 0, 0) : glm::dvec3(0.4, 0, 0), s == 0 ? back : glm::dmat3(1.0),
             {0.05 * (s % 3) - 0.05, 0.02 * (s % 2), 0});
    const int hip = add(at, JointKind::Hip, {0.2, 0, 0}, glm::dmat3(glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0), glm::dvec3(-1, 0, 0)),
                        {0.1 * s - 0.3, -0.4, 0.05});
    const int knee = add(hip, JointKind::Knee, {0.4, 0, 0}, glm::dmat3(1.0), {0.8 + 0.01 * s, 0, 0});
    add(knee, JointKind::Weld, {0.4, 0, 0}, glm::dmat3(1.0), {});
  }
  for (PlanBody& body : plan.bodies) body.ranges[0] = {true, -1.5, 1.5};
  return plan;
}

// The 12-segment centipede hangs from its sixth bend, the middle of its longest chain (a
// foot of the first segment to one of the last): 10 bodies deep instead of its plain 16
// (head, 12 bends, hip, knee, foot), its mass matrix's fill down by a third (the legs'
// own depth stays). At the kinematic angles every body stands where the plan has it.
// Out of contact, its soft servos driving every hinge 0.1 from where it starts, it moves
// as the same mechanism hanging from its head: the two differ only by the integrator's
// error, which falls as RK4's (by about 2^4 when the step halves; below 1e-5 after 0.5 s
// at 0.5 ms). The walking creatures' stiff servos make the motion chaotic, so there the
// two part by as much as any change in rounding makes them.
TEST(MjcfBuilder, ACreatureHangsFromItsCentreAndMovesAsFromItsHead) {
  std::vector<std::array<double, 3>> angles;
  const BodyPlan plan = centipede(12, angles);
  const Nesting centred = nestingOf(plan), plain = nestingOf(plan, false);
  EXPECT_EQ(nestingDepth(plan), 10);
  std::vector<bool> head(plan.bodies.size(), false), sixth(plan.bodies.size(), false);
  head[0] = true;
  sixth[1 + 5 * 4] = true;  // after the head, four bodies a segment
  EXPECT_EQ(plain.free, head);
  EXPECT_EQ(centred.free, sixth);
  PhysicsDef def;
  def.ground = -100;
  def.rungeKutta = true;
  def.kp = 20;
  def.kd = 1;
  // The largest difference between the bodies' places and frames after 0.5 s at `step`.
  auto apart = [&](double step) {
    def.timestep = step;
    MujocoModel one(mjcfOf(plan, def, "head", usualRoom(plan), plain));
    MujocoModel other(mjcfOf(plan, def, "centre", usualRoom(plan), centred));
    if (step == 0.001) {
      std::cout << "mass matrix entries: " << one.model()->nM << " from the head, " << other.model()->nM
                << " from the centre\n";
      EXPECT_LT(other.model()->nM, 0.7 * one.model()->nM);
    }
    for (MujocoModel* sim : {&one, &other}) {
      EXPECT_EQ(sim->model()->nv, 6 + 12 * 6);
      EXPECT_EQ(sim->model()->nu, 12 * 6);
      setAngles(*sim, plan, angles);
      mj_kinematics(sim->model(), sim->data());
      expectBodiesWhereThePlanHasThem(*sim, plan, 1e-12);
      for (std::size_t b = 0; b < plan.bodies.size(); ++b)
        for (int dof = 0; dof < hingeCount(plan.bodies[b].kind); ++dof) {
          const std::string name = "s" + std::to_string(b) + "_" + std::to_string(dof);
          const int servo = mj_name2id(sim->model(), mjOBJ_ACTUATOR, name.c_str());
          EXPECT_GE(servo, 0) << name;
          if (servo >= 0) sim->data()->ctrl[servo] = angles[b][static_cast<std::size_t>(dof)] + 0.1;
        }
      for (long n = 0; n < std::lround(0.5 / step); ++n) sim->step();
      mj_kinematics(sim->model(), sim->data());
    }
    double most = 0, moved = 0;
    for (std::size_t b = 0; b < plan.bodies.size(); ++b) {
      const int a = mj_name2id(one.model(), mjOBJ_BODY, bodyName(static_cast<int>(b)).c_str());
      const int c = mj_name2id(other.model(), mjOBJ_BODY, bodyName(static_cast<int>(b)).c_str());
      for (int k = 0; k < 3; ++k) {
        most = std::max(most, std::abs(one.data()->xpos[3 * a + k] - other.data()->xpos[3 * c + k]));
        moved = std::max(moved, std::abs(one.data()->xpos[3 * a + k] - plan.bodies[b].position[k]));
        for (int e = 0; e < 3; ++e)
          most = std::max(most, std::abs(one.data()->xmat[9 * a + 3 * k + e] - other.data()->xmat[9 * c + 3 * k + e]));
      }
    }
    EXPECT_GT(moved, 1);  // it fell
    return most;
  };
  const double coarse = apart(0.001), fine = apart(0.0005);
  std::cout << "apart after 0.5 s: " << coarse << " at 1 ms, " << fine << " at 0.5 ms\n";
  EXPECT_LT(fine, 1e-5);
  EXPECT_LT(fine, coarse / 10);
}

// A cantilever as the elastic design model cuts it (interpreters/physics/elastic_rods.h):
// n segments of length h, each joined at its midpoint by springs of EI / h; the half
// segment at the clamp is fixed, the rest are n bodies, the last half a segment long.
BodyPlan cantilever(int n, double length, double radius, double density, double stiffness) {
  const double h = length / n;
  BodyPlan plan;
  PlanBody clamp;
  clamp.id = 1;
  clamp.kind = JointKind::Weld;
  clamp.base = clamp.orientation = kLevel;
  clamp.limbs.push_back({{0, 0, 0}, {h / 2, 0, 0}, radius, density, true, false});
  plan.bodies.push_back(clamp);
  for (int i = 0; i < n; ++i) {
    PlanBody body;
    body.id = static_cast<uint64_t>(2 + i);
    body.parent = i;
    body.kind = JointKind::Bend;
    body.position = {h / 2 + i * h, 0, 0};
    body.base = body.orientation = kLevel;
    body.limbs.push_back({body.position, {std::min(body.position.x + h, length), 0, 0}, radius, density, true, false});
    body.spring = stiffness / h;
    body.damping = 0;
    body.driven = false;
    plan.bodies.push_back(body);
  }
  return plan;
}

// The first natural frequency of the same chain in the plane, small angles: links of
// lengths l_i (uniform cylinders of mass rho A l_i, radius r) at absolute angles phi_i,
// a spring k before each. The kinetic energy gives the mass matrix, the springs on the
// angles' differences the stiffness; the least generalized eigenvalue is omega^2.
double chainFrequency(const std::vector<double>& lengths, double k, double rhoA, double r) {
  const auto n = static_cast<Eigen::Index>(lengths.size());
  Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(n, n), stiff = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double l = lengths[static_cast<std::size_t>(i)], m = rhoA * l;
    Eigen::VectorXd centre = Eigen::VectorXd::Zero(n);  // its centre's speed per angle's speed
    for (Eigen::Index j = 0; j < i; ++j) centre[j] = lengths[static_cast<std::size_t>(j)];
    centre[i] = l / 2;
    mass += m * centre * centre.transpose();
    mass(i, i) += m * (3 * r * r + l * l) / 12;
    Eigen::VectorXd turn = Eigen::VectorXd::Zero(n);
    turn[i] = 1;
    if (i > 0) turn[i - 1] = -1;
    stiff += k * turn * turn.transpose();
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(stiff, mass);
  return std::sqrt(solver.eigenvalues().minCoeff()) / (2 * std::numbers::pi);
}

// Released from the shape a tip load bends it into (1 % of its length at the tip),
// weightless and undamped, a cantilever of 10 segments swings at its first natural
// frequency: 1.875^2 sqrt(EI / (rho A L^4)) / (2 pi) of the continuous rod within 3 %
// (the bound; the chain of 10 is 0.23 % above it), and the discrete chain's own
// eigenvalue within 0.3 % (what is left is the zero crossings' reading of the higher
// modes the release shape also holds, averaged over nine cycles, and RK4's error at
// 0.5 ms, 1/2000 of a period).
TEST(MjcfBuilder, ACantileverSwingsAtItsFirstNaturalFrequency) {
  constexpr int n = 10;
  constexpr double length = 1, radius = 0.01, density = 1000, stiffness = 1;  // f1 = 1.0 Hz
  PhysicsDef def;
  def.gravity = 0;
  def.ground = -100;
  def.rungeKutta = true;
  def.timestep = 0.0005;
  const BodyPlan plan = cantilever(n, length, radius, density, stiffness);
  MujocoModel sim(mjcfOf(plan, def, "cantilever"));
  const mjModel* m = sim.model();
  mjData* d = sim.data();
  ASSERT_EQ(m->nq, 2 * n);
  ASSERT_EQ(m->nu, 0);
  const double h = length / n;
  // A tip load P turns the spring at x by P (L - x) h / EI; scaled to a tip of 0.01 L.
  double tip = 0;
  for (int i = 0; i < n; ++i) {
    const double x = h / 2 + i * h;
    tip += (length - x) * (length - x) * h / stiffness;
  }
  for (int i = 0; i < n; ++i) {
    const double x = h / 2 + i * h;
    const int pitch = mj_name2id(m, mjOBJ_JOINT, hingeName(i + 1, 1).c_str());
    d->qpos[m->jnt_qposadr[pitch]] = 0.01 * length * (length - x) * h / stiffness / tip;
  }
  mj_forward(m, d);
  const int last = mj_name2id(m, mjOBJ_BODY, bodyName(n).c_str());
  auto tipHeight = [&] { return d->xpos[3 * last + 1] + d->xmat[9 * last + 3] * h / 2; };
  EXPECT_NEAR(tipHeight(), 0.01 * length, 1e-5);
  std::vector<double> crossings;
  double before = tipHeight();
  for (int step = 1; step * def.timestep <= 10; ++step) {
    sim.step();
    const double now = tipHeight();
    if (before > 0 && now <= 0) crossings.push_back((step - 1 + before / (before - now)) * def.timestep);
    before = now;
  }
  ASSERT_GE(crossings.size(), 9u);
  const double frequency = static_cast<double>(crossings.size() - 1) / (crossings.back() - crossings.front());
  const double area = std::numbers::pi * radius * radius;
  const double continuous =
      1.875104068711961 * 1.875104068711961 / (2 * std::numbers::pi) * std::sqrt(stiffness / (density * area)) / (length * length);
  std::vector<double> lengths(n, h);
  lengths.back() = h / 2;
  const double chain = chainFrequency(lengths, stiffness / h, density * area, radius);
  std::cout << "cantilever: " << frequency << " Hz; continuous rod " << continuous << ", chain " << chain << "\n";
  EXPECT_NEAR(frequency / continuous, 1, 0.03);
  EXPECT_NEAR(frequency / chain, 1, 0.003);
}

// Chains of `hinges` bodies each, each body turning about one hinge on the one before,
// the first on the world.
BodyPlan chains(int count, int hinges) {
  BodyPlan plan;
  for (int c = 0; c < count; ++c)
    for (int i = 0; i < hinges; ++i) {
      PlanBody body;
      body.id = static_cast<uint64_t>(plan.bodies.size() + 1);
      body.parent = i == 0 ? -1 : static_cast<int>(plan.bodies.size()) - 1;
      body.kind = JointKind::Hinge;
      body.position = {0.1 * i, 1, 0.5 * c};
      body.base = body.orientation = kLevel;
      body.limbs.push_back({body.position, body.position + glm::dvec3(0.1, 0, 0), 0.01});
      plan.bodies.push_back(std::move(body));
    }
  return plan;
}

// Small and past 100 degrees of freedom, a model asks for MuJoCo's Newton solver, which
// factors its Hessian sparsely on a sparse model (mjcfOf says why).
TEST(MjcfBuilder, ModelsOfEverySizeUseNewtonsSolver) {
  MujocoModel small(mjcfOf(chains(1, 5), {}, "chains"));
  EXPECT_EQ(small.model()->opt.solver, mjSOL_NEWTON);
  MujocoModel more(mjcfOf(chains(3, 34), {}, "chains"));
  ASSERT_EQ(more.model()->nv, 102);
  EXPECT_EQ(more.model()->opt.solver, mjSOL_NEWTON);
}

// kDeepestBodies is MuJoCo's own bound: a chain that deep compiles, one body more does not.
TEST(MjcfBuilder, TheDeepestNestingIsWhatMujocosReaderTakes) {
  EXPECT_EQ(nestingDepth(chains(3, kDeepestBodies)), kDeepestBodies);
  EXPECT_EQ(nestingDepth({}), 0);
  MujocoModel deepest(mjcfOf(chains(1, kDeepestBodies), {}, "chain"));
  EXPECT_EQ(deepest.model()->nbody, kDeepestBodies + 1);
  EXPECT_THROW(MujocoModel(mjcfOf(chains(1, kDeepestBodies + 1), {}, "chain")), MujocoError);
}

// The room's bytes as MuJoCo sets them aside: its stack (nstack doubles) of a compiled
// model with that room, within 1 %.
TEST(MjcfBuilder, TheRoomsBytesAreMujocosStack) {
  for (const int rows : {100, 1000, 4000}) {
    const MujocoRoom room{rows / 4, rows};
    const std::string xml = "<mujoco>" + sizeElement(room) +
                            "<worldbody><body><freejoint/><geom size=\"0.1\"/></body></worldbody></mujoco>";
    MujocoModel sim(xml);
    const double stack = static_cast<double>(sizeof(mjtNum)) * static_cast<double>(sim.model()->nstack);
    EXPECT_NEAR(static_cast<double>(mujocoRoomBytes(room)), stack, 0.01 * stack) << rows;
  }
}

TEST(MjcfBuilder, BadPhysicsIsNamed) {
  PhysicsDef def;
  EXPECT_EQ(physicsError(def), nullptr);
  def.timestep = 0;
  EXPECT_NE(physicsError(def), nullptr);
  def = {};
  def.density = std::nan("");
  EXPECT_NE(physicsError(def), nullptr);
  EXPECT_THROW(MujocoModel("<mujoco><worldbody><geom type=\"nothing\"/></worldbody></mujoco>"), MujocoError);
}

}  // namespace
}  // namespace ontogen
