#pragma once
// The table of the "dynamics" set's own commands: the physical constants of the body a
// word develops (interpreters/dynamics/dynamics_set.h). The set also runs the creature
// set's commands (interpreters/creature/creature_commands.h); these come first in its
// table. Each sets a value for the whole model: the last one in a word holds.

#include <span>
#include <string_view>

namespace ontogen {

enum class DynamicsOp {
  Density,   ///< density: of every limb
  Servo,     ///< servo: the joints' position servos
  Friction,  ///< friction: of the ground and the limbs
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
