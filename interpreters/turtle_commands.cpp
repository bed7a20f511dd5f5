#include "interpreters/turtle_commands.h"

#include <array>

namespace ontogen {

namespace {

// Angles below: "deg" means degrees, or radians when the set is in radians mode.
constexpr std::array kCommands = {
    TurtleCommand{"F", TurtleOp::Forward, 0, 1, "F(l)",
                  "move l units (default: step) along H, drawing a line, or a cylinder of "
                  "the current radius when it is > 0"},
    TurtleCommand{"f", TurtleOp::Move, 0, 1, "f(l)",
                  "move l units (default: step) along H without drawing"},
    TurtleCommand{"+", TurtleOp::TurnLeft, 0, 1, "+(a)",
                  "turn left by a deg (default: angle) about U: H turns towards L"},
    TurtleCommand{"-", TurtleOp::TurnRight, 0, 1, "-(a)",
                  "turn right by a deg (default: angle) about U: H turns away from L"},
    TurtleCommand{"&", TurtleOp::PitchDown, 0, 1, "&(a)",
                  "pitch down by a deg (default: angle) about L: H turns towards -U"},
    TurtleCommand{"^", TurtleOp::PitchUp, 0, 1, "^(a)",
                  "pitch up by a deg (default: angle) about L: H turns towards U"},
    TurtleCommand{"\\", TurtleOp::RollLeft, 0, 1, "\\(a)",
                  "roll left by a deg (default: angle) about H: L turns towards -U"},
    TurtleCommand{"/", TurtleOp::RollRight, 0, 1, "/(a)",
                  "roll right by a deg (default: angle) about H: L turns towards U"},
    TurtleCommand{"<", TurtleOp::YawLeft, 0, 1, "<(a)",
                  "yaw left by a deg (default: yawAngle) about U, like +"},
    TurtleCommand{">", TurtleOp::YawRight, 0, 1, ">(a)",
                  "yaw right by a deg (default: yawAngle) about U, like -"},
    TurtleCommand{"|", TurtleOp::TurnAround, 0, 0, "|", "turn around: 180 deg about U"},
    TurtleCommand{"[", TurtleOp::Push, 0, 0, "[",
                  "push the turtle state (position, frame, radius)"},
    TurtleCommand{"]", TurtleOp::Pop, 0, 0, "]",
                  "pop the turtle state; an unmatched ] is ignored and counted in a warning"},
    TurtleCommand{"!", TurtleOp::SetRadius, 1, 1, "!(r)",
                  "set the radius of following cylinders to r units (0: lines)"},
    TurtleCommand{"cC", TurtleOp::Cylinder, 0, 2, "cC(l, capped)",
                  "draw a cylinder of the current radius, l units (default: step) along H, "
                  "and move to its end like F; capped != 0 closes both ends"},
    TurtleCommand{"disc", TurtleOp::Disc, 1, 2, "disc(inner, outer)",
                  "draw an annulus of radii inner..outer units (one argument: a full disc "
                  "of that radius) centred at the turtle in the H-L plane, without moving"},
    TurtleCommand{"sphere", TurtleOp::Sphere, 0, 1, "sphere(r)",
                  "draw a sphere of radius r units (default: the current radius) at the "
                  "turtle, without moving"},
    TurtleCommand{"$", TurtleOp::RollHorizontal, 0, 0, "$",
                  "roll about H so that L is horizontal (world up is +y); ignored when H "
                  "is vertical"},
};

}  // namespace

std::span<const TurtleCommand> turtleCommands() { return kCommands; }

const TurtleCommand* findTurtleCommand(std::string_view name) {
  for (const TurtleCommand& command : kCommands) {
    if (command.name == name) return &command;
  }
  return nullptr;
}

}  // namespace ontogen
