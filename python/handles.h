#pragma once
// What the Python objects hold: a compiled program with the text it came from, a world
// growing it. Python's threads may call into them at once with the GIL released, so a
// world keeps a lock of its own.

#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include <pybind11/pybind11.h>

#include "core/world.h"
#include "model/program.h"

namespace ontogen::python {

/// A compiled program, as `ontogen.compile` and `ontogen.load` give it.
struct ProgramHandle {
  std::shared_ptr<const Program> program;
  std::string name;  ///< as diagnostics show it (a path, "PATH (converted)", "<string>")
  std::string stem;  ///< names a run's outputs
  std::string text;  ///< the cell-language text it was compiled from (converted ones too)
};

/// A world growing a program.
struct WorldHandle {
  std::shared_ptr<ProgramHandle> program;
  WorldDef def;
  std::unique_ptr<World> world;
  double dt = 1;
  std::mutex mutex;  ///< held while the world grows or is read, the GIL released
};

/// A new world of `program` at time 0 (Program.world); the model's query modules are
/// answered as `ontogen run` answers them.
std::shared_ptr<WorldHandle> makeWorld(std::shared_ptr<ProgramHandle> program, uint64_t seed, unsigned threads);

/// Grows `world` to `until` in steps of `dt` as World::advanceTo does (within `limits`,
/// its WorldDef's), calling `checkInterrupt` after each step.
void growTo(World& world, double until, double dt, const WorldLimits& limits,
            const std::function<void()>& checkInterrupt);

/// Raises ontogen.ModelError (the Python class) with `message`.
[[noreturn]] void raiseModelError(const std::string& message);

/// Thrown by withoutGil's check to leave the engine when Python has a KeyboardInterrupt
/// (or another signal's exception) pending.
struct Interrupted {};

/// Runs `work` with the GIL released, handing it a function to call between steps that
/// checks for Ctrl-C (on the main thread, at most every few hundredths of a second) and
/// stops the work by throwing Interrupted when Python has a KeyboardInterrupt pending;
/// re-raises it when Interrupted leaves `work`.
void withoutGil(const std::function<void(const std::function<void()>& checkInterrupt)>& work);

/// The id as words show and rules read it: its low 53 bits.
uint64_t shownId(uint64_t id);
/// The same for a parent, -1 for none.
int64_t shownParent(uint64_t parent);

}  // namespace ontogen::python
