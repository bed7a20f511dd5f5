// Fuzz target: compile, then grow a few steps with small limits and write the word as
// `ontogen word --json` does. A program that compiles must develop or stop with a
// located model error or a limit; the JSON must be valid.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/limits.h"
#include "core/successors.h"
#include "core/word.h"
#include "core/world.h"
#include "interpreters/set_registry.h"
#include "interpreters/text/word_text.h"
#include "lang/compiler.h"
#include "tests/fuzz/fuzz_limits.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace ontogen;
  static const std::vector<CommandSetInfo> sets = commandSets();
  CompileOptions options;
  options.commandSets = sets;
  options.maxSourceBytes = fuzz::kMaxSourceBytes;
  DiagnosticSink sink;
  std::shared_ptr<const Program> program =
      compileSource(fuzz::kProgramName, std::string(reinterpret_cast<const char*>(data), size), sink, options);
  if (!program) return 0;
  WorldDef def;
  def.limits = fuzz::growLimits();
  std::vector<WordAtTime> words;
  try {
    World world(program, def);
    words.push_back({world.time(), captureWord(world)});
    const double until = std::min(program->until, fuzz::kGrowSteps * program->dt);
    world.advanceTo(until, program->dt);
    words.push_back({world.time(), captureInterpretedWord(world)});
  } catch (const LimitError&) {
    return 0;  // a named limit, as ontogen reports it
  } catch (const ModelError&) {
    return 0;  // a located run-time error of the model
  }
  std::ostringstream json;
  writeWordJson(json, words);
  if (!nlohmann::json::accept(json.str())) std::abort();  // word --json must be valid JSON
  return 0;
}
