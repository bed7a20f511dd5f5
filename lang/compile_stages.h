#pragma once
// The stages of one compilation, in the order the driver (lang/compiler.cpp) runs them
// over a CompileContext (lang/compile_context.h). Each group is defined in the file
// named above it. A stage reports errors to the context's sink and goes on, so one run
// reports as many as it can.

#include <string>
#include <vector>

#include "lang/ast.h"
#include "lang/compile_context.h"

namespace ontogen::detail {

// ---- lang/compile_functions.cpp: constants, equivs, development functions ----

/// Takes CompileOptions::defines, the last value of each name; reports values that are not finite.
void takeDefineOverrides(CompileContext& ctx);
/// A block's #defines into its scope; `system`: the block's index, -1 for the top level.
void compileDefines(CompileContext& ctx, const std::vector<ast::Define>& list, Scope& scope, int system);
/// Every value given from outside must name a #define of the program.
void checkDefineOverrides(CompileContext& ctx);
/// `equiv f mov` statements into a scope.
void compileEquivs(CompileContext& ctx, const std::vector<ast::Equiv>& list, Scope& scope);
/// Development functions into a scope (they may call each other in any order).
void compileFunctions(CompileContext& ctx, const std::vector<ast::DevelopmentFunction>& list, Scope& scope);
/// A function named after a symbol develops it (after every master exists).
void attachDevelopmentFunctions(CompileContext& ctx);

// ---- lang/compile_directives.cpp: directives ----

/// A block's directives (`#angle 30`, `#seed 4` ...): interpretation settings into
/// `target`, program-wide ones into the program.
void compileDirectives(CompileContext& ctx, const std::vector<ast::Setting>& list, InterpretSettings& target,
                       const Scope& scope);

// ---- lang/compile_systems.cpp: systems, pools, axioms, placements, symbol classes ----

/// A system's label and state, as a cell that stands for it in its parents' pools.
void declareSystemCells(CompileContext& ctx);
/// A system's definition, scope, directives, functions and pool.
void declareSystem(CompileContext& ctx, const ast::System& system, int index);
/// Its productions, axiom, interpretation blocks and placements.
void compileSystem(CompileContext& ctx, const ast::System& system, int index);
/// Per system, the class of every master (brackets, ignored symbols), once every master exists.
void classifySymbols(CompileContext& ctx);

// ---- lang/compile_scales.cpp: multiscale L-systems ----

/// The scales of each L-system with `scale N:` lines, given to its rules with a context;
/// contexts the multiscale matching does not cover are errors at their place.
void compileScales(CompileContext& ctx);

// ---- lang/compile_rules.cpp: cells, rules, productions ----

/// The declared cells' masters: state, defaults, lifetime.
void declareCells(CompileContext& ctx);
/// Their rules and interpretation blocks.
void compileCells(CompileContext& ctx);
/// An L-system's productions, as terminal rules of its symbols.
void compileProductions(CompileContext& ctx, const ast::System& system, Scope& scope, int index);

// ---- lang/compile_interpretation.cpp: interpretation blocks ----

/// One `interpret SET { ... }` block of a master; `params` and `scope`, when given, name
/// its state and resolve its names (an L-system's `interpret SET X(a) { ... }`).
void compileInterpretation(CompileContext& ctx, const ast::Interpretation& block, int master,
                           const std::vector<std::string>* params = nullptr, const Scope* scope = nullptr);
/// An L-system's `interpret SET X(a) { ... }` blocks.
void compileSymbolInterpretations(CompileContext& ctx, const ast::System& system, const Scope& scope, int index);
/// The instruction each master stands for (its label, or the command an equiv names).
void resolveCommands(CompileContext& ctx);

// ---- lang/program_checks.cpp: the whole program, once every master exists ----

/// Each system's engine flags (terminal context, randomness, per-step rules, rates) and
/// the checks that its cells' rules fit its pool.
void summariseSystems(CompileContext& ctx);
/// The system tree: no system contains itself; the root (CompileOptions::rootSystem or
/// the first system no other contains); every `parent.x` read reaches systems with x.
void checkSystemTree(CompileContext& ctx);

// ---- lang/letter_runs.cpp: ABOP's strings written without #letters ----

/// Warns at a successor or axiom module such as `FF` whose label nothing defines while
/// each of its letters is a symbol of its block: ABOP's `FF`, meant as two modules.
void warnLetterRuns(CompileContext& ctx);

}  // namespace ontogen::detail
