#pragma once
// The physics set as an environment (core/environment_process.h): results back in the
// model. After the world is seeded and after every step it solves the word as the
// physics set draws it and writes into each query module ?F(x, y, z), ?M(x, y, z) and
// ?D(x, y, z) the force at the base, the moment about the base and the displacement of
// the tip of the rod before it on its path; rules read them in the next step, so growth
// can respond to load. The turtle's own queries (?P, ?H, ?L, ?U) are answered as the
// geometry set would. Solving is deterministic, so are the answers.

#include <memory>

#include "core/environment_process.h"
#include "interpreters/geometry/turtle_queries.h"
#include "interpreters/physics/physics_set.h"
#include "model/program.h"

namespace ontogen {

class PhysicsQueries final : public EnvironmentProcess {
 public:
  explicit PhysicsQueries(const PhysicsSetDef& def, std::shared_ptr<const TurtleQueries> turtle)
      : def_(def), turtle_(std::move(turtle)) {}
  /// The physics set of a system's geometry settings (#angle, #length, #radius ...).
  static std::shared_ptr<const PhysicsQueries> forSettings(const InterpretSettings& settings);

  void respond(const World& world, std::vector<QueryAnswer>& answers) const override;

 private:
  PhysicsSetDef def_;
  std::shared_ptr<const TurtleQueries> turtle_;
};

/// Whether a program asks the physics set (?F, ?M or ?D).
bool asksPhysics(const Program& program);

}  // namespace ontogen
