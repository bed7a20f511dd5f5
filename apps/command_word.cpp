#include <iostream>
#include <sstream>

#include "apps/commands.h"
#include "apps/program_loader.h"
#include "core/word.h"
#include "interpreters/text/word_text.h"

namespace ontogen::app {

// The words stream to standard output cell by cell, without a record per cell. Nothing
// is printed unless every time was reached: the words before the last are kept as text
// (far smaller than the pools that made them) and the last, often by far the largest,
// streams once the world has reached it, when nothing can fail any more (an interpreted
// word is kept to the end too: making its image can still fail).
int runWord(const WordOptions& options) {
  LoadedProgram loaded = loadProgram(options.common);
  if (!loaded.program) return loaded.exitCode;
  const Program& program = *loaded.program;
  const WorldDef def = worldDefOf(options.common, program);
  double dt = options.common.step.value_or(program.dt);
  std::ostringstream earlier;
  std::unique_ptr<World> world;
  auto writeWord = [&](std::ostream& out, double t, bool first, bool last) {
    BufferedOutput buffered(out);
    if (options.json == "compact") {
      CompactWordJsonWriter writer(buffered);
      if (first) writer.begin();
      writer.beginTime(t, first);
      writer.writeWord(*world, options.interpreted);
      writer.endTime();
      if (last) writer.end();
    } else if (options.json == "full") {
      WordJsonWriter writer(buffered);
      if (first) writer.begin();
      writer.beginTime(t, first);
      if (options.interpreted)
        visitInterpretedWord(*world, writer);
      else
        visitWord(*world, writer);
      writer.endTime();
      if (last) writer.end();
    } else {
      buffered.text() += "t = " + formatExact(t) + ": ";
      writeWordText(*world, buffered, options.precision, options.interpreted);
      buffered.text() += '\n';
    }
  };
  const int failed = developReporting([&] {
    world = std::make_unique<World>(loaded.program, def);
    for (size_t i = 0; i < options.times.size(); ++i) {
      const double t = options.times[i];
      if (t < world->time()) world = std::make_unique<World>(loaded.program, def);  // time runs forward only
      world->advanceTo(t, dt);
      const bool last = i + 1 == options.times.size();
      // The homomorphism's image can still pass a limit while it is made: an interpreted
      // word is kept as text to the end too.
      const bool stream = last && !options.interpreted;
      if (stream) {
        // Giving a word grown without ids its ids again can still pass the memory limit.
        // The full JSON prints the ids, the compact JSON and text do not (WordVisitor::readsIds).
        prepareToVisit(*world, options.json == "full");
        std::cout << earlier.str();
        earlier = std::ostringstream();
      }
      writeWord(stream ? std::cout : earlier, t, i == 0, last);
    }
  });
  if (failed) return failed;
  std::cout << earlier.str();
  std::cout.flush();
  return kExitOk;
}

}  // namespace ontogen::app
