#include "interpreters/dynamics/mjcf_builder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

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

TEST(MjcfBuilder, AtTheKinematicAnglesEveryBodyStandsWhereItsJointDoes) {
  PlanBody root;
  root.id = 1;
  root.kind = JointKind::Free;
  root.position = {0.1, 0.8, 0.3};
  root.base = root.orientation = turned(JointKind::Hip, kLevel, {0.4, 0.1, -0.2});
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
  MujocoModel sim(mjcfOf(plan, PhysicsDef{}, "pose"));
  mjData* d = sim.data();
  d->qpos[7] = bendAngles[0];
  d->qpos[8] = bendAngles[1];
  d->qpos[9] = kneeAngles[0];
  mj_kinematics(sim.model(), d);
  for (int b = 0; b < 3; ++b) {
    const PlanBody& body = plan.bodies[static_cast<std::size_t>(b)];
    const int id = mj_name2id(sim.model(), mjOBJ_BODY, bodyName(b).c_str());
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(d->xpos[3 * id + k], body.position[k], 1e-12) << b;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(d->xmat[9 * id + 3 * k + c], body.orientation[c][k], 1e-12) << b;
    }
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
