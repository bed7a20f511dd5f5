#pragma once
// A body plan (body_plan.h) as a MuJoCo model in MJCF, the XML MuJoCo's compiler reads:
// a body per plan body, nested as the plan's parents, placed so that at the hinges'
// kinematic angles every body stands where the plan's joint does; a free joint at each
// root, hinges with their ranges, a capsule per limb whose mass and inertia come from
// its size and the density; a position servo per hinge; a ground plane. ontogen is
// y-up, so gravity points along -y and the plane faces +y. Numbers are written with 17
// significant digits, so the text is the model exactly.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

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
  /// The most iterations MuJoCo's constraint solver takes a step, a whole number 1..kMostSolverIterations
  /// (MuJoCo's default).
  int iterations = 100;
  /// The solver stops when the cost falls by less than this fraction, >= 0 and < 1 (0: always
  /// every iteration; MuJoCo's default).
  double tolerance = 1e-8;

  bool operator==(const PhysicsDef&) const = default;
};

/// The most solver iterations a step: far past what a contact needs to converge, and a
/// bound on a step's time.
constexpr int kMostSolverIterations = 1000;

/// Why def is no physics, or null when it is.
const char* physicsError(const PhysicsDef& def);

/// The names MuJoCo knows the parts by: body "b<index>", hinge "j<index>_<dof>" (the
/// hinges of plan body index, wherever they are written), its servo "s<index>_<dof>", a
/// free joint "free<index>" (of the body written at the centre), the ground "ground".
std::string bodyName(int body);
std::string hingeName(int body, int dof);
std::string freeName(int body);

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

/// The most room the plan's body can use at once: 4 contacts for each limb that touches
/// the ground (a cylinder on a plane; a capsule makes 2), 4 rows a contact (a pyramid of
/// condim 3) and a row for each hinge (its range's end). MuJoCo 2.2's scratch memory grows
/// as the rows squared, so the room never grows past this.
MujocoRoom mostRoom(const BodyPlan& plan);

/// About the bytes MuJoCo 2.2 sets aside for `room` as it makes a model's data: its
/// stack of 5 rows² + 60 rows doubles (measured on libmujoco 2.2.2), which dwarfs the rest.
uint64_t mujocoRoomBytes(MujocoRoom room);

/// The room twice over (each size doubled), for a step that ran out, but no more than
/// `most`.
MujocoRoom doubled(MujocoRoom room, MujocoRoom most);

/// How mjcfOf nests the plan's bodies. A free body's tree (a creature) hangs from the
/// body at its centre, the middle of its longest chain of bodies, which carries the free
/// joint: a chain of n bodies is then n/2 deep, not n, and MuJoCo's costs per step (its
/// mass matrix's factor, products and solves, each a sum over every degree of freedom of
/// those between it and the root) about halve. The bodies between the centre and the
/// plan's root hang the other way round: each from its child in the plan, turned by that
/// child's hinges taken backwards, so the hinges keep their angles, ranges, springs and
/// servos and the model is the same mechanism. Other trees (clamped rods, hinged chains)
/// hang as the plan has them.
struct Nesting {
  std::vector<int> parent;  ///< each body's parent as written; -1: the world
  /// The plan body whose hinges each body carries: itself; for a body hanging the other
  /// way round, the child it hangs from; -1 for a centre, whose plan parent carries them.
  std::vector<int> hinges;
  std::vector<bool> free;   ///< the body carries a free joint
};

/// The nesting of the plan as mjcfOf writes it; with `centred` false, as the plan has it
/// (every body from its plan parent, a free joint at each free body).
Nesting nestingOf(const BodyPlan& plan, bool centred = true);

/// The MJCF text of the plan under def, its model named `name`, with `room`.
std::string mjcfOf(const BodyPlan& plan, const PhysicsDef& def, std::string_view name, MujocoRoom room);

/// The MJCF text of the plan nested as `nesting` says (nestingOf's, centred or not).
std::string mjcfOf(const BodyPlan& plan, const PhysicsDef& def, std::string_view name, MujocoRoom room,
                   const Nesting& nesting);

/// The MJCF text with room usualRoom(plan).
std::string mjcfOf(const BodyPlan& plan, const PhysicsDef& def, std::string_view name);

/// The most bodies MuJoCo 2.2 reads nested in one another: its XML reader (tinyxml2)
/// stops at 100 elements deep, and a body's geoms and joints sit inside it.
constexpr int kDeepestBodies = 96;

/// The most bodies of the plan nested in one another as mjcfOf writes it (a root alone:
/// 1; none: 0).
int nestingDepth(const BodyPlan& plan);

/// The MJCF's `<size .../>` element for `room` (as mjcfOf writes it, one line).
std::string sizeElement(MujocoRoom room);

}  // namespace ontogen
