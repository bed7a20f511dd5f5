#pragma once

#include <functional>
#include <optional>
#include <string_view>

#include "lang/ast.h"
#include "model/diagnostics.h"
#include "model/expression.h"
#include "model/source.h"

namespace ontogen {

/// How the expression compiler resolves names; the rule or block being compiled supplies it.
struct NameLookup {
  /// Frame slot of a name, or -1.
  std::function<int(std::string_view)> slot;
  /// Value of a named constant (#define, pi, true ...), if the name is one.
  std::function<std::optional<double>(std::string_view)> constant;
  /// Index of a user function (development function), or -1.
  std::function<int(std::string_view)> function;
  /// Arity of a user function.
  std::function<int(int)> functionArity;
  /// Registers a neighbour aggregate call (`count(A)`, `sum(x)`, `mean(A.x)` ...) and
  /// returns its index, or -1 after reporting why it is wrong. Absent where aggregates
  /// cannot be read (outside rules). Called again for the same call: same index, no report.
  std::function<int(const ast::Expr& call, DiagnosticSink& sink)> aggregate;
  /// Registers a read of the enclosing systems' state (`parent.x`, `parent.parent.age`,
  /// `root.x`) and returns its index in Program::ancestorRefs. Absent where no system
  /// encloses the expression (constants, axioms).
  std::function<int(const std::string& path, SourceSpan span)> ancestor;
  /// Extra advice for an unknown name (e.g. "declare it as a state variable"), may be empty.
  std::function<std::string(std::string_view)> unknownHint;
};

/// True for a call that names a neighbour aggregate: count(), count(A), sum(x), mean(x),
/// and min(x) / max(x) with one argument (with two they are the ordinary functions).
bool isAggregateCall(const ast::Expr& call);

/// The text of `a.b` or `a.b.c` (`me.x`, `parent.length`, `parent.parent.age`), or ""
/// for other shapes.
std::string memberPath(const ast::Expr& member);

/// Compiles one expression: resolves names, checks calls and folds constants. Reports
/// errors to the sink and returns an empty expression if there were any.
CompiledExpression compileExpression(const ast::Expr& expr, const NameLookup& names, DiagnosticSink& sink);

/// Evaluates an expression that must be constant (a #define, a terminal age). Reports
/// `what` in the error when it is not.
std::optional<double> evaluateConstant(const ast::Expr& expr, const NameLookup& names, DiagnosticSink& sink,
                                       std::string_view what);

}  // namespace ontogen
