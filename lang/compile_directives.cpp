// A block's directives, read through the directive table (lang/directives.h): each
// value is evaluated as a constant in the block's scope, checked against its row's
// range, and applied by its row to the block's interpretation settings or to the
// program. #define is a constant (lang/compile_functions.cpp).

#include <cmath>
#include <filesystem>
#include <string>

#include "lang/compile_stages.h"
#include "lang/directives.h"
#include "lang/expression_compiler.h"

namespace ontogen::detail {

namespace {

bool takesExpression(DirectiveKind kind) {
  return kind == DirectiveKind::Number || kind == DirectiveKind::Integer || kind == DirectiveKind::NumberedFile ||
         kind == DirectiveKind::NumberedName;
}

// A file is read relative to the directory of the program that names it; its location
// goes with it, for the errors of loading it before the run.
void placeFile(const ast::Setting& setting, DirectiveValue& value) {
  value.path = setting.word;
  if (!setting.span.valid()) return;
  const std::filesystem::path base = std::filesystem::path(setting.span.file->name()).parent_path();
  if (std::filesystem::path(value.path).is_relative()) value.path = (base / value.path).lexically_normal().string();
  value.location = setting.span.file->name() + ":" + std::to_string(setting.span.line()) + ":" +
                   std::to_string(setting.span.column());
}

// The set that owns a file directive checks the file, if the caller gave the sets.
std::string checkFile(const CompileContext& ctx, const Directive& directive, const std::string& path) {
  for (const CommandSetInfo& set : ctx.options.commandSets)
    if (set.name == directiveOwnerName(directive.owner) && set.checkFile) return set.checkFile(path);
  return {};
}

// `#range NAME LOW HIGH` names a #define of its block (or, in a block, a top-level one it
// sees) and a range with room in it; it sets nothing, the variation operators read it.
void checkRange(CompileContext& ctx, const ast::Setting& setting, const Scope& scope) {
  const std::string& name = setting.word;
  if (!std::isfinite(setting.low) || !std::isfinite(setting.high) || !(setting.low < setting.high))
    ctx.sink.error(setting.span, "#range " + name + " needs finite numbers LOW < HIGH");
  if (!scope.constants.values.count(name) && !ctx.global.constants.values.count(name))
    ctx.sink.error(setting.span, "#range names '" + name + "', which is no #define of its block or of the top level");
}

}  // namespace

void compileDirectives(CompileContext& ctx, const std::vector<ast::Setting>& list, InterpretSettings& target,
                       const Scope& scope) {
  DirectiveTarget into{target, *ctx.program};
  for (const auto& setting : list) {
    const Directive& directive = *setting.directive;
    if (directive.kind == DirectiveKind::Range) {
      checkRange(ctx, setting, scope);
      continue;
    }
    DirectiveValue value;
    value.word = setting.word;
    value.numerator = setting.numerator;
    value.denominator = setting.denominator;
    if (directive.kind == DirectiveKind::NumberedName) value.name = setting.word;
    if (takesExpression(directive.kind)) {
      auto number =
          evaluateConstant(*setting.value, ctx.constantLookup(scope), ctx.sink, "#" + std::string(directive.name));
      if (!number) continue;
      if (!directive.accepts(*number)) {
        ctx.sink.error(setting.span, std::string(directive.rangeError));
        continue;
      }
      value.number = *number;
    }
    if (directive.kind == DirectiveKind::NumberedFile) {
      placeFile(setting, value);
      if (std::string problem = checkFile(ctx, directive, value.path); !problem.empty()) {
        ctx.sink.error(setting.span, problem);
        continue;
      }
    }
    directive.apply(value, into);
  }
}

}  // namespace ontogen::detail
