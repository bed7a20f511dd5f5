#include "interpreters/timeline/timeline_recorder.h"

#include <cmath>

#include "core/limits.h"

namespace ontogen {

namespace {
// Brackets, turns and other symbols with no rules of their own only steer
// interpretation; they would bury the cells that develop.
bool develops(const MasterCell& master) {
  return master.system >= 0 || !master.rules.empty() || !master.terminalRules.empty() ||
         (master.declared && master.symbolClass == kSymbolModule);
}
}  // namespace

void TimelineRecorder::sample(const World& world) {
  if (samples_ == 0) start_ = world.time();
  ++samples_;
  time_ = world.time();
  auto previous = rows_.end();
  walk(world, 0, previous);
  for (Entry& entry : rows_)
    if (entry.alive && entry.lastSample != samples_) {
      entry.alive = false;
      entry.row.gone = time_;
    }
}

void TimelineRecorder::walk(const World& world, int depth, std::list<Entry>::iterator& previous) {
  const Program& program = world.program();
  for (CellCursor cursor = world.rootPool().cursor(); !cursor.done(); cursor.next()) {
    const MasterCell& master = program.masters[cursor.master()];
    if (!develops(master)) continue;
    const uint64_t id = cursor.id();
    auto found = byId_.find(id);
    if (found == byId_.end()) {
      if (rows_.size() >= maxRows_) {
        if (omittedIds_.insert(id).second) ++omitted_;
        continue;
      }
      Entry entry;
      entry.row.label = master.label;
      entry.row.depth = depth;
      entry.row.born = cursor.birth();
      entry.row.system = master.system >= 0;
      // After the cell before it in the walk; a first cell with none (its pool's
      // earlier cells are gone) goes below everything, so generations read downwards.
      auto at = previous == rows_.end() ? rows_.end() : std::next(previous);
      found = byId_.emplace(id, rows_.insert(at, entry)).first;
    }
    Entry& entry = *found->second;
    entry.lastSample = samples_;
    previous = found->second;
    if (const World* child = world.childOf(id)) walk(*child, depth + 1, previous);
  }
}

Timeline TimelineRecorder::finish() const {
  Timeline timeline;
  timeline.start = start_;
  timeline.end = time_;
  timeline.omitted = omitted_;
  for (const Entry& entry : rows_) {
    TimelineRow row = entry.row;
    if (entry.alive) row.gone = time_;
    timeline.rows.push_back(std::move(row));
  }
  return timeline;
}

Timeline recordTimeline(std::shared_ptr<const Program> program, const WorldDef& def, double until, double dt,
                        size_t maxRows) {
  World world(std::move(program), def);
  TimelineRecorder recorder(maxRows);
  recorder.sample(world);
  // The time is advanced a step at a time, so each advance sees one step to come: the
  // whole way is checked against the step limit first, or --until 1e9 runs for hours.
  checkStepLimit(world.stats().steps, std::ceil((until - world.time()) / dt), dt, until, def.limits);
  while (world.time() < until - timeTolerance(until)) {
    world.advanceTo(std::min(until, world.time() + dt), dt);
    recorder.sample(world);
  }
  return recorder.finish();
}

}  // namespace ontogen
