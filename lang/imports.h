#pragma once
// `import "lib.cell";` (paper 002, section 4.2: modules imported into a program's
// namespace). A program and the files it imports, directly or through other imports,
// are parsed once each and merged into one tree, so a library's cells, systems, equivs,
// functions and constants are declared as if written in the program. Paths are relative
// to the importing file. A file imported twice (or in a cycle) is read once. Two
// declarations of one name are the compiler's ordinary "defined twice" errors, which name
// both places.

#include <memory>
#include <vector>

#include "lang/ast.h"
#include "model/diagnostics.h"
#include "lang/source_reader.h"

namespace ontogen {

struct ParsedProgram {
  ast::Program tree;
  std::vector<std::shared_ptr<const SourceFile>> sources;  ///< the main file first
};

/// Parses `main` and everything it imports. Constants, equivs, functions and cells of
/// imported files come before the importer's (so its #defines may use theirs); systems
/// come after (so the program's own first system stays the root). Errors go to the sink.
/// An import must be a regular file (lang/source_reader.h), and `main` with everything
/// it imports at most `maxSourceBytes` bytes.
ParsedProgram parseWithImports(std::shared_ptr<const SourceFile> main, DiagnosticSink& sink,
                               uint64_t maxSourceBytes = kDefaultMaxSourceBytes);

}  // namespace ontogen
