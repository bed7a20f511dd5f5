#pragma once
// The table of commands of the "physics" interpretation set (physics_set.h): the rods
// of paper 003's design models and their attributes. The set also runs every turtle
// command of the geometry set (turtle_commands.h), so a program that draws with F
// becomes a rod tree as it is. The set executes from this table, the compiler checks
// arities against it and `ontogen help` prints it. SI units: metres, kilograms,
// seconds, newtons; angles in degrees unless the program says #radians.

#include <span>
#include <string_view>

namespace ontogen {

enum class PhysicsOp {
  Rod,        ///< rod: a rod along H (paper 003's design-model symbol)
  Density,    ///< density: the mass density of the rods that follow
  Load,       ///< load: an external force on the next rod
  Young,      ///< young: the Young's modulus of the rods that follow
  Stiffness,  ///< stiffness: their bending stiffness EI, given
  Elastic,    ///< elastic: the elastic design model on, drawn deflected
  Arrows,     ///< arrows: how force and moment arrows are scaled
  Query,      ///< ?F, ?M, ?D: the rod before it answers its force, moment or deflection
};

struct PhysicsCommand {
  std::string_view name;
  PhysicsOp op;
  int minArity;
  int maxArity;
  std::string_view signature;
  std::string_view doc;
};

/// Every command of the set, in the order `ontogen help` lists them.
std::span<const PhysicsCommand> physicsCommands();

/// The command named `name`, or nullptr.
const PhysicsCommand* findPhysicsCommand(std::string_view name);

}  // namespace ontogen
