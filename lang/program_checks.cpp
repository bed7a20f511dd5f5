// The passes over the whole program once every master exists: what each system's engine
// needs to know and whether its cells' rules fit its pool; then the system tree (no
// system contains itself), the root, and the reads of enclosing systems it makes
// possible.

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "lang/compile_stages.h"
#include "lang/system_tree.h"

namespace ontogen::detail {

namespace {

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

// Systems nest at most kMaxSystemDepth deep; the message names the chain's two ends.
void checkDepth(CompileContext& ctx, const SystemTree& tree) {
  const SystemTree::Depths depths = tree.depths();
  const auto deepest = std::max_element(depths.depth.begin(), depths.depth.end());
  if (deepest == depths.depth.end() || *deepest <= kMaxSystemDepth) return;
  int s = static_cast<int>(deepest - depths.depth.begin());
  // The first system of the chain past the limit is where the text goes too deep.
  while (depths.depth[s] > kMaxSystemDepth + 1) s = depths.above[s];
  int top = s;
  while (depths.above[top] >= 0) top = depths.above[top];
  const auto& systems = ctx.program->systems;
  ctx.sink.error(systems[s].span, "system '" + systems[s].name + "' is nested " + std::to_string(depths.depth[s]) +
                                      " deep (under '" + systems[top].name + "'), past the limit of " +
                                      std::to_string(kMaxSystemDepth) + " nested systems");
}

}  // namespace

// What each system's engine needs to know of the cells its pool can hold (terminal
// rules reading context, randomness, per-step rules, rates), and whether their rules
// fit the pool.
void summariseSystems(CompileContext& ctx) {
  for (size_t s = 0; s < ctx.program->systems.size(); ++s) {
    SystemDefinition& definition = ctx.program->systems[s];
    // The masters its pool can hold: its axiom and placements, and every successor of
    // their rules, transitively.
    std::vector<bool> grows = SystemTree::reachableMasters(*ctx.program, definition);
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

void checkSystemTree(CompileContext& ctx) {
  if (ctx.sink.hasErrors()) {
    // No tree to trust, but the root's own errors (no system at all, an unknown
    // --system) still belong in the report.
    chooseRoot(ctx, SystemTree(*ctx.program));
    return;
  }
  SystemTree tree(*ctx.program);
  if (!checkCycles(ctx, tree)) return;
  checkDepth(ctx, tree);
  for (size_t s = 0; s < ctx.program->systems.size(); ++s)
    if (!tree.containers(static_cast<int>(s)).empty()) ctx.program->hasSystemCells = true;
  chooseRoot(ctx, tree);
  // With no system there is no root for `root.x` to read (chooseRoot said so).
  if (ctx.program->systems.empty()) return;
  checkAncestorReads(ctx, tree);
}

}  // namespace ontogen::detail
