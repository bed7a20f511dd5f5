#include <iomanip>
#include <iostream>
#include <sstream>

#include "apps/commands.h"
#include "apps/program_loader.h"
#include "core/salts.h"
#include "interpreters/interpret.h"
#include "interpreters/output_file.h"
#include "interpreters/physics/physics_set.h"
#include "interpreters/physics/statics_output.h"
#include "interpreters/run.h"
#include "interpreters/set_registry.h"
#include "model/message_number.h"

namespace ontogen::app {

// Grows the program to --at (else #until), interprets that word through the physics set
// and prints what it solved: JSON with --json, else a line per rod; --equations writes
// the system of equations. The set's warnings go to stderr, located.
int runStatics(const StaticsOptions& options) {
  LoadedProgram loaded = loadProgram(options.common);
  if (!loaded.program) return loaded.exitCode;
  const Program& program = *loaded.program;
  const WorldDef def = worldDefOf(options.common, program);
  const double dt = options.common.step.value_or(program.dt);
  const double at = options.at.value_or(program.until);
  std::unique_ptr<InterpretationSet> made = makeInterpretationSet("physics", program.rootSystem().settings);
  auto& physics = dynamic_cast<PhysicsSet&>(*made);
  const int failed = developReporting([&] {
    World world(loaded.program, def);
    world.advanceTo(at, dt);
    physics.beginFrame(FrameTarget{".", loaded.stem, 0, 1, world.time()});
    interpretWord(world, physics);
  });
  if (failed) return failed;
  for (SetWarning& warning : physics.takeWarnings())
    std::cerr << formatRunDiagnostic(
        {Severity::Warning, std::move(warning.message), warning.span, std::move(warning.cell), warning.time, warning.count});

  const PhysicsFrame& frame = physics.frame();
  std::ostringstream text;
  try {
    if (!options.equations.empty())
      writeFileAtomically(options.equations, [&](std::ostream& out) {
        writeStaticsEquations(out, physics.table(), frame.g, frame.time);
      });
    if (options.json) {
      writeStaticsJson(text, frame);
    } else {
      text << frame.rods.size() << " rods at t = " << frame.time << " s"
           << (frame.elastic ? " (elastic, " + std::to_string(frame.iterations) + " iterations)" : std::string(""))
           << "\n";
      for (const RodResult& rod : frame.rods)
        text << "  rod " << (rod.id & kIdBits) << ": mass " << rod.mass << " kg, |F| " << rod.force.norm() << " N, |M| "
             << rod.moment.norm() << " N m\n";
    }
  } catch (const NonFiniteResult& bad) {
    std::cerr << "ontogen: error: " << bad.what() << " (t = " << messageNumber(frame.time) << ")\n";
    return kExitModelError;
  } catch (const OutputError& bad) {
    std::cerr << "ontogen: error: " << bad.what() << "\n";
    return kExitOutputError;
  }
  std::cout << text.str();
  return kExitOk;
}

}  // namespace ontogen::app
