// Constants, equivs and development functions: what a scope names. A block's #defines
// (with the values given from outside, CompileOptions::defines), its `equiv`s and its
// functions `g mov(tau, beta) = ...`, and which symbols the functions develop.

#include <cmath>
#include <functional>
#include <map>
#include <set>
#include <string>

#include "model/builtins.h"
#include "lang/compile_stages.h"
#include "lang/expression_compiler.h"
#include "model/message_number.h"

namespace ontogen::detail {

namespace {

// A development function that calls itself, directly or not, would never return.
void checkRecursion(CompileContext& ctx) {
  size_t count = ctx.program->functions.size();
  std::vector<int> state(count, 0);  // 0 new, 1 on the path, 2 done
  std::function<bool(size_t)> visit = [&](size_t f) -> bool {
    if (state[f] == 1) return true;
    if (state[f] == 2) return false;
    state[f] = 1;
    for (int call : ctx.program->functionBodies[f].calledFunctions())
      if (visit(static_cast<size_t>(call))) {
        if (state[f] == 1 && !ctx.reportedRecursion.count(f)) {
          ctx.reportedRecursion.insert(f);
          ctx.sink.error(ctx.program->functions[f].span, "development function '" + ctx.program->functions[f].name +
                                                             "' calls itself; it would never end");
        }
        state[f] = 2;
        return true;
      }
    state[f] = 2;
    return false;
  };
  for (size_t f = 0; f < count; ++f) visit(f);
}

}  // namespace

namespace {
// Whether `expr` names an infinity (`inf`, or a constant that is one) or writes a number
// that is one: an infinite value it makes otherwise overflowed (`1e308 * 10`, `1 / 0`).
bool readsInfinity(CompileContext& ctx, const ast::Expr& expr, Scope& scope) {
  if (expr.kind == ast::Expr::Kind::Number) return std::isinf(expr.number);
  if (expr.kind == ast::Expr::Kind::Name) {
    DiagnosticSink quiet;  // its errors are the define's own, reported once
    const std::optional<double> value = evaluateConstant(expr, ctx.constantLookup(scope), quiet, "a name");
    return value && std::isinf(*value);
  }
  for (const ast::ExprPtr& arg : expr.args)
    if (arg && readsInfinity(ctx, *arg, scope)) return true;
  return false;
}
}  // namespace

// `system`: index of the block holding the list, -1 for the top level.
void compileDefines(CompileContext& ctx, const std::vector<ast::Define>& list, Scope& scope, int system) {
  for (const auto& define : list) {
    auto given = ctx.overrides.find(define.name);
    if (given != ctx.overrides.end()) ctx.overridden.insert(define.name);
    if (scope.constants.values.count(define.name)) {
      ctx.sink.error(define.span, "'" + define.name + "' is defined twice");
      continue;
    }
    if (findConstant(define.name) || findBuiltin(define.name)) {
      ctx.sink.error(define.span, "'" + define.name + "' is a built-in name and cannot be redefined");
      continue;
    }
    // A value from outside replaces the text's, which is then not evaluated at all.
    std::optional<double> value;
    if (given != ctx.overrides.end())
      value = given->second;
    else
      value = evaluateConstant(*define.value, ctx.constantLookup(scope), ctx.sink, "the value of #define");
    if (!value) continue;
    // `inf` is a constant a define may name (a lifetime that never ends), but NaN is
    // no value anything can use. Kept even so: its uses would each be an unknown name.
    if (std::isnan(*value)) ctx.sink.error(define.span, "the value of #define " + define.name + " is not a number (NaN)");
    else if (std::isinf(*value) && given == ctx.overrides.end() && !readsInfinity(ctx, *define.value, scope))
      ctx.sink.error(define.value->span, "the value of #define " + define.name +
                                             " overflows to an infinity (past ±1.8e308); write inf if an infinity is meant");
    scope.constants.values[define.name] = *value;
    ctx.program->defines.push_back({define.name, *value, system, given != ctx.overrides.end(), define.span});
  }
}

// The values given from outside, the last of each name (as later flags win on a
// command line). A value that is not finite is reported and left out, so the text's
// value stands and no error follows from it.
void takeDefineOverrides(CompileContext& ctx) {
  for (const DefineOverride& define : ctx.options.defines) ctx.overrides[define.name] = define.value;
  for (auto it = ctx.overrides.begin(); it != ctx.overrides.end();) {
    if (std::isfinite(it->second)) {
      ++it;
      continue;
    }
    ctx.sink.error(SourceSpan{}, "cannot set '" + it->first + "' to " + messageNumber(it->second) +
                                     ": a value for a #define must be a finite number");
    it = ctx.overrides.erase(it);
  }
}

// Every value given from outside must name a #define of the program.
void checkDefineOverrides(CompileContext& ctx) {
  std::string known;
  std::set<std::string_view> listed;
  for (const ProgramDefine& define : ctx.program->defines)
    if (listed.insert(define.name).second) known += (known.empty() ? "" : ", ") + define.name;
  std::set<std::string_view> reported;
  for (const DefineOverride& given : ctx.options.defines) {
    const std::string& name = given.name;
    if (!ctx.overrides.count(name) || ctx.overridden.count(name) || !reported.insert(name).second) continue;
    ctx.sink.error(SourceSpan{}, "cannot set '" + name + "': the program has no #define " + name +
                                     (known.empty() ? " (it has no #define)" : " (it defines " + known + ")"));
  }
}

void compileEquivs(CompileContext& ctx, const std::vector<ast::Equiv>& list, Scope& scope) {
  for (const auto& equiv : list) {
    if (scope.equivs.count(equiv.symbol)) {
      ctx.sink.error(equiv.span, "'" + equiv.symbol + "' already has an equiv");
      continue;
    }
    scope.equivs[equiv.symbol] = equiv.command;
  }
}

void compileFunctions(CompileContext& ctx, const std::vector<ast::DevelopmentFunction>& list, Scope& scope) {
  // Declare first so that functions can call each other in any order.
  std::vector<int> indices;
  for (const auto& function : list) {
    if (scope.functions.count(function.name)) {
      ctx.sink.error(function.span, "development function '" + function.name + "' is defined twice");
      indices.push_back(-1);
      continue;
    }
    if (findBuiltin(function.name)) {
      ctx.sink.error(function.span, "'" + function.name + "' is a built-in function and cannot be redefined");
      indices.push_back(-1);
      continue;
    }
    DevelopmentFunction definition;
    definition.name = function.name;
    definition.arity = static_cast<int>(function.params.size());
    definition.span = function.span;
    int moduleParam = 0;
    for (const auto& param : function.params) {
      if (isAgeName(param.name))
        definition.sources.push_back(DevelopmentFunction::kFromAge);
      else if (isTerminalAgeName(param.name))
        definition.sources.push_back(DevelopmentFunction::kFromTerminalAge);
      else
        definition.sources.push_back(moduleParam++);
    }
    int index = static_cast<int>(ctx.program->functions.size());
    ctx.program->functions.push_back(std::move(definition));
    ctx.program->functionBodies.emplace_back();
    scope.functions[function.name] = index;
    indices.push_back(index);
  }
  for (size_t i = 0; i < list.size(); ++i) {
    if (indices[i] < 0) continue;
    const auto& function = list[i];
    std::map<std::string, int, std::less<>> slots;
    for (size_t p = 0; p < function.params.size(); ++p) {
      if (slots.count(function.params[p].name))
        ctx.sink.error(function.params[p].span, "parameter '" + function.params[p].name + "' appears twice");
      slots[function.params[p].name] = static_cast<int>(p);
    }
    NameLookup names = ctx.constantLookup(scope);
    names.slot = [&slots](std::string_view name) {
      auto it = slots.find(name);
      return it == slots.end() ? -1 : it->second;
    };
    ctx.addFunctions(names, scope);
    names.unknownHint = [](std::string_view name) -> std::string {
      if (isAgeName(name) || isTerminalAgeName(name))
        return "list it among the function's parameters, as in 'g mov(tau, beta) = ...'";
      return {};
    };
    ctx.program->functionBodies[indices[i]] = compileExpression(*function.body, names, ctx.sink);
  }
  checkRecursion(ctx);
}

// A development function named after a symbol develops it: an L-system's functions
// its own symbols, top-level functions the program's cells and symbols. Functions
// named after no symbol are helpers that others call.
void attachDevelopmentFunctions(CompileContext& ctx) {
  for (size_t m = 0; m < ctx.program->masters.size(); ++m) {
    MasterCell& master = ctx.program->masters[m];
    const Scope& scope = master.scope >= 0 ? *ctx.scopes[master.scope] : ctx.global;
    int functionIndex = scope.findFunction(master.label);
    if (functionIndex < 0) continue;
    const DevelopmentFunction& definition = ctx.program->functions[functionIndex];
    int moduleParams = 0;
    for (int source : definition.sources) moduleParams += source >= 0;
    if (moduleParams > static_cast<int>(master.stateCount())) {
      // A label with several numbers of parameters (L-systems): the function develops
      // those modules that have the parameters it names.
      bool fitsAnother = false;
      for (const MasterCell& other : ctx.program->masters)
        fitsAnother = fitsAnother || (other.label == master.label && other.scope == master.scope &&
                                      static_cast<int>(other.stateCount()) >= moduleParams);
      if (fitsAnother) continue;
      ctx.sink.error(definition.span, "development function '" + definition.name + "' names " +
                                          std::to_string(moduleParams) + " module parameters, but '" + master.label +
                                          "' has " + std::to_string(master.stateCount()));
      continue;
    }
    master.developmentFunction = functionIndex;
  }
}

}  // namespace ontogen::detail
