#include "lang/compiler.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <set>

#include "lang/compile_context.h"
#include "lang/compile_stages.h"
#include "lang/expression_compiler.h"
#include "lang/imports.h"
#include "lang/parser.h"
#include "lang/system_tree.h"

namespace ontogen {

namespace detail {

// Helpers of the stages, until each stage has a file of its own.
void classifySymbols(CompileContext& ctx);
void summariseSystems(CompileContext& ctx);
std::vector<bool> reachable(const CompileContext& ctx, const SystemDefinition& system);
bool visibleIn(const MasterCell& master, int system);
bool checkCycles(CompileContext& ctx, const SystemTree& tree);
void chooseRoot(CompileContext& ctx, const SystemTree& tree);
void checkAncestorReads(CompileContext& ctx, const SystemTree& tree);

// Per system, the class of every master: branch brackets, and the symbols its
// `ignore:` or `consider:` list leaves out of context matching.
void classifySymbols(CompileContext& ctx) {
  for (auto& [index, system] : ctx.ignoreLists) {
    SystemDefinition& definition = ctx.program->systems[index];
    definition.symbolClass.resize(ctx.program->masters.size());
    for (size_t m = 0; m < ctx.program->masters.size(); ++m)
      definition.symbolClass[m] = ctx.program->masters[m].symbolClass;
    if (!system->ignore.empty() && !system->consider.empty())
      ctx.sink.error(system->consider.front().span, "a system has either 'ignore' or 'consider', not both");
    std::set<std::string> listed;
    for (const auto& list : system->ignore) listed.insert(list.symbols.begin(), list.symbols.end());
    for (const auto& list : system->consider) listed.insert(list.symbols.begin(), list.symbols.end());
    bool consider = !system->consider.empty();
    if (listed.empty()) continue;
    for (size_t m = 0; m < ctx.program->masters.size(); ++m) {
      const MasterCell& master = ctx.program->masters[m];
      if (master.symbolClass != kSymbolModule) continue;
      bool inList = listed.count(master.label) > 0;
      if (inList != consider) definition.symbolClass[m] |= kSymbolIgnored;
    }
  }
}

// What each system's engine needs to know of the cells its pool can hold (terminal
// rules reading context, randomness, per-step rules, rates), and whether their rules
// fit the pool.
void summariseSystems(CompileContext& ctx) {
  for (size_t s = 0; s < ctx.program->systems.size(); ++s) {
    SystemDefinition& definition = ctx.program->systems[s];
    std::vector<bool> grows = reachable(ctx, definition);
    for (size_t m = 0; m < ctx.program->masters.size(); ++m) {
      const MasterCell& master = ctx.program->masters[m];
      if (!visibleIn(master, static_cast<int>(s))) continue;
      for (const auto& rule : master.terminalRules) {
        if (rule.hasContext() || !rule.aggregates.empty()) definition.terminalContext = true;
        if (rule.probability.empty() == false) definition.stochastic = true;
      }
      for (const auto& rule : master.rules)
        if (rule.hasDiscrete || (!rule.hasRate && !rule.hasAction)) definition.sampledRules = true;
      for (const auto& rule : master.rules) {
        if (rule.hasRate) definition.rates = true;
        if (definition.poolKind == PoolKind::Spatial && grows[m] && rule.hasContext())
          ctx.sink.error(rule.span, "a positional context ('A me B') does not fit the spatial pool of system '" +
                                        definition.name +
                                        "', where neighbours are the cells within a distance; read "
                                        "them with count(), sum(x), mean(x), min(x) or max(x)");
        const int poolDimensions =
            definition.poolKind == PoolKind::Grid ? static_cast<int>(definition.grid.dimensions) : 1;
        if (definition.poolKind != PoolKind::Spatial && grows[m] && rule.hasContext() &&
            rule.contextDimensions != poolDimensions)
          ctx.sink.error(rule.span,
                         "this context has " + std::to_string(rule.contextDimensions) + " dimension" +
                             (rule.contextDimensions == 1 ? " ('A me B')" : "s") + ", but the pool of system '" +
                             definition.name + "' is " +
                             (definition.poolKind == PoolKind::Grid ? "a " + std::to_string(poolDimensions) + "-D grid"
                                                                    : std::string("linear")) +
                             "; match its dimensions (parentheses mark them: '(A) (B me C) (D)' is 2-D) or read the "
                             "neighbours with count(), sum(x), mean(x), min(x) or max(x)");
      }
      if (definition.poolKind != PoolKind::Linear && grows[m] && !master.terminalRules.empty())
        ctx.sink.error(master.terminalRules.front().span,
                       "terminal rules (lifetimes) in a " + std::string(poolKindName(definition.poolKind)) +
                           " pool are not available in this version; use a per-step rule with 'age > ...'");
    }
  }
}

// The masters a system's pool can hold: its axiom and placements, and every successor
// of their rules, transitively.
std::vector<bool> reachable(const CompileContext& ctx, const SystemDefinition& system) {
  return SystemTree::reachableMasters(*ctx.program, system);
}

bool visibleIn(const MasterCell& master, int system) {
  return master.scope == -1 || master.scope == system;
}

// A system that contains itself, directly or through others, is rejected: the
// hierarchy is a tree (paper 002, section 2.2).
bool checkCycles(CompileContext& ctx, const SystemTree& tree) {
  std::vector<int> cycle = tree.findCycle();
  if (cycle.empty()) return true;
  std::string path;
  for (int s : cycle) path += (path.empty() ? "" : " contains ") + ("'" + ctx.program->systems[s].name + "'");
  ctx.sink.error(ctx.program->systems[cycle.front()].span, "system '" + ctx.program->systems[cycle.front()].name +
                                                               "' contains itself: " + path +
                                                               "; the systems must form a tree");
  return false;
}

// The root is the system named by --system, else the first one no other system contains.
void chooseRoot(CompileContext& ctx, const SystemTree& tree) {
  if (ctx.program->systems.empty()) {
    ctx.sink.error(SourceSpan{ctx.program->sources.front().get(), 0, 0},
                   "the program defines no system or lsystem to grow");
    return;
  }
  ctx.program->root = 0;
  for (size_t i = 0; i < ctx.program->systems.size(); ++i)
    if (tree.containers(static_cast<int>(i)).empty()) {
      ctx.program->root = static_cast<int>(i);
      break;
    }
  if (!ctx.options.rootSystem.empty()) {
    for (size_t i = 0; i < ctx.program->systems.size(); ++i)
      if (ctx.program->systems[i].name == ctx.options.rootSystem) {
        ctx.program->root = static_cast<int>(i);
        return;
      }
    std::string known;
    for (const auto& system : ctx.program->systems) known += (known.empty() ? "" : ", ") + system.name;
    ctx.sink.error(SourceSpan{}, "no system named '" + ctx.options.rootSystem + "' (the program has: " + known + ")");
  }
}

// Every system a `parent...x` read can reach must have x (or it is `age`); a read past
// the root is an error.
void checkAncestorReads(CompileContext& ctx, const SystemTree& tree) {
  for (const AncestorRead& read : ctx.ancestorReads) {
    std::set<int> level;
    if (read.reader.system >= 0)
      level.insert(read.reader.system);
    else
      for (int s : tree.systemsHolding(read.reader.master)) level.insert(s);
    if (read.ref.level == 0) level = {ctx.program->root};
    for (int k = 1; k < read.ref.level && !level.empty(); ++k) {
      std::set<int> up;
      for (int s : level) {
        std::vector<int> containers = tree.containers(s);
        if (containers.empty() && s == ctx.program->root) {
          ctx.sink.error(read.span, "'" + read.path + "' goes above the root system '" + ctx.program->systems[s].name +
                                        "', which has no parent");
          up.clear();
          break;
        }
        up.insert(containers.begin(), containers.end());
      }
      level = std::move(up);
    }
    for (int s : level) {
      if (read.ref.name == "age") continue;
      const SystemDefinition& system = ctx.program->systems[s];
      const MasterCell* master = system.master >= 0 ? &ctx.program->masters[system.master] : nullptr;
      bool has = master && std::find(master->stateNames.begin(), master->stateNames.end(), read.ref.name) !=
                               master->stateNames.end();
      if (has) continue;
      std::string known = "age";
      if (master)
        for (const auto& name : master->stateNames) known += ", " + name;
      ctx.sink.error(read.span, "'" + read.path + "' reads system '" + system.name + "', which has no state '" +
                                    read.ref.name + "' (it has: " + known + ")");
      break;
    }
  }
}

namespace {

std::unique_ptr<Program> run(CompileContext& ctx, std::vector<std::shared_ptr<const SourceFile>> sources) {
  for (auto& source : sources) {
    ctx.sink.retain(source);
    ctx.program->sources.push_back(std::move(source));
  }
  ctx.global.system = -1;
  takeDefineOverrides(ctx);
  compileDefines(ctx, ctx.tree.defines, ctx.global, -1);
  compileEquivs(ctx, ctx.tree.equivs, ctx.global);
  compileDirectives(ctx, ctx.tree.settings, ctx.globalSettings, ctx.global);
  compileFunctions(ctx, ctx.tree.functions, ctx.global);
  declareCells(ctx);
  declareSystemCells(ctx);
  for (size_t i = 0; i < ctx.tree.systems.size(); ++i) declareSystem(ctx, ctx.tree.systems[i], static_cast<int>(i));
  checkDefineOverrides(ctx);
  compileCells(ctx);
  for (size_t i = 0; i < ctx.tree.systems.size(); ++i) compileSystem(ctx, ctx.tree.systems[i], static_cast<int>(i));
  attachDevelopmentFunctions(ctx);
  resolveCommands(ctx);
  classifySymbols(ctx);
  summariseSystems(ctx);
  if (!ctx.sink.hasErrors()) {
    SystemTree tree(*ctx.program);
    if (checkCycles(ctx, tree)) {
      for (size_t s = 0; s < ctx.program->systems.size(); ++s)
        if (!tree.containers(static_cast<int>(s)).empty()) ctx.program->hasSystemCells = true;
      chooseRoot(ctx, tree);
      checkAncestorReads(ctx, tree);
    }
  } else {
    chooseRoot(ctx, SystemTree(*ctx.program));
  }
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
  ParsedProgram parsed = parseWithImports(std::move(source), sink);
  if (sink.hasErrors()) return nullptr;
  return compile(parsed.tree, std::move(parsed.sources), sink, options);
}

}  // namespace ontogen
