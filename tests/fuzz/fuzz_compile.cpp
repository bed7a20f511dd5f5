// Fuzz target: the whole compiler (parse, imports, checks, lowering) with every
// interpretation set's commands, as `ontogen check` runs it. Any text must compile or
// give located errors; nothing may crash, hang or leak.

#include <cstddef>
#include <cstdint>
#include <string>

#include "interpreters/set_registry.h"
#include "lang/compiler.h"
#include "model/diagnostics.h"
#include "tests/fuzz/fuzz_limits.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace ontogen;
  static const std::vector<CommandSetInfo> sets = commandSets();
  CompileOptions options;
  options.commandSets = sets;
  options.maxSourceBytes = fuzz::kMaxSourceBytes;
  DiagnosticSink sink;
  (void)compileSource(fuzz::kProgramName, std::string(reinterpret_cast<const char*>(data), size), sink, options);
  (void)formatDiagnostics(sink);
  return 0;
}
