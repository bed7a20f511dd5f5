#pragma once
// The table of the "dynamics" set's own commands: the physical constants of the body a
// word develops (interpreters/dynamics/dynamics_set.h). The set also runs the creature
// set's commands (interpreters/creature/creature_commands.h); these come first in its
// table. density, servo, friction, gravity, damping, wind, control and solver set a value for the whole
// model (the last one in a word holds); rod draws a rod of the plant the word grows, with
// the stiffness and elastic segments given before it on its path.

#include <span>
#include <string_view>

namespace ontogen {

enum class DynamicsOp {
  Density,   ///< density: of every limb
  Servo,     ///< servo: the joints' position servos
  Friction,  ///< friction: of the ground and the limbs
  Gravity,   ///< gravity: its strength along -y
  Rod,       ///< rod: an elastic rod along H
  Stiffness, ///< stiffness: the bending stiffness of the rods that follow
  Elastic,   ///< elastic: the segments a rod bends in
  Damping,   ///< damping: the rods' springs' damping
  Wind,      ///< wind: the air's speed, and its gusts
  Control,   ///< control: how often the servos' targets are taken from the kinematic pose
  Solver,    ///< solver: MuJoCo's constraint solver's iterations and tolerance
};

struct DynamicsCommand {
  std::string_view name;
  DynamicsOp op;
  int minArity;
  int maxArity;
  std::string_view signature;
  std::string_view doc;
};

/// The set's own commands, in the order `ontogen help` lists them.
std::span<const DynamicsCommand> dynamicsCommands();

/// The command named `name`, or nullptr.
const DynamicsCommand* findDynamicsCommand(std::string_view name);

}  // namespace ontogen
