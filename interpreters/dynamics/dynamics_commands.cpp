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
};

}  // namespace

std::span<const DynamicsCommand> dynamicsCommands() { return kCommands; }

const DynamicsCommand* findDynamicsCommand(std::string_view name) {
  for (const DynamicsCommand& command : kCommands)
    if (command.name == name) return &command;
  return nullptr;
}

}  // namespace ontogen
