// The driver: one CompileContext, the stages of lang/compile_stages.h in order.

#include "lang/compiler.h"

#include "lang/compile_context.h"
#include "lang/compile_stages.h"
#include "lang/imports.h"
#include "lang/parser.h"
#include "lang/system_tree.h"

namespace ontogen {

namespace detail {

namespace {

std::unique_ptr<Program> run(CompileContext& ctx, std::vector<std::shared_ptr<const SourceFile>> sources) {
  for (auto& source : sources) {
    ctx.sink.retain(source);
    ctx.program->sources.push_back(std::move(source));
  }
  // The top level first: its constants, equivs, directives and functions are every block's.
  takeDefineOverrides(ctx);
  compileDefines(ctx, ctx.tree.defines, ctx.global, -1);
  compileEquivs(ctx, ctx.tree.equivs, ctx.global);
  compileDirectives(ctx, ctx.tree.settings, ctx.globalSettings, ctx.global);
  compileFunctions(ctx, ctx.tree.functions, ctx.global);
  // Before the passes whose cost grows with the square of the systems.
  if (ctx.tree.systems.size() > kMaxSystems) {
    const ast::System& first = ctx.tree.systems[kMaxSystems];
    ctx.sink.error(first.nameSpan, "system '" + first.name + "' is one too many: a program has at most " +
                                       std::to_string(kMaxSystems) + " systems");
    return nullptr;
  }
  // Every master a declaration makes, before any rule names one.
  declareCells(ctx);
  declareSystemCells(ctx);
  for (size_t i = 0; i < ctx.tree.systems.size(); ++i) declareSystem(ctx, ctx.tree.systems[i], static_cast<int>(i));
  checkDefineOverrides(ctx);  // every block's #defines are known now
  // Rules, axioms, placements and interpretation blocks; they may add implicit masters.
  compileCells(ctx);
  for (size_t i = 0; i < ctx.tree.systems.size(); ++i) compileSystem(ctx, ctx.tree.systems[i], static_cast<int>(i));
  // Every master exists.
  attachDevelopmentFunctions(ctx);
  resolveCommands(ctx);
  warnLetterRuns(ctx);
  classifySymbols(ctx);
  compileScales(ctx);
  summariseSystems(ctx);
  checkSystemTree(ctx);
  if (ctx.sink.hasErrors()) return nullptr;
  return std::move(ctx.program);
}

}  // namespace

}  // namespace detail

std::unique_ptr<Program> compile(const ast::Program& tree, std::shared_ptr<const SourceFile> source,
                                 DiagnosticSink& sink, const CompileOptions& options) {
  detail::CompileContext ctx(tree, sink, options);
  return detail::run(ctx, {std::move(source)});
}

std::unique_ptr<Program> compile(const ast::Program& tree, std::vector<std::shared_ptr<const SourceFile>> sources,
                                 DiagnosticSink& sink, const CompileOptions& options) {
  detail::CompileContext ctx(tree, sink, options);
  return detail::run(ctx, std::move(sources));
}

std::unique_ptr<Program> compileSource(std::string name, std::string text, DiagnosticSink& sink,
                                       const CompileOptions& options) {
  auto source = std::make_shared<const SourceFile>(std::move(name), std::move(text));
  ParsedProgram parsed = parseWithImports(std::move(source), sink, options.maxSourceBytes);
  if (sink.hasErrors()) return nullptr;
  return compile(parsed.tree, std::move(parsed.sources), sink, options);
}

}  // namespace ontogen
