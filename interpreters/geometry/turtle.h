#pragma once
// The 3-D turtle: a position and a right-handed orthonormal frame (H heading, L left,
// U up; H x L = U) that the commands of turtle_commands.h move, turn and use to draw
// into a Geometry. The frame starts as ABOP's: H = +y, L = -x, U = +z, so a turtle that
// only turns with + and - draws in the world x-y plane, heading up the page.
//
// The frame is re-orthonormalised after every rotation (Gram-Schmidt on H and L, U as
// their cross product), so it stays orthonormal to rounding over millions of commands.

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "interpreters/geometry.h"
#include "interpreters/geometry/environment.h"
#include "interpreters/geometry/gap_filter.h"
#include "interpreters/geometry/gc_mesher.h"
#include "interpreters/geometry/surface.h"
#include "interpreters/geometry/turtle_commands.h"

namespace ontogen {

/// The turtle's settings; validated when a Turtle is created.
struct TurtleDef {
  double step = 1;        ///< default length of F, f and cC, model units
  double angle = 90;      ///< default angle of + - & ^ \ /, degrees (radians if radians)
  double yawAngle = 90;   ///< default angle of < and >, degrees (radians if radians)
  double radius = 0;      ///< initial radius of F and cC, model units; 0 draws lines
  bool radians = false;   ///< angles (defaults and arguments) are in radians
  /// Predefined surfaces by id (0..1023), e.g. loaded from OBJ files (#surface).
  std::map<int, Surface> surfaces{};
};

/// Everything [ saves and ] restores.
struct TurtleState {
  glm::dvec3 position{0.0, 0.0, 0.0};  ///< model units
  glm::dvec3 heading{0.0, 1.0, 0.0};  ///< H, unit
  glm::dvec3 left{-1.0, 0.0, 0.0};    ///< L, unit
  glm::dvec3 up{0.0, 0.0, 1.0};       ///< U = H x L, unit
  double radius = 0;                  ///< model units; 0 draws lines
  uint32_t material = 0;              ///< palette index (color)
  double depth = 0;                   ///< segments drawn by F on the path from the origin
  int section = -12;                  ///< GC section: id >= 0, or -n for a circle of n points
  int gc = -1;                        ///< the generalized cylinder F extends, or -1
  int plate = -1;                     ///< the plate F adds corners to, or -1
};

/// Problems the turtle skipped over; the interpreter turns them into warnings.
struct TurtleWarnings {
  int64_t unmatchedPops = 0;  ///< ] with an empty stack, ignored
  int64_t badArguments = 0;   ///< wrong arity, non-finite or negative radii: command ignored
  int64_t blocked = 0;        ///< F that the environment stopped (obstacle, resource, depth)
};

/// Executes turtle commands into a Geometry.
class Turtle {
 public:
  /// Throws std::invalid_argument when def has a non-finite or negative field.
  explicit Turtle(const TurtleDef& def = {});

  /// Back to the initial state: origin, ABOP frame, def radius, empty stack, no warnings,
  /// no tropism, empty environment, no sections, no open generalized cylinder.
  void reset();

  /// Meshes every generalized cylinder still open into geometry, closes open plates and
  /// adds every plate, through the gap filter when it is on (end of a frame).
  void finish(Geometry& geometry);

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
  /// The environment declared so far in this frame.
  const Environment& environment() const { return environment_; }
  /// Total length drawn by F and cC since the last reset, model units.
  double drawnLength() const { return drawnLength_; }
  /// The plates drawn so far in this frame, as drawn (before the gap filter).
  const std::vector<Plate>& plates() const { return plates_; }
  /// The gap filter's tolerance, model units; 0 when it is off.
  double gapTolerance() const { return gapTolerance_; }
  /// The surface id stands for now: a patch of this frame, else a predefined one; null
  /// when neither exists.
  const Surface* surface(int id) const;

 private:
  double length(std::span<const double> args) const;
  /// Draws a cylinder of the current radius (a line when 0) along H and moves to its end.
  void drawForward(double requested, bool capped, Geometry& geometry);
  double angle(std::span<const double> args, double fallback) const;
  /// a' = a cos t + b sin t, b' = b cos t - a sin t: a turns towards b by t radians.
  void rotate(glm::dvec3& a, glm::dvec3& b, double radians);
  void orthonormalise();
  void rollHorizontal();
  /// Turns the frame by the smallest rotation that takes H to the unit vector heading.
  void turnHeadingTo(const glm::dvec3& heading);
  /// Applies tropism, the environment and the limits before a forward move; returns the
  /// distance to move, or nullopt when the move is blocked.
  std::optional<double> prepareForward(double distance);
  const GcSection* section(int key);
  void finishGc(int index, bool caps, Geometry& geometry);
  void executeEnvironment(TurtleOp op, std::span<const double> args);
  void executeCylinderCommand(TurtleOp op, std::span<const double> args, Geometry& geometry);
  void executeSurfaceCommand(TurtleOp op, std::span<const double> args, Geometry& geometry);
  /// The surface an argument names; throws SurfaceError when there is none.
  const Surface& surfaceArgument(double id) const;
  void placeSurface(const Surface& surface, double scale, Geometry& geometry);
  void closePlate();

  /// A generalized cylinder being built.
  struct OpenGc {
    std::vector<GcControlPoint> points;
    uint32_t material = 0;
    bool open = true;
  };

  TurtleDef def_;
  TurtleState state_;
  std::vector<TurtleState> stack_;
  TurtleWarnings warnings_;
  glm::dvec3 tropism_{0.0};  // T as given: H turns by tropismStrength_ |H x T| radians
  double tropismStrength_ = 0;
  Environment environment_;
  bool environmentActive_ = false;
  double drawnLength_ = 0;
  std::map<int, GcSection> sections_;   // by id
  std::map<int, GcSection> circles_;    // by point count
  std::optional<int> definingSection_;
  GcSection pendingSection_;
  std::vector<OpenGc> gcs_;
  std::map<int, Surface> patches_;  // defined in this frame, by id
  std::optional<int> definingPatch_;
  int patchResolution_ = 8;
  std::vector<glm::dvec3> patchPoints_;
  std::vector<Plate> plates_;
  double gapTolerance_ = 0;
};

}  // namespace ontogen
