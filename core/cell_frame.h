#pragma once
// The one loader of a cell's frame (model/program.h): its state values, then the
// read-only internal state of FrameSlot (age, terminal age, time, id, position). Rules,
// grid placements and interpretation blocks all read a cell through it, so `age` or
// `me.x` can never mean two things.

#include <algorithm>
#include <array>
#include <cstdint>

#include "core/salts.h"
#include "model/program.h"
#include "pools/cell_cursor.h"
#include "pools/cell_record.h"

namespace ontogen {

/// The slots every frame has: age, terminal age, time, id. The hot loops (rules and rates
/// over large pools) write only these, and the place (loadPlace) for the masters whose
/// expressions read it (MasterCell::readsPosition, readsParent).
inline void loadAgeAndId(double* internal, double birth, uint64_t id, double lifetime, double when) {
  internal[FrameSlot::kAge] = when - birth;
  internal[FrameSlot::kTerminalAge] = lifetime;
  internal[FrameSlot::kTime] = when;
  internal[FrameSlot::kId] = idValue(id);
}
inline void loadAgeAndId(double* internal, const CellRecord& cell, double lifetime, double when) {
  loadAgeAndId(internal, cell.birth, cell.id, lifetime, when);
}

/// The place slots: position (me.x, me.y, me.z) and parent (me.parent).
inline void loadPlace(double* internal, const std::array<double, 3>& position, double parent) {
  internal[FrameSlot::kX] = position[0];
  internal[FrameSlot::kY] = position[1];
  internal[FrameSlot::kZ] = position[2];
  internal[FrameSlot::kParent] = parent;
}

/// Writes the internal-state slots at `internal` (the frame after the state values) for
/// `cell` at global time `when` (seconds); `position` is its index (linear pool), grid
/// coordinates or spatial x, y, z; `parent` the id value of the cell it hangs from
/// (idValue, core/parents.h), -1 for none.
inline void loadInternalState(double* internal, const CellRecord& cell, double lifetime, double when,
                              const std::array<double, 3>& position, double parent = -1) {
  loadAgeAndId(internal, cell, lifetime, when);
  loadPlace(internal, position, parent);
}

/// Copies the cell's `master.stateCount()` values from `state` into `frame` and fills the
/// internal state after them. Returns `frame`.
inline double* loadCellFrame(double* frame, const MasterCell& master, const CellRecord& cell, const double* state,
                             double when, const std::array<double, 3>& position, double parent = -1) {
  const uint32_t n = master.stateCount();
  std::copy(state, state + n, frame);
  loadInternalState(frame + n, cell, master.lifetime, when, position, parent);
  return frame;
}

/// The same for a cell as a cursor gives it (pools/cell_cursor.h), state included.
inline double* loadCellFrame(double* frame, const MasterCell& master, const CellView& cell, double when,
                             const std::array<double, 3>& position, double parent = -1) {
  const uint32_t n = master.stateCount();
  std::copy(cell.state, cell.state + n, frame);
  loadAgeAndId(frame + n, cell.birth, cell.id, master.lifetime, when);
  loadPlace(frame + n, position, parent);
  return frame;
}

}  // namespace ontogen
