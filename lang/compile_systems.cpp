// Systems: each block's definition and scope, its pool (linear, grid, spatial), its
// axiom and, in a grid, its placements. A system that is not an L-system is also a
// cell, whose label and state stand for it in the pools of the systems containing it.

#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <string>

#include "lang/compile_stages.h"
#include "lang/expression_compiler.h"
#include "model/message_number.h"

namespace ontogen::detail {

namespace {

// `pool grid(nx [, ny [, nz]]) [wrap | clamp | closed] [vonneumann | moore]`
void gridShape(CompileContext& ctx, const ast::System& system, const Scope& scope, SystemDefinition& definition) {
  GridShape& shape = definition.grid;
  if (system.poolArgs.empty() || system.poolArgs.size() > 3) {
    ctx.sink.error(system.poolSpan, "a grid has 1 to 3 sizes, as in 'pool grid(64, 64)'");
    return;
  }
  shape.dimensions = static_cast<int>(system.poolArgs.size());
  uint64_t sites = 1;
  for (size_t axis = 0; axis < system.poolArgs.size(); ++axis) {
    auto value = evaluateConstant(*system.poolArgs[axis], ctx.constantLookup(scope), ctx.sink, "a grid size");
    if (!value) return;
    if (!(*value >= 1) || *value != std::floor(*value) || *value > 1e9) {
      ctx.sink.error(system.poolArgs[axis]->span, "a grid size is a whole number ≥ 1, not " + messageNumber(*value));
      return;
    }
    shape.size[axis] = static_cast<uint32_t>(*value);
    sites *= shape.size[axis];
  }
  if (sites >= GridPool::kEmpty) {
    ctx.sink.error(system.poolSpan, "a grid has fewer than 4294967295 sites; this one has " + std::to_string(sites));
    return;
  }
  bool boundarySet = false, neighbourhoodSet = false;
  for (const auto& option : system.poolOptions) {
    bool* set = nullptr;
    if (option == "wrap" || option == "clamp" || option == "closed") {
      set = &boundarySet;
      shape.boundary = option == "wrap"    ? GridBoundary::Wrap
                       : option == "clamp" ? GridBoundary::Clamp
                                           : GridBoundary::Closed;
    } else if (option == "moore" || option == "vonneumann") {
      set = &neighbourhoodSet;
      shape.neighbourhood = option == "moore" ? GridNeighbourhood::Moore : GridNeighbourhood::VonNeumann;
    } else {
      ctx.sink.error(system.poolSpan,
                     "unknown grid option '" + option + "' (expected wrap, clamp or closed, and vonneumann or moore)");
      continue;
    }
    if (*set)
      ctx.sink.error(system.poolSpan, "the grid's " + std::string(set == &boundarySet ? "boundary" : "neighbourhood") +
                                          " is given twice");
    *set = true;
  }
}

// `pool spatial(radius)`: cells within the radius are neighbours.
void spatialRadius(CompileContext& ctx, const ast::System& system, const Scope& scope, SystemDefinition& definition) {
  if (system.poolArgs.size() != 1 || !system.poolOptions.empty()) {
    ctx.sink.error(system.poolSpan, "a spatial pool takes its neighbourhood radius, as in 'pool spatial(1.5)'");
    return;
  }
  auto value = evaluateConstant(*system.poolArgs[0], ctx.constantLookup(scope), ctx.sink, "the radius");
  if (!value) return;
  if (!(*value > 0) || !std::isfinite(*value)) {
    ctx.sink.error(system.poolArgs[0]->span, "the radius must be greater than 0");
    return;
  }
  definition.spatialRadius = *value;
}

// `fill A(e)` and `at(x, y) A(1)`. Values are compiled against a frame of internal
// state only, so they may read the site's me.x, me.y, me.z (and draw random numbers).
void compilePlacements(CompileContext& ctx, const ast::System& system, Scope& scope, SystemDefinition& definition) {
  if (system.placements.empty()) return;
  if (definition.poolKind != PoolKind::Grid) {
    ctx.sink.error(system.placements.front().span,
                   "'fill' and 'at' place cells in a grid pool; this system's pool is " +
                       std::string(poolKindName(definition.poolKind)));
    return;
  }
  std::map<std::string, int, std::less<>> none;
  ctx.reader = Reader{-1, static_cast<int>(&definition - ctx.program->systems.data())};
  NameLookup names = ctx.frameLookup(none, 0, scope);
  for (const auto& placement : system.placements) {
    GridPlacement compiled;
    compiled.fill = placement.fill;
    compiled.span = placement.span;
    if (placement.module.isMe) {
      ctx.sink.error(placement.module.span, "'me' is not a cell to place; name a cell");
      continue;
    }
    if (!placement.fill) {
      if (static_cast<int>(placement.at.size()) != definition.grid.dimensions) {
        ctx.sink.error(placement.span, "the grid has " + std::to_string(definition.grid.dimensions) + " dimension" +
                                           (definition.grid.dimensions == 1 ? "" : "s") + ", so 'at' takes " +
                                           std::to_string(definition.grid.dimensions) + " coordinate" +
                                           (definition.grid.dimensions == 1 ? "" : "s"));
        continue;
      }
      bool ok = true;
      for (size_t axis = 0; axis < placement.at.size(); ++axis) {
        auto value = evaluateConstant(*placement.at[axis], ctx.constantLookup(scope), ctx.sink, "a site coordinate");
        if (!value) {
          ok = false;
          continue;
        }
        if (!(*value >= 0) || *value != std::floor(*value) || *value >= definition.grid.size[axis]) {
          ctx.sink.error(placement.at[axis]->span, "coordinate " + messageNumber(*value) +
                                                       " is outside the grid (0 to " +
                                                       std::to_string(definition.grid.size[axis] - 1) + ")");
          ok = false;
          continue;
        }
        compiled.at[axis] = static_cast<int64_t>(*value);
      }
      if (!ok) continue;
    }
    int master = ctx.resolveModule(placement.module, -1);
    compiled.master = static_cast<MasterId>(master);
    const MasterCell& target = ctx.program->masters[master];
    if (placement.module.age) ctx.sink.error(placement.module.age->span, "cells placed in a grid start with age 0");
    for (uint32_t i = 0; i < target.stateCount(); ++i) {
      if (i < placement.module.args.size())
        compiled.values.push_back(compileExpression(*placement.module.args[i], names, ctx.sink));
      else
        compiled.values.push_back(CompiledExpression::constant(target.defaults[i]));
    }
    definition.placements.push_back(std::move(compiled));
  }
}

// Values are compiled now and evaluated when a world is made.
std::vector<AxiomCell> compileAxiom(CompileContext& ctx, const ast::System& system, const Scope& scope, int index) {
  int moduleScope = system.isLSystem ? index : -1;
  std::vector<AxiomCell> axiom;
  for (const auto& module : system.axiom) {
    if (module.isMe) continue;
    int master = ctx.resolveModule(module, moduleScope);
    AxiomCell cell;
    cell.master = master;
    const MasterCell& definition = ctx.program->masters[master];
    NameLookup names = ctx.constantLookup(scope);
    ctx.addFunctions(names, scope);
    // Values may read the system's own state and those above it (parent.x, root.x).
    ctx.reader = Reader{-1, index};
    NameLookup withSystems = names;
    withSystems.ancestor = [&ctx](const std::string& path, SourceSpan span) {
      ++ctx.ancestorUses;
      return ctx.registerAncestor(path, span);
    };
    for (uint32_t i = 0; i < definition.stateCount(); ++i) {
      if (i < module.args.size()) {
        const int usesBefore = ctx.ancestorUses;
        const int errorsBefore = ctx.sink.errorsReported();
        CompiledExpression compiled = compileExpression(*module.args[i], withSystems, ctx.sink);
        if (ctx.ancestorUses != usesBefore && ctx.sink.errorsReported() == errorsBefore && !compiled.isStochastic()) {
          cell.fromSystems.resize(definition.stateCount());
          cell.fromSystems[i] = std::move(compiled);
          cell.values.push_back(0);
          continue;
        }
        if (ctx.sink.errorsReported() != errorsBefore) {
          cell.values.push_back(0);
          continue;
        }
        auto value = evaluateConstant(*module.args[i], names, ctx.sink, "an axiom value");
        cell.values.push_back(value.value_or(0));
      } else {
        cell.values.push_back(definition.defaults[i]);
      }
    }
    if (module.age) {
      cell.age = evaluateConstant(*module.age, names, ctx.sink, "an axiom age").value_or(0);
      const MasterCell& target = ctx.program->masters[master];
      // Written so that NaN, which passes every comparison, fails this one.
      if (!(cell.age >= 0) || cell.age >= target.lifetime)
        ctx.sink.error(
            module.age->span,
            "'" + module.label + "' cannot start with age " + messageNumber(cell.age) +
                (!(cell.age >= 0) ? "; ages are ≥ 0" : ", not below its terminal age " + messageNumber(target.lifetime)));
    }
    axiom.push_back(std::move(cell));
  }
  return axiom;
}

}  // namespace

// A system (not an L-system) is also a cell: its label and state stand for it in the
// pools of the systems that contain it (paper 002, section 2.2). It has no rules.
void declareSystemCells(CompileContext& ctx) {
  for (size_t i = 0; i < ctx.tree.systems.size(); ++i) {
    const ast::System& system = ctx.tree.systems[i];
    if (system.isLSystem) {
      if (!system.state.empty())
        ctx.sink.error(system.state.front().span, "an lsystem has no state; write 'system' to give it some");
      continue;
    }
    if (int other = ctx.findMaster(system.name, -1); other >= 0) {
      ctx.sink.error(system.nameSpan, "'" + system.name + "' is already a cell (at " +
                                          where(ctx.program->masters[other].span) +
                                          "); a system's name labels its cell, so the two need different names");
      continue;
    }
    int index = ctx.addMaster(system.name, -1, system.nameSpan);
    ctx.program->masters[index].declared = true;
    ctx.program->masters[index].system = static_cast<int>(i);
    ctx.arityKnown[index] = true;
    ctx.declareState(system.state, index);
    ctx.systemMaster[i] = index;
  }
}

// ---- systems ----
void declareSystem(CompileContext& ctx, const ast::System& system, int index) {
  SystemDefinition definition;
  definition.name = system.name;
  definition.span = system.nameSpan;
  definition.isLSystem = system.isLSystem;
  if (auto it = ctx.systemMaster.find(static_cast<size_t>(index)); it != ctx.systemMaster.end())
    definition.master = it->second;
  for (const auto& other : ctx.program->systems)
    if (other.name == system.name)
      ctx.sink.error(system.nameSpan,
                     "system '" + system.name + "' is defined twice (also at " + where(other.span) + ")");
  if (system.poolKind == "linear") {
    definition.poolKind = PoolKind::Linear;
    if (!system.poolArgs.empty() || !system.poolOptions.empty())
      ctx.sink.error(system.poolSpan, "the linear pool takes no arguments or options");
  } else if (system.poolKind == "grid") {
    definition.poolKind = PoolKind::Grid;
  } else if (system.poolKind == "spatial") {
    definition.poolKind = PoolKind::Spatial;
  } else {
    ctx.sink.error(system.poolSpan, "unknown pool kind '" + system.poolKind + "' (expected linear, grid or spatial)");
  }
  auto scope = std::make_unique<Scope>();
  scope->system = system.isLSystem ? index : -1;
  scope->outer = &ctx.global;
  scope->constants.outer = &ctx.global.constants;
  definition.settings = ctx.globalSettings;
  ctx.program->systems.push_back(std::move(definition));
  compileDefines(ctx, system.defines, *scope, index);
  if (!system.isLSystem && !system.equivs.empty())
    ctx.sink.error(system.equivs.front().span,
                   "cells are shared by every system, so their equivs are too: write 'equiv' at the top level");
  compileEquivs(ctx, system.equivs, *scope);
  compileDirectives(ctx, system.settings, ctx.program->systems.back().settings, *scope);
  if (system.isLSystem) compileFunctions(ctx, system.functions, *scope);
  if (ctx.program->systems.back().poolKind == PoolKind::Grid)
    gridShape(ctx, system, *scope, ctx.program->systems.back());
  if (ctx.program->systems.back().poolKind == PoolKind::Spatial)
    spatialRadius(ctx, system, *scope, ctx.program->systems.back());
  ctx.scopes.push_back(std::move(scope));
}

void compileSystem(CompileContext& ctx, const ast::System& system, int index) {
  Scope& scope = *ctx.scopes[index];
  if (system.isLSystem) compileProductions(ctx, system, scope, index);
  ctx.program->systems[index].axiom = compileAxiom(ctx, system, scope, index);
  if (system.isLSystem) compileSymbolInterpretations(ctx, system, scope, index);
  compilePlacements(ctx, system, scope, ctx.program->systems[index]);
  if (ctx.program->systems[index].poolKind == PoolKind::Grid &&
      ctx.program->systems[index].axiom.size() > ctx.program->systems[index].grid.siteCount())
    ctx.sink.error(system.axiomSpan, "the axiom has " + std::to_string(ctx.program->systems[index].axiom.size()) +
                                         " cells, more than the grid's " +
                                         std::to_string(ctx.program->systems[index].grid.siteCount()) + " sites");
  ctx.ignoreLists.push_back({index, &system});
}

namespace {

// The classes of every master with the symbols one list leaves out of context matching.
std::vector<uint8_t> classesWith(const CompileContext& ctx, const ast::SymbolList& list) {
  std::vector<uint8_t> classes(ctx.program->masters.size());
  const std::set<std::string> listed(list.symbols.begin(), list.symbols.end());
  for (size_t m = 0; m < ctx.program->masters.size(); ++m) {
    const MasterCell& master = ctx.program->masters[m];
    classes[m] = master.symbolClass;
    if (master.symbolClass == kSymbolModule && (listed.count(master.label) > 0) != list.consider)
      classes[m] |= kSymbolIgnored;
  }
  return classes;
}

// An L-system's `ignore:` and `consider:` lines apply each to the productions after it,
// up to the next one (L-Py); productions above the first see every module.
void classifyPerRule(CompileContext& ctx, const ast::System& system, int index) {
  SystemDefinition& definition = ctx.program->systems[index];
  for (const auto& list : system.filters) definition.ruleClasses.push_back(classesWith(ctx, list));
  definition.ruleClasses.push_back(classesWith(ctx, ast::SymbolList{}));  // no list: nothing ignored
  const int none = static_cast<int>(system.filters.size());
  for (MasterCell& master : ctx.program->masters) {
    if (master.scope != index) continue;
    for (CompiledRule& rule : master.terminalRules)
      if (rule.symbolClasses < 0) rule.symbolClasses = none;
  }
}

}  // namespace

// Per system, the class of every master: branch brackets, and the symbols its
// `ignore:` or `consider:` list leaves out of context matching.
void classifySymbols(CompileContext& ctx) {
  for (auto& [index, system] : ctx.ignoreLists) {
    SystemDefinition& definition = ctx.program->systems[index];
    definition.symbolClass.resize(ctx.program->masters.size());
    for (size_t m = 0; m < ctx.program->masters.size(); ++m)
      definition.symbolClass[m] = ctx.program->masters[m].symbolClass;
    if (system->isLSystem && !system->filters.empty()) classifyPerRule(ctx, *system, index);
    const bool both = !system->ignore.empty() && !system->consider.empty();
    if (both && system->isLSystem) continue;  // each rule sees its own list; neighbours see every module
    if (both) ctx.sink.error(system->consider.front().span, "a system has either 'ignore' or 'consider', not both");
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

}  // namespace ontogen::detail
