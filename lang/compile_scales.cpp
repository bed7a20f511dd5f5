// L-Py's multiscale modules in an L-system block: `scale N: A B` lines give labels a
// scale, and the block's contexts then match as a multiscale tree (docs/LANGUAGE.md 4.8,
// core/multiscale_context.h). The matching covers contexts of modules, with `[` and `]`
// on the right; what it does not cover is refused at its place rather than matched
// otherwise than L-Py would.

#include <map>
#include <string>

#include "lang/compile_context.h"
#include "lang/compile_stages.h"

namespace ontogen::detail {

namespace {

constexpr const char* kCovered =
    " in a multiscale L-system (one with 'scale N:' or 'level N:' lines): its contexts '<', '<<' and '>' hold "
    "modules, and '[' ']' on the right";

void checkSide(CompileContext& ctx, const std::vector<ast::Module>& side, bool left) {
  for (const ast::Module& module : side) {
    if (!module.alternatives.empty())
      ctx.sink.error(module.span, std::string("alternatives '( | )'") + kCovered);
    else if (module.label == "*")
      ctx.sink.error(module.span, std::string("the wildcard '*'") + kCovered);
    else if (module.label == "∅")
      ctx.sink.error(module.span, std::string("'∅' (nothing)") + kCovered);
    else if (left && module.label == "[")
      ctx.sink.error(module.span, std::string("'[' in a left context") + kCovered);
  }
}

void checkRules(CompileContext& ctx, const ast::System& system) {
  for (const ast::Rule& rule : system.productions) {
    checkSide(ctx, rule.left, true);
    checkSide(ctx, rule.right, false);
    checkSide(ctx, rule.newLeft, true);
    if (!rule.newRight.empty()) ctx.sink.error(rule.newRightSpan, std::string("a new right context '>>'") + kCovered);
  }
}

void attach(std::vector<CompiledRule>& rules, const std::shared_ptr<const ScaleTable>& scales) {
  for (CompiledRule& rule : rules)
    if (rule.hasContext()) rule.scales = scales;
}

}  // namespace

void compileScales(CompileContext& ctx) {
  for (size_t index = 0; index < ctx.tree.systems.size(); ++index) {
    const ast::System& system = ctx.tree.systems[index];
    if (!system.isLSystem || system.scales.empty()) continue;
    std::map<std::string, const ast::ScaleLine*> scaleOf;
    for (const ast::ScaleLine& line : system.scales)
      for (size_t k = 0; k < line.symbols.size(); ++k) {
        const auto [at, added] = scaleOf.emplace(line.symbols[k], &line);
        if (!added)
          ctx.sink.error(line.symbolSpans[k], "'" + line.symbols[k] + "' already has a scale (" +
                                                  std::to_string(at->second->scale) + ", at line " +
                                                  std::to_string(at->second->span.line()) + ")");
      }
    checkRules(ctx, system);
    for (const ast::ScaleLine& line : system.scales)
      if (line.levels != system.scales.front().levels)
        ctx.sink.error(line.span, std::string("a block gives its modules scales ('scale N:') or levels ('level N:'), "
                                              "not both; the line at ") +
                                      std::to_string(system.scales.front().span.line()) + " gives " +
                                      (system.scales.front().levels ? "levels" : "scales"));
    auto scales = std::make_shared<ScaleTable>();
    scales->levels = system.scales.front().levels;
    scales->of.assign(ctx.program->masters.size(), kUnscaled);
    for (size_t m = 0; m < ctx.program->masters.size(); ++m) {
      const MasterCell& master = ctx.program->masters[m];
      const auto found = scaleOf.find(master.label);
      if (found != scaleOf.end() && master.symbolClass == kSymbolModule) scales->of[m] = found->second->scale;
    }
    for (MasterCell& master : ctx.program->masters) {
      if (master.scope != static_cast<int>(index)) continue;
      attach(master.terminalRules, scales);
      attach(master.decompositionRules, scales);
      attach(master.homomorphismRules, scales);
    }
  }
}

}  // namespace ontogen::detail
