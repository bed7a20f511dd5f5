#include "interpreters/physics/physics_commands.h"

#include <array>

namespace ontogen {

namespace {

constexpr std::array kCommands = {
    PhysicsCommand{"rod", PhysicsOp::Rod, 1, 3, "rod(l, r, rho)",
                   "a rod l m along H from the turtle, its base, to its tip, where the turtle moves: radius r m "
                   "(default: the turtle's !), mass density rho kg/m^3 (default: density's); F and cC make rods too"},
    PhysicsCommand{"density", PhysicsOp::Density, 1, 1, "density(rho)",
                   "mass density of the rods that follow, kg/m^3 (>= 0; default 1; pushed with [)"},
    PhysicsCommand{"load", PhysicsOp::Load, 3, 4, "load(x, y, z, at)",
                   "an external force (x, y, z) N in world coordinates on the next rod, acting at the fraction at of "
                   "its length from its base (0..1, default 1: the tip); loads on one rod add up"},
    PhysicsCommand{"young", PhysicsOp::Young, 1, 1, "young(E)",
                   "Young's modulus of the rods that follow, Pa (> 0): EI = E pi r^4 / 4 (pushed with [)"},
    PhysicsCommand{"stiffness", PhysicsOp::Stiffness, 1, 1, "stiffness(EI)",
                   "bending stiffness of the rods that follow, N m^2 (> 0), instead of young's; 0: rigid "
                   "(pushed with [)"},
    PhysicsCommand{"elastic", PhysicsOp::Elastic, 1, 1, "elastic(n)",
                   "the elastic design model: each rod bends in n segments (1..1024) under the loads and is drawn "
                   "deflected; 0: rigid statics only (the default)"},
    PhysicsCommand{"arrows", PhysicsOp::Arrows, 2, 2, "arrows(f, m)",
                   "force arrows f m/N, moment arrows m m/(N m) long; 0: scaled so the largest is as long as the "
                   "longest rod (the default); < 0: not drawn"},
    PhysicsCommand{"?F", PhysicsOp::Query, 0, 3, "?F(x, y, z)",
                   "query: after each step, the force (N) at the base of the rod before it on its path"},
    PhysicsCommand{"?M", PhysicsOp::Query, 0, 3, "?M(x, y, z)",
                   "query: after each step, the moment (N m) about the base of the rod before it on its path"},
    PhysicsCommand{"?D", PhysicsOp::Query, 0, 3, "?D(x, y, z)",
                   "query: after each step, how far the tip of the rod before it sags (m; 0 for rigid rods)"},
};

}  // namespace

std::span<const PhysicsCommand> physicsCommands() { return kCommands; }

const PhysicsCommand* findPhysicsCommand(std::string_view name) {
  for (const PhysicsCommand& command : kCommands)
    if (command.name == name) return &command;
  return nullptr;
}

}  // namespace ontogen
