#include "interpreters/physics/physics_queries.h"

#include <algorithm>

#include "core/world.h"
#include "interpreters/interpret.h"

namespace ontogen {

std::shared_ptr<const PhysicsQueries> PhysicsQueries::forSettings(const InterpretSettings& settings) {
  PhysicsSetDef def;
  def.turtle = turtleDefOf(settings);
  return std::make_shared<const PhysicsQueries>(def, TurtleQueries::forSettings(settings));
}

void PhysicsQueries::respond(const World& world, std::vector<QueryAnswer>& answers) const {
  if (turtle_) turtle_->respond(world, answers);
  // A set of its own each time: respond() is const and may be called from any world.
  PhysicsSet set(def_);
  FrameTarget target;
  target.time = world.time();
  set.beginFrame(target);
  interpretWord(world, set);
  const auto& solved = set.queryAnswers();
  if (solved.empty()) return;
  const Program& program = world.program();
  for (CellCursor cell = world.rootPool().cursor(); !cell.done(); cell.next()) {
    const char kind = program.masters[cell.master()].query;
    if (kind != 'F' && kind != 'M' && kind != 'D') continue;
    const auto it = solved.find(cell.id());
    if (it == solved.end()) continue;
    answers.push_back({static_cast<uint32_t>(cell.index()), {it->second.x(), it->second.y(), it->second.z()}});
  }
}

bool asksPhysics(const Program& program) {
  return std::any_of(program.masters.begin(), program.masters.end(), [](const auto& master) {
    return master.query == 'F' || master.query == 'M' || master.query == 'D';
  });
}

}  // namespace ontogen
