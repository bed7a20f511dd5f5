#pragma once
// The 3-D turtle: a position and a right-handed orthonormal frame (H heading, L left,
// U up; H x L = U) that the commands of turtle_commands.h move, turn and use to draw
// into a Geometry. The frame starts as ABOP's: H = +y, L = -x, U = +z, so a turtle that
// only turns with + and - draws in the world x-y plane, heading up the page.
//
// The frame is re-orthonormalised after every rotation (Gram-Schmidt on H and L, U as
// their cross product), so it stays orthonormal to rounding over millions of commands.

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "interpreters/geometry.h"
#include "interpreters/turtle_commands.h"

namespace ontogen {

/// The turtle's settings; validated when a Turtle is created.
struct TurtleDef {
  double step = 1;        ///< default length of F, f and cC, model units
  double angle = 90;      ///< default angle of + - & ^ \ /, degrees (radians if radians)
  double yawAngle = 90;   ///< default angle of < and >, degrees (radians if radians)
  double radius = 0;      ///< initial radius of F and cC, model units; 0 draws lines
  bool radians = false;   ///< angles (defaults and arguments) are in radians
};

/// Everything [ saves and ] restores.
struct TurtleState {
  glm::dvec3 position{0.0, 0.0, 0.0};  ///< model units
  glm::dvec3 heading{0.0, 1.0, 0.0};  ///< H, unit
  glm::dvec3 left{-1.0, 0.0, 0.0};    ///< L, unit
  glm::dvec3 up{0.0, 0.0, 1.0};       ///< U = H x L, unit
  double radius = 0;                  ///< model units; 0 draws lines
};

/// Problems the turtle skipped over; the interpreter turns them into warnings.
struct TurtleWarnings {
  int64_t unmatchedPops = 0;  ///< ] with an empty stack, ignored
  int64_t badArguments = 0;   ///< wrong arity, non-finite or negative radii: command ignored
};

/// Executes turtle commands into a Geometry.
class Turtle {
 public:
  /// Throws std::invalid_argument when def has a non-finite or negative field.
  explicit Turtle(const TurtleDef& def = {});

  /// Back to the initial state: origin, ABOP frame, def radius, empty stack, no warnings.
  void reset();

  /// Executes the command named `command` with its evaluated arguments (lengths in model
  /// units, angles in degrees or radians per TurtleDef), drawing into geometry. Returns
  /// false, doing nothing, when there is no such turtle command.
  bool execute(std::string_view command, std::span<const double> args, Geometry& geometry);
  /// The same, for a command already looked up in the table.
  void execute(const TurtleCommand& command, std::span<const double> args, Geometry& geometry);

  /// Position, frame and radius now.
  const TurtleState& state() const { return state_; }
  /// Depth of the [ ] stack.
  std::size_t depth() const { return stack_.size(); }
  /// What was skipped since the last reset.
  const TurtleWarnings& warnings() const { return warnings_; }
  /// The settings the turtle was created with.
  const TurtleDef& def() const { return def_; }

 private:
  double length(std::span<const double> args) const;
  /// Draws a cylinder of the current radius (a line when 0) along H and moves to its end.
  void drawForward(double distance, bool capped, Geometry& geometry);
  double angle(std::span<const double> args, double fallback) const;
  /// a' = a cos t + b sin t, b' = b cos t - a sin t: a turns towards b by t radians.
  void rotate(glm::dvec3& a, glm::dvec3& b, double radians);
  void orthonormalise();
  void rollHorizontal();

  TurtleDef def_;
  TurtleState state_;
  std::vector<TurtleState> stack_;
  TurtleWarnings warnings_;
};

}  // namespace ontogen
