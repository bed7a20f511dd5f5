#pragma once
// Recursive-descent parser of the cell language. It recovers after an error (skipping
// to the end of the statement) so that one run reports as many errors as it can, and
// stays silent on tokens that are already errors. The grammar is in docs/LANGUAGE.md.

#include "lang/ast.h"
#include "model/diagnostics.h"
#include "model/source.h"

namespace ontogen {

/// Parses a whole program. The tree is returned even when errors were reported; callers
/// check sink.hasErrors() before compiling it.
ast::Program parse(const SourceFile& file, DiagnosticSink& sink);

}  // namespace ontogen
