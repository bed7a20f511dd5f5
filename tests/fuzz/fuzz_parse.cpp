// Fuzz target: the lexer and the parser, and the diagnostics they print. Any text must
// give tokens, a tree and located messages; nothing may crash, hang or leak.

#include <cstddef>
#include <cstdint>
#include <string>

#include "model/diagnostics.h"
#include "lang/lexer.h"
#include "lang/parser.h"
#include "model/source.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace ontogen;
  const SourceFile file("fuzz.cell", std::string(reinterpret_cast<const char*>(data), size));
  DiagnosticSink lexSink;
  (void)lex(file, lexSink);
  (void)formatDiagnostics(lexSink);
  DiagnosticSink parseSink;
  (void)parse(file, parseSink);
  (void)formatDiagnostics(parseSink);
  return 0;
}
