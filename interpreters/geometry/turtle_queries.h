#pragma once
// The turtle as an environment (core/environment_process.h): it answers cpfg's query
// modules (ABOP 1.10) by walking the world's word as the geometry set draws it
// (interpretation blocks and the homomorphism's image included) and noting, at each
// ?P(x, y, z), ?H, ?L or ?U, the turtle's position, heading, left or up vector there.
// Everything it draws is thrown away. The turtle is deterministic, so are the answers.

#include <memory>

#include "core/environment_process.h"
#include "interpreters/geometry/turtle.h"
#include "model/program.h"

namespace ontogen {

/// The turtle of a system's geometry settings (#length, #angle, #radius ...), without
/// surfaces: what every set that runs the turtle starts from.
TurtleDef turtleDefOf(const InterpretSettings& settings);

class TurtleQueries final : public EnvironmentProcess {
 public:
  /// A turtle with these settings (step, angles, radius; no surfaces: placing one does
  /// not move the turtle, so queries do not need them).
  explicit TurtleQueries(const TurtleDef& def) : def_(def) {}
  /// The turtle of a system's geometry settings (#angle, #length ...).
  static std::shared_ptr<const TurtleQueries> forSettings(const InterpretSettings& settings);

  void respond(const World& world, std::vector<QueryAnswer>& answers) const override;

 private:
  TurtleDef def_;
};

}  // namespace ontogen
