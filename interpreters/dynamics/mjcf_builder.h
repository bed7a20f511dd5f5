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

/// The MJCF text of the plan under def, its model named `name`.
std::string mjcfOf(const BodyPlan& plan, const PhysicsDef& def, std::string_view name);

}  // namespace ontogen
