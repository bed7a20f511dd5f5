#include "interpreters/dynamics/dynamics_commands.h"

#include <array>

namespace ontogen {

namespace {

constexpr std::array kCommands = {
    DynamicsCommand{"density", DynamicsOp::Density, 1, 1, "density(rho)",
                    "the density of every limb, mass per cubic model unit (> 0; default 100): a limb's mass and "
                    "inertia are a capsule's of its length and mean radius"},
    DynamicsCommand{"servo", DynamicsOp::Servo, 2, 3, "servo(kp, kd[, torque])",
                    "every joint's position servo: kp torque per radian away from the kinematic pose (>= 0; "
                    "default 5000), kd torque per radian a second of the joint's speed (>= 0; default 100), at most "
                    "torque (> 0; default 4000)"},
    DynamicsCommand{"friction", DynamicsOp::Friction, 1, 1, "friction(mu)",
                    "the sliding friction between the limbs and the ground (>= 0; default 1)"},
    DynamicsCommand{"gravity", DynamicsOp::Gravity, 1, 1, "gravity(g)",
                    "gravity along -y, model units per second squared (>= 0; default 9.81)"},
    DynamicsCommand{"rod", DynamicsOp::Rod, 2, 3, "rod(l, r[, rho])",
                    "an elastic rod l long along H from the turtle, radius r, density rho (default: density's), "
                    "hanging from the rod before it on its path (none: fixed at its base); the turtle moves to its "
                    "tip. It bends in elastic's segments joined by springs of stiffness / segment length"},
    DynamicsCommand{"stiffness", DynamicsOp::Stiffness, 1, 1, "stiffness(EI)",
                    "the bending stiffness of the rods that follow on this path, EI (> 0; 0: rigid, the default; "
                    "pushed with [)"},
    DynamicsCommand{"elastic", DynamicsOp::Elastic, 1, 1, "elastic(n)",
                    "the rods that follow on this path bend in n segments (1..64; default 4; pushed with [)"},
    DynamicsCommand{"damping", DynamicsOp::Damping, 1, 1, "damping(beta)",
                    "each rod spring's damping is its stiffness times beta seconds (>= 0; default 0.01)"},
    DynamicsCommand{"wind", DynamicsOp::Wind, 3, 5, "wind(x, y, z[, gust, period])",
                    "the air moves at (x, y, z) units a second, its speed varying by the fraction gust as "
                    "sin(2 pi t / period) (default 0, 4 s): each rod segment feels the drag 1/2 rho_air Cd 2r h "
                    "|v| v of the air's speed v across it relative to its own (rho_air 1.2, Cd 1.2)"},
    DynamicsCommand{"control", DynamicsOp::Control, 1, 1, "control(period)",
                    "the servos' targets are the kinematic pose taken every period seconds of simulated time, "
                    "on a grid from time 0, and followed linearly between (0 to 1; default 0.01; 0: at every step)"},
    DynamicsCommand{"solver", DynamicsOp::Solver, 1, 2, "solver(iterations[, tolerance])",
                    "MuJoCo's constraint solver (contacts, ranges) takes at most iterations a step (a whole number "
                    "1..1000; default 100), stopping early when an iteration improves its cost by less than the "
                    "fraction tolerance (>= 0, below 1; default 1e-8; 0: every iteration)"},
};

}  // namespace

std::span<const DynamicsCommand> dynamicsCommands() { return kCommands; }

const DynamicsCommand* findDynamicsCommand(std::string_view name) {
  for (const DynamicsCommand& command : kCommands)
    if (command.name == name) return &command;
  return nullptr;
}

}  // namespace ontogen
