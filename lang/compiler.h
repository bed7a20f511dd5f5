#pragma once
// Checks a parsed program and lowers it to the cell model (model/program.h): cells and
// L-system modules become master cells, productions become terminal rules, successor
// words become actions, every expression is compiled once. Errors go to the sink with
// their location; compilation goes on to report as many as it can.

#include <functional>
#include <optional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "lang/ast.h"
#include "model/diagnostics.h"
#include "model/program.h"
#include "lang/source_reader.h"

namespace ontogen {

/// An instruction an interpretation set understands (for checking interpretation blocks).
struct CommandInfo {
  std::string_view name;
  int minArity = 0;
  int maxArity = 0;  ///< -1: any
  /// The set's own number for the command (its index in the set's table): compiled
  /// instructions carry it, so the set runs them without looking a name up. -1: none
  /// (the set runs the command by its name).
  int id = -1;
};

/// A set the program may name in `interpret SET { ... }`.
struct CommandSetInfo {
  std::string name;
  std::function<const CommandInfo*(std::string_view)> find;
  /// Names the set gives meaning to in its blocks' arguments, as `minor` in
  /// `scale(minor)`; program constants shadow them. Empty: none.
  std::function<std::optional<double>(std::string_view)> constant = {};
  /// Checks a file a directive of this set names (#surface's OBJ file), resolved against
  /// the program's folder: empty when the set can use it, else why not, so that `check`
  /// finds what `run` would fail on. Null: files are not checked.
  std::function<std::string(const std::string& path)> checkFile = {};
};

/// A value for a program's `#define`, given from outside the text (`--define NAME=VALUE`),
/// so a sweep or a search can vary a model without editing it.
struct DefineOverride {
  std::string name;  ///< a name the program defines with #define
  double value = 0;  ///< in the units the text uses for it; must be finite
};

/// Errors in the options themselves (an unknown rootSystem or define name) are reported
/// like the program's, but with no source span: they belong to no text.
struct CompileOptions {
  std::vector<CommandSetInfo> commandSets;  ///< empty: interpretation blocks are not checked
  std::string rootSystem;                   ///< empty: the first system of the program
  /// Every `#define NAME` of the program (top level, blocks, imported files) takes the
  /// value given for NAME as if its text had said that number: the constants after it,
  /// expressions, axioms, lifetimes, grid sizes and directives all see it. A name given
  /// twice takes the last value; a name the program does not define is an error.
  std::vector<DefineOverride> defines;
  /// compileSource: the most source text the program and its imports may have, bytes.
  uint64_t maxSourceBytes = kDefaultMaxSourceBytes;
};

/// Compiles a parsed program whose text is `source`. Returns null when there were errors.
std::unique_ptr<Program> compile(const ast::Program& tree, std::shared_ptr<const SourceFile> source,
                                 DiagnosticSink& sink, const CompileOptions& options = {});
/// The same for a program merged from several files (lang/imports.h), the main one first.
std::unique_ptr<Program> compile(const ast::Program& tree, std::vector<std::shared_ptr<const SourceFile>> sources,
                                 DiagnosticSink& sink, const CompileOptions& options = {});

/// Parses and compiles a program text in one call, with the files it imports (paths
/// relative to the directory of `name`).
std::unique_ptr<Program> compileSource(std::string name, std::string text, DiagnosticSink& sink,
                                       const CompileOptions& options = {});

}  // namespace ontogen
