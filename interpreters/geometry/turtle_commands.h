#pragma once
// The table of turtle commands of the "geometry" interpretation set. The turtle executes
// from it, the interpreter checks arities against it, error messages quote its
// signatures and `ontogen help` prints it.
//
// Frame and rotations (ABOP, Prusinkiewicz & Lindenmayer 1990, ch. 1.5): the turtle
// carries a right-handed orthonormal frame H (heading), L (left), U (up), H x L = U,
// starting at H = (0,1,0), L = (-1,0,0), U = (0,0,1). ABOP's matrices R_U, R_L, R_H are
// read so that every command does what its name says:
//   + turns left:   H rotates towards L  (about U)     - the opposite
//   & pitches down: H rotates towards -U (about L)     ^ the opposite
//   \ rolls left:   L rotates towards -U (about H)     / the opposite
// Angles are degrees unless TurtleDef::radians; lengths are model units.

#include <span>
#include <string_view>

namespace ontogen {

/// What a turtle command does; the turtle dispatches on it.
enum class TurtleOp {
  Forward,         ///< F
  Move,            ///< f
  TurnLeft,        ///< +
  TurnRight,       ///< -
  PitchDown,       ///< &
  PitchUp,         ///< ^
  RollLeft,        ///< backslash
  RollRight,       ///< /
  YawLeft,         ///< <
  YawRight,        ///< >
  TurnAround,      ///< |
  Push,            ///< [
  Pop,             ///< ]
  SetRadius,       ///< !
  Cylinder,        ///< cC
  Disc,            ///< disc
  Sphere,          ///< sphere
  RollHorizontal,  ///< $
  Color,           ///< color
  Tropism,         ///< tropism
  Circle,          ///< circle: select a circular cross-section
  Section,         ///< section: start defining a polyline cross-section
  Point,           ///< point: add a point to the section being defined
  EndSection,      ///< endsection
  UseSection,      ///< usesection
  GcBegin,         ///< gcbegin: start a generalized cylinder
  GcEnd,           ///< gcend: finish it
  Ceiling,         ///< ceiling: environment plane growth cannot pass upwards
  Ground,          ///< ground: environment plane growth cannot pass downwards
  ObstacleSphere,  ///< obstaclesphere
  ObstacleBox,     ///< obstaclebox
  Attractor,       ///< attractor
  Repeller,        ///< repeller
  MaxLength,       ///< maxlength: resource limit
  MaxDepth,        ///< maxdepth: generation limit
  PlaceSurface,    ///< surface: place a predefined surface
  BlendSurfaces,   ///< blend: place a weighted blend of surfaces
  Patch,           ///< patch: start defining a Bezier patch surface
  PatchPoint,      ///< patchpoint: add a control point to it
  EndPatch,        ///< endpatch
  Plate,           ///< plate: start a flat facet
  EndPlate,        ///< endplate: close it
  GapFilter,       ///< gapfilter: join plate corners at the end of the frame
  Query,           ///< ?P ?H ?L ?U: cpfg's query modules; draw nothing (core/environment_process.h)
};

/// One row of the table.
struct TurtleCommand {
  std::string_view name;       ///< the command as it appears in a word, e.g. "cC"
  TurtleOp op;                 ///< what the turtle does
  int minArity;                ///< fewer arguments are an error
  int maxArity;                ///< more arguments are an error
  std::string_view signature;  ///< e.g. "cC(l, capped)"
  std::string_view doc;        ///< one line, with units and defaults
};

/// Every turtle command, in the order `ontogen help` lists them.
std::span<const TurtleCommand> turtleCommands();

/// The command named `name`, or nullptr when the turtle does not know it.
const TurtleCommand* findTurtleCommand(std::string_view name);

}  // namespace ontogen
