#include <iostream>

#include "apps/commands.h"
#include "apps/program_loader.h"
#include "core/word.h"
#include "interpreters/text/word_text.h"

namespace ontogen::app {

int runWord(const WordOptions& options) {
  LoadedProgram loaded = loadProgram(options.common);
  if (!loaded.program) return loaded.exitCode;
  const Program& program = *loaded.program;
  const WorldDef def = worldDefOf(options.common, program);
  double dt = options.common.step.value_or(program.dt);
  std::vector<WordAtTime> words;
  const int failed = developReporting([&] {
    auto world = std::make_unique<World>(loaded.program, def);
    for (double t : options.times) {
      if (t < world->time()) world = std::make_unique<World>(loaded.program, def);  // time runs forward only
      world->advanceTo(t, dt);
      words.push_back({t, options.interpreted ? captureInterpretedWord(*world) : captureWord(*world)});
    }
  });
  if (failed) return failed;
  if (options.json) {
    writeWordJson(std::cout, words);
  } else {
    for (const auto& word : words)
      std::cout << "t = " << formatExact(word.time) << ": " << formatWord(word.cells, options.precision) << "\n";
  }
  return kExitOk;
}

}  // namespace ontogen::app
