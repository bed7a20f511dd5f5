#pragma once
// A body plan (body_plan.h) as a MuJoCo model in MJCF, the XML MuJoCo's compiler reads:
// a body per plan body, nested as the plan's parents, placed so that at the hinges'
// kinematic angles every body stands where the plan's joint does; a free joint at each
// root, hinges with their ranges, a capsule per limb whose mass and inertia come from
// its size and the density; a position servo per hinge; a ground plane. ontogen is
// y-up, so gravity points along -y and the plane faces +y. Numbers are written with 17
// significant digits, so the text is the model exactly.

#include <string>
#include <string_view>

#include "interpreters/dynamics/body_plan.h"

namespace ontogen {

/// The physics of a model; validated by physicsError().
struct PhysicsDef {
  double timestep = 0.002;  ///< of the simulation, seconds, > 0
  double gravity = 9.81;    ///< model units per second squared, >= 0, along -y
  double ground = 0;        ///< the ground's height (world y), model units
  double density = 100;     ///< of the limbs, mass per cubic model unit, > 0
  double friction = 1;      ///< sliding, between the limbs and the ground, >= 0
  double kp = 5000;         ///< the servos' stiffness, torque per radian, >= 0 (0: no servos)
  double kd = 100;          ///< their damping, torque per radian a second, >= 0
  double torque = 4000;     ///< the most torque a servo gives, > 0 (infinity: no limit)
  bool rungeKutta = false;  ///< integrate with MuJoCo's RK4 instead of its semi-implicit Euler
};

/// Why def is no physics, or null when it is.
const char* physicsError(const PhysicsDef& def);

/// The names MuJoCo knows the parts by: body "b<index>", hinge "j<index>_<dof>", its
/// servo "s<index>_<dof>", the ground "ground".
std::string bodyName(int body);
std::string hingeName(int body, int dof);

/// The room MuJoCo sets aside for contacts and constraint rows, its `<size nconmax njmax>`.
/// MuJoCo 2.2 sizes each model's scratch memory by about 5 rows² doubles and clears it as
/// it makes the model's data, so room costs time even when unused: a simulation starts
/// with usualRoom() and grows the room when a step runs out of it (DynamicsSet).
struct MujocoRoom {
  int contacts = 0;
  int rows = 0;
};

/// Room for about one ground contact per limb (a walking body touches the ground with a
/// few of them) and a row for every hinge at its range's end: at least 16 contacts.
MujocoRoom usualRoom(const BodyPlan& plan);

/// The room twice over (each size doubled), for a step that ran out.
MujocoRoom doubled(MujocoRoom room);

/// The MJCF text of the plan under def, its model named `name`, with `room`.
std::string mjcfOf(const BodyPlan& plan, const PhysicsDef& def, std::string_view name, MujocoRoom room);

/// The MJCF text with room usualRoom(plan).
std::string mjcfOf(const BodyPlan& plan, const PhysicsDef& def, std::string_view name);

/// The most bodies MuJoCo 2.2 reads nested in one another: its XML reader (tinyxml2)
/// stops at 100 elements deep, and a body's geoms and joints sit inside it.
constexpr int kDeepestBodies = 96;

/// The most bodies of the plan nested in one another (a root alone: 1; none: 0).
int nestingDepth(const BodyPlan& plan);

/// The MJCF's `<size .../>` element for `room` (as mjcfOf writes it, one line).
std::string sizeElement(MujocoRoom room);

}  // namespace ontogen
