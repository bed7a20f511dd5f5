#pragma once
// The table of commands of the "creature" interpretation set: an articulated turtle that
// builds a skeleton of joints and rigid limbs (interpreters/creature/creature_set.h).
// The set executes from it, the compiler checks arities against it and `ontogen help`
// prints it. Angles are degrees unless the program says #radians; lengths model units.

#include <span>
#include <string_view>

namespace ontogen {

enum class CreatureOp {
  Gait,       ///< gait: start a creature, its root joint
  Range,      ///< range: the range of a degree of freedom of the next joint
  Bend,       ///< bend: a 2-DOF joint (yaw, pitch): body segments
  Hinge,      ///< hinge: a 1-DOF joint, driven
  Hip,        ///< hip: the 3-DOF joint of a two-bone leg whose foot follows the gait
  Knee,       ///< knee: the 1-DOF joint of that leg, from its inverse kinematics
  Foot,       ///< foot: the end of the leg
  Limb,       ///< limb: a rigid limb, drawn as a generalized cylinder
  Move,       ///< f
  TurnLeft,   ///< +
  TurnRight,  ///< -
  PitchDown,  ///< &
  PitchUp,    ///< ^
  RollLeft,   ///< backslash
  RollRight,  ///< /
  TurnAround, ///< |
  Push,       ///< [
  Pop,        ///< ]
  Color,      ///< color
};

struct CreatureCommand {
  std::string_view name;
  CreatureOp op;
  int minArity;
  int maxArity;
  std::string_view signature;
  std::string_view doc;
};

/// Every command of the set, in the order `ontogen help` lists them.
std::span<const CreatureCommand> creatureCommands();

/// The command named `name`, or nullptr.
const CreatureCommand* findCreatureCommand(std::string_view name);

}  // namespace ontogen
