// Compiles a program of the cell language from a string, grows it and prints its
// derivation word at t = 0, 1, ..., 4: a host of ontogen's installed libraries
// (docs/EMBEDDING.md). The libraries never print; diagnostics come back in the sink.

#include <exception>
#include <iostream>
#include <memory>

#include "core/word.h"
#include "core/world.h"
#include "interpreters/set_registry.h"
#include "interpreters/text/word_text.h"
#include "lang/compiler.h"
#include "model/diagnostics.h"

namespace {

// The Thue-Morse system (paper 004, section II): every module lives one time unit, so
// the word at time n is generation n.
constexpr const char* kProgram = R"(
lsystem thueMorse {
  axiom a
  p1: a -> a b
  p2: b -> b a
}
)";

}  // namespace

int main() {
  ontogen::DiagnosticSink sink;
  ontogen::CompileOptions options;
  options.commandSets = ontogen::commandSets();  // check `interpret` blocks as `ontogen` does
  std::shared_ptr<const ontogen::Program> program =
      ontogen::compileSource("thue_morse.cell", kProgram, sink, options);
  std::cerr << ontogen::formatDiagnostics(sink);
  if (!program) return 1;

  try {
    ontogen::World world(program, ontogen::WorldDef{.seed = 1});
    for (int t = 0; t <= 4; ++t) {
      world.advanceTo(t, program->dt);
      std::cout << "t = " << t << ": " << ontogen::formatWord(ontogen::captureWord(world)) << "\n";
    }
  } catch (const std::exception& error) {  // a growth limit passed (LimitError) or the model failed (ModelError)
    std::cerr << "thue_morse: " << error.what() << "\n";
    return 3;
  }
  return 0;
}
