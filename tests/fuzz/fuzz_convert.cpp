// Fuzz target: `ontogen convert`, the same bytes read as cpfg's .l (with themselves as the
// view file) and as L-Py's .lpy, each converted program compiled as `check` would, and
// the compiler's diagnostics shown at the file's lines. Any text must give a program or
// located messages; nothing may crash, hang or leak.

#include <cstddef>
#include <cstdint>
#include <string>

#include "lang/compiler.h"
#include "lang/convert/convert.h"
#include "model/diagnostics.h"
#include "model/source.h"
#include "tests/fuzz/fuzz_limits.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace ontogen;
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (convert::Dialect dialect : {convert::Dialect::Cpfg, convert::Dialect::LPy}) {
    const SourceFile file(dialect == convert::Dialect::Cpfg ? "fuzz.l" : "fuzz.lpy", text);
    DiagnosticSink sink;
    convert::ConvertResult converted = convert::convertFile(file, dialect, text, sink, fuzz::kMaxSourceBytes);
    (void)formatDiagnostics(sink);
    if (!converted.program) continue;
    DiagnosticSink compileSink;
    CompileOptions options;
    options.maxSourceBytes = fuzz::kMaxSourceBytes;
    (void)compileSource("fuzz.lpy (converted)", std::move(*converted.program), compileSink, options);
    for (const Diagnostic& d : compileSink.diagnostics())
      (void)formatDiagnostic(convert::mapToOriginal(d, file, converted.lineOrigins));
  }
  return 0;
}
