#pragma once

#include <vector>

#include "model/diagnostics.h"
#include "lang/token.h"

namespace ontogen {

/// Splits a source file into tokens (ending with EndOfFile). Comments are `// ...` and
/// `/* ... */`. Bad characters become Error tokens and a diagnostic; lexing goes on.
std::vector<Token> lex(const SourceFile& file, DiagnosticSink& sink);

}  // namespace ontogen
