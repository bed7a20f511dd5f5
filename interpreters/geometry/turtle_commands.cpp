#include "interpreters/geometry/turtle_commands.h"

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
    TurtleCommand{"color", TurtleOp::Color, 0, 1, "color(i)",
                  "draw with palette colour i (0..15, taken modulo 16; default: the next "
                  "colour); `;` separates instructions, so colour has a name"},
    TurtleCommand{"tropism", TurtleOp::Tropism, 4, 4, "tropism(x, y, z, e)",
                  "before each F, bend H towards the vector T = (x, y, z) by e |H x T| radians, T "
                  "as given, not normalised (ABOP 2.4); e = 0 turns tropism off"},
    TurtleCommand{"circle", TurtleOp::Circle, 0, 1, "circle(n)",
                  "generalized cylinders from here use a circular cross-section of n points "
                  "(default 12, 3..1024)"},
    TurtleCommand{"section", TurtleOp::Section, 1, 1, "section(id)",
                  "start defining the closed polyline cross-section number id (0..1023) from "
                  "the point commands that follow"},
    TurtleCommand{"point", TurtleOp::Point, 2, 2, "point(x, y)",
                  "add the point (x, y) to the section being defined; x along L, y along U, "
                  "anticlockwise, scaled by the radius"},
    TurtleCommand{"endsection", TurtleOp::EndSection, 0, 0, "endsection",
                  "finish the section being defined (it needs at least 3 points)"},
    TurtleCommand{"usesection", TurtleOp::UseSection, 1, 1, "usesection(id)",
                  "generalized cylinders from here use the defined section id"},
    TurtleCommand{"gcbegin", TurtleOp::GcBegin, 0, 0, "gcbegin",
                  "start a generalized cylinder here: each F adds a control point instead "
                  "of a cylinder"},
    TurtleCommand{"gcend", TurtleOp::GcEnd, 0, 1, "gcend(caps)",
                  "finish the generalized cylinder: a smooth tube through its control "
                  "points; caps != 0 (default 1) closes both ends"},
    TurtleCommand{"ceiling", TurtleOp::Ceiling, 1, 1, "ceiling(h)",
                  "environment: the plane y = h, which no segment crosses upwards"},
    TurtleCommand{"ground", TurtleOp::Ground, 1, 1, "ground(h)",
                  "environment: the plane y = h, which no segment crosses downwards"},
    TurtleCommand{"obstaclesphere", TurtleOp::ObstacleSphere, 4, 4,
                  "obstaclesphere(x, y, z, r)",
                  "environment: a sphere of radius r at (x, y, z) that growth goes around"},
    TurtleCommand{"obstaclebox", TurtleOp::ObstacleBox, 6, 6,
                  "obstaclebox(x0, y0, z0, x1, y1, z1)",
                  "environment: an axis-aligned box between two corners that growth goes "
                  "around"},
    TurtleCommand{"attractor", TurtleOp::Attractor, 5, 5,
                  "attractor(x, y, z, strength, falloff)",
                  "environment: before each F, bend H towards (x, y, z) by strength |H x D| / "
                  "(1 + (d / falloff)^2) radians"},
    TurtleCommand{"repeller", TurtleOp::Repeller, 5, 5, "repeller(x, y, z, strength, falloff)",
                  "environment: like attractor, bending H away from the point"},
    TurtleCommand{"maxlength", TurtleOp::MaxLength, 1, 1, "maxlength(L)",
                  "environment: resource limit, at most L units drawn by F in the frame; the "
                  "segment that reaches it is shortened"},
    TurtleCommand{"maxdepth", TurtleOp::MaxDepth, 1, 1, "maxdepth(n)",
                  "environment: generation limit, F draws only the first n segments of "
                  "each path from the origin"},
    TurtleCommand{"surface", TurtleOp::PlaceSurface, 1, 2, "surface(id, s)",
                  "place surface id (#surface, or patch) at the turtle scaled by s (default 1): "
                  "its x along H x U, y along H, z along U; the turtle does not move"},
    TurtleCommand{"blend", TurtleOp::BlendSurfaces, 3, 17, "blend(s, id1, w1, id2, w2, ...)",
                  "place the vertex-wise blend sum(w_i surface_i) / sum(w_i) of up to 8 surfaces "
                  "of one topology, scaled by s, like surface"},
    TurtleCommand{"patch", TurtleOp::Patch, 1, 2, "patch(id, n)",
                  "start defining surface id (0..1023) as the bicubic Bezier patch of the 16 "
                  "patchpoint commands that follow, cut into n x n cells (default 8, 1..256)"},
    TurtleCommand{"patchpoint", TurtleOp::PatchPoint, 3, 3, "patchpoint(x, y, z)",
                  "add a control point (surface units) to the patch being defined, row by row, "
                  "4 to a row"},
    TurtleCommand{"endpatch", TurtleOp::EndPatch, 0, 0, "endpatch",
                  "finish the patch being defined (it needs exactly 16 points)"},
    TurtleCommand{"plate", TurtleOp::Plate, 0, 0, "plate",
                  "start a flat facet at the turtle: until endplate each F adds the point where "
                  "it ends as a corner instead of drawing"},
    TurtleCommand{"endplate", TurtleOp::EndPlate, 0, 0, "endplate",
                  "close the facet back to its first corner (it needs at least 3 corners)"},
    TurtleCommand{"gapfilter", TurtleOp::GapFilter, 1, 1, "gapfilter(t)",
                  "at the end of the frame join plate corners closer than t units and colour "
                  "each plate by how much its edges stretched, blue to red; 0 turns it off"},
    // cpfg's query modules (ABOP 1.10): the turtle environment writes its frame into them.
    TurtleCommand{"?P", TurtleOp::Query, 0, 3, "?P(x, y, z)",
                  "query: draws nothing; after each step the turtle's position here is written into "
                  "the module's parameters"},
    TurtleCommand{"?H", TurtleOp::Query, 0, 3, "?H(x, y, z)",
                  "query: after each step the turtle's heading H here is written into the module"},
    TurtleCommand{"?L", TurtleOp::Query, 0, 3, "?L(x, y, z)",
                  "query: after each step the turtle's left vector L here is written into the module"},
    TurtleCommand{"?U", TurtleOp::Query, 0, 3, "?U(x, y, z)",
                  "query: after each step the turtle's up vector U here is written into the module"},
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
