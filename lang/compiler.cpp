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
CompiledRule compileRule(CompileContext& ctx, const ast::Rule& rule, int master, int scopeIndex, const Scope& scope,
                         bool lsystem);
std::unique_ptr<ast::Expr> combine(const ast::Assignment& assignment);
std::unique_ptr<ast::Expr> cloneExpr(const ast::Expr& expr);
int registerAggregate(CompileContext& ctx, const ast::Expr& call, DiagnosticSink& sink,
                      std::vector<AggregateQuery>& queries, int moduleScope);
void finishMasters(CompileContext& ctx);
std::vector<bool> reachable(const CompileContext& ctx, const SystemDefinition& system);
bool visibleIn(const MasterCell& master, int system);
bool checkCycles(CompileContext& ctx, const SystemTree& tree);
void chooseRoot(CompileContext& ctx, const SystemTree& tree);
void checkAncestorReads(CompileContext& ctx, const SystemTree& tree);

void declareCells(CompileContext& ctx) {
  for (const auto& cell : ctx.tree.cells) {
    if (ctx.program->findMaster(cell.name, -1) >= 0) {
      ctx.sink.error(cell.nameSpan, "cell '" + cell.name + "' is defined twice (also at " +
                                        where(ctx.program->masters[ctx.program->findMaster(cell.name, -1)].span) + ")");
      continue;
    }
    int index = ctx.addMaster(cell.name, -1, cell.nameSpan);
    ctx.program->masters[index].declared = true;
    ctx.arityKnown[index] = true;
    ctx.declareState(cell.state, index);
    if (cell.lifetime) {
      auto value = evaluateConstant(*cell.lifetime, ctx.constantLookup(ctx.global), ctx.sink, "the lifetime");
      if (value) {
        if (!(*value > 0))
          ctx.sink.error(cell.lifetimeSpan, "the lifetime must be greater than 0");
        else
          ctx.program->masters[index].lifetime = *value;
        ctx.program->masters[index].timedNotation = true;
      }
    }
    ctx.cellMaster[&cell] = index;
  }
}

void compileProductions(CompileContext& ctx, const ast::System& system, Scope& scope, int index) {
  // Terminal ages: one per symbol; untimed productions live one time unit.
  std::map<int, std::pair<double, SourceSpan>> terminal;
  std::vector<std::pair<int, const ast::Rule*>> productions;
  for (const auto& production : system.productions) {
    int master = ctx.resolveModule(production.predecessor, index, /*predecessor=*/true);
    double age = 1.0;
    if (production.predecessor.age) {
      auto value = evaluateConstant(*production.predecessor.age, ctx.constantLookup(scope), ctx.sink, "a terminal age");
      if (!value) continue;
      age = *value;
      if (!(age > 0)) {
        ctx.sink.error(production.predecessor.age->span, "the terminal age must be greater than 0");
        continue;
      }
    }
    auto [it, inserted] = terminal.emplace(master, std::make_pair(age, production.predecessor.span));
    if (!inserted && it->second.first != age) {
      ctx.sink.error(production.predecessor.span,
                     "'" + production.predecessor.label + "' has terminal age " + formatNumber(age) + " here but " +
                         formatNumber(it->second.first) + " at line " + std::to_string(it->second.second.line()) +
                         "; a symbol has one terminal age");
      continue;
    }
    productions.push_back({master, &production});
  }
  for (auto& [master, age] : terminal) {
    ctx.program->masters[master].lifetime = age.first;
    ctx.program->masters[master].declared = true;
  }
  for (auto& [master, production] : productions) {
    ctx.readsPosition = false;
    CompiledRule rule = compileRule(ctx, *production, master, index, scope, /*lsystem=*/true);
    if (ctx.readsPosition) ctx.program->masters[master].readsPosition = true;
    ctx.program->masters[master].terminalRules.push_back(std::move(rule));
  }
}

// ---- cells ----
void compileCells(CompileContext& ctx) {
  for (const auto& cell : ctx.tree.cells) {
    auto it = ctx.cellMaster.find(&cell);
    if (it == ctx.cellMaster.end()) continue;
    int master = it->second;
    bool anyTerminal = false;
    for (const auto& rule : cell.rules) {
      ctx.readsPosition = false;
      CompiledRule compiled = compileRule(ctx, rule, master, -1, ctx.global, /*lsystem=*/false);
      if (ctx.readsPosition) ctx.program->masters[master].readsPosition = true;
      if (rule.terminal) {
        anyTerminal = true;
        ctx.program->masters[master].terminalRules.push_back(std::move(compiled));
      } else {
        ctx.program->masters[master].rules.push_back(std::move(compiled));
      }
    }
    if (anyTerminal && ctx.program->masters[master].lifetime == kForever)
      ctx.sink.error(cell.nameSpan,
                     "cell '" + cell.name + "' has 'terminal:' rules but no lifetime; add 'lifetime 1;'");
    for (const auto& block : cell.interpretations) compileInterpretation(ctx, block, master);
  }
}

CompiledRule compileRule(CompileContext& ctx, const ast::Rule& rule, int master, int scopeIndex, const Scope& scope,
                         bool lsystem) {
  ctx.reader = Reader{master, -1};
  CompiledRule compiled;
  compiled.name = rule.name;
  compiled.span = rule.span;
  // Copies, not a reference: resolving context and successor labels may add masters.
  struct {
    std::string label;
    std::vector<std::string> stateNames;
  } self{ctx.program->masters[master].label, ctx.program->masters[master].stateNames};
  const int stateCount = static_cast<int>(self.stateNames.size());
  std::map<std::string, int, std::less<>> slots;
  std::map<std::string, SourceSpan, std::less<>> where;
  auto bind = [&](const std::string& name, int slot, SourceSpan span) {
    if (isReadOnlyName(name)) {
      ctx.sink.error(span, "'" + name + "' is read-only internal state and cannot be a parameter name");
      return;
    }
    if (slots.emplace(name, slot).second) {
      where[name] = span;
    } else if (!where.count(name)) {
      ctx.sink.error(span, "'" + name + "' is already a state variable of '" + self.label + "'");
    } else {
      ctx.sink.error(span, "'" + name + "' is already bound in this rule (at line " +
                               std::to_string(where[name].line()) + ":" + std::to_string(where[name].column()) + ")");
    }
  };
  if (lsystem) {
    for (size_t i = 0; i < rule.predecessor.args.size(); ++i)
      bind(rule.predecessor.args[i]->name, static_cast<int>(i), rule.predecessor.args[i]->span);
  } else {
    for (int i = 0; i < stateCount; ++i) slots[self.stateNames[i]] = i;
    if (rule.predecessor.isMe && rule.predecessor.hasArgs)
      ctx.sink.error(rule.predecessor.span, "'me' takes no parameters; the cell's state is read by name");
  }
  int nextSlot = stateCount + FrameSlot::kCount;
  auto contextBinding = [&](const ast::Module& module, bool leftSide) {
    ContextBinding binding;
    if (module.label == "[" || module.label == "]") {
      if (leftSide)
        ctx.sink.error(module.span, "a left context cannot contain brackets; it follows the path to the root");
      binding.item.kind = module.label == "[" ? ContextItem::Kind::BranchOpen : ContextItem::Kind::BranchClose;
      return binding;
    }
    int contextMaster = ctx.resolveModule(module, lsystem ? scopeIndex : -1);
    binding.item.master = static_cast<uint32_t>(contextMaster);
    if (!module.args.empty()) {
      binding.firstSlot = nextSlot;
      binding.count = static_cast<int>(module.args.size());
      if (binding.count != static_cast<int>(ctx.program->masters[contextMaster].stateCount()))
        ctx.sink.error(module.span, "'" + module.label + "' has " +
                                        std::to_string(ctx.program->masters[contextMaster].stateCount()) +
                                        " state values; a context binds all of them or none");
      for (const auto& arg : module.args) bind(arg->name, nextSlot++, arg->span);
    }
    return binding;
  };
  // Left context nearest first.
  for (auto it = rule.left.rbegin(); it != rule.left.rend(); ++it) compiled.left.push_back(contextBinding(*it, true));
  for (const auto& module : rule.right) compiled.right.push_back(contextBinding(module, false));
  compiled.contextDimensions = rule.contextDimensions;
  for (size_t k = 0; k < rule.offsets.size() && k < compiled.right.size(); ++k) {
    compiled.right[k].offset = rule.offsets[k];
    if (compiled.right[k].item.kind != ContextItem::Kind::Module)
      ctx.sink.error(rule.right[k].span, "brackets have no place in a context of " +
                                             std::to_string(rule.contextDimensions) + " dimensions");
  }
  compiled.frameSize = nextSlot;
  for (const auto& binding : compiled.left) compiled.leftItems.push_back(binding.item);
  for (const auto& binding : compiled.right) compiled.rightItems.push_back(binding.item);
  if (compiled.leftItems.size() > kMaxContextItems || compiled.rightItems.size() > kMaxContextItems)
    ctx.sink.error(rule.span, "a context has at most " + std::to_string(kMaxContextItems) + " modules on each side");

  NameLookup names = ctx.frameLookup(slots, stateCount, scope);
  names.aggregate = [&ctx, &compiled, moduleScope = lsystem ? scopeIndex : -1](const ast::Expr& call,
                                                                               DiagnosticSink& sink) {
    return registerAggregate(ctx, call, sink, compiled.aggregates, moduleScope);
  };
  if (rule.predicate) compiled.predicate = compileExpression(*rule.predicate, names, ctx.sink);
  for (const auto& assignment : rule.calculations) {
    StateCalculation calculation;
    calculation.span = assignment.span;
    if (assignment.isRate) {
      if (lsystem) {
        ctx.sink.error(assignment.span, "'rate' belongs to the cell language; write the module as a cell");
        continue;
      }
      if (rule.terminal) {
        ctx.sink.error(assignment.span, "'rate' integrates while a cell lives; a terminal rule fires once");
        continue;
      }
      if (assignment.op != TokenKind::Equal) {
        ctx.sink.error(assignment.span, "write 'rate(x) = e': the rate is the derivative itself");
        continue;
      }
      calculation.isRate = true;
    }
    if (isReadOnlyName(assignment.target) || internalSlot(assignment.target) >= 0) {
      ctx.sink.error(assignment.targetSpan, "'" + assignment.target + "' is read-only internal state");
      continue;
    }
    auto it = std::find(self.stateNames.begin(), self.stateNames.end(), assignment.target);
    if (lsystem || it == self.stateNames.end()) {
      ctx.sink.error(assignment.targetSpan,
                     slots.count(assignment.target)
                         ? "'" + assignment.target + "' belongs to a neighbour; a cell writes only its own state"
                         : "'" + assignment.target + "' is not a state variable of '" + self.label + "'");
      continue;
    }
    calculation.slot = static_cast<int>(it - self.stateNames.begin());
    calculation.value = compileExpression(*combine(assignment), names, ctx.sink);
    (calculation.isRate ? compiled.hasRate : compiled.hasDiscrete) = true;
    compiled.calculations.push_back(std::move(calculation));
  }
  compiled.hasAction = rule.hasAction;
  if (rule.hasAction) compiled.hasDiscrete = true;
  const ast::Module* identityKeeper = nullptr;  // `me` or `=X`: one cell goes on with the id
  for (const auto& successor : rule.successors) {
    SuccessorTemplate result;
    result.span = successor.span;
    if (successor.isMe || successor.keepsIdentity) {
      if (identityKeeper)
        ctx.sink.error(successor.span, "only one successor keeps the cell's identity, and '" +
                                           (identityKeeper->isMe ? std::string("me") : "=" + identityKeeper->label) +
                                           "' already does");
      identityKeeper = &successor;
    }
    result.keepsIdentity = successor.keepsIdentity;
    if (successor.isMe) {
      if (lsystem) ctx.sink.error(successor.span, "'me' is not part of the L-system notation; repeat the module");
      result.isMe = true;
      if (successor.hasArgs) ctx.sink.error(successor.span, "'me' takes no parameters; set state before '->'");
      compiled.successors.push_back(std::move(result));
      continue;
    }
    int successorMaster = ctx.resolveModule(successor, lsystem ? scopeIndex : -1);
    result.master = static_cast<uint32_t>(successorMaster);
    const MasterCell& target = ctx.program->masters[successorMaster];
    for (uint32_t i = 0; i < target.stateCount(); ++i) {
      if (i < successor.args.size())
        result.args.push_back(compileExpression(*successor.args[i], names, ctx.sink));
      else
        result.args.push_back(CompiledExpression::constant(target.defaults[i]));
    }
    if (successor.age) result.birthAge = compileExpression(*successor.age, names, ctx.sink);
    bool bornAtZero =
        result.birthAge.empty() || (result.birthAge.isConstant() && result.birthAge.constantValue() == 0.0);
    result.stateless = target.stateCount() == 0 && bornAtZero && target.lifetime > 0;
    compiled.successors.push_back(std::move(result));
  }
  if (rule.probability) {
    compiled.probability = compileExpression(*rule.probability, names, ctx.sink);
    if (compiled.probability.isConstant() && !(compiled.probability.constantValue() >= 0))
      ctx.sink.error(rule.probability->span, "a probability must be ≥ 0");
  }
  return compiled;
}

// `x += e` is compiled as `x = x + e`.
std::unique_ptr<ast::Expr> combine(const ast::Assignment& assignment) {
  auto copy = cloneExpr(*assignment.value);
  if (assignment.op == TokenKind::Equal) return copy;
  auto target = std::make_unique<ast::Expr>();
  target->kind = ast::Expr::Kind::Name;
  target->name = assignment.target;
  target->span = assignment.targetSpan;
  auto node = std::make_unique<ast::Expr>();
  node->kind = ast::Expr::Kind::Binary;
  node->span = assignment.span;
  node->op = assignment.op == TokenKind::PlusEqual    ? TokenKind::Plus
             : assignment.op == TokenKind::MinusEqual ? TokenKind::Minus
             : assignment.op == TokenKind::StarEqual  ? TokenKind::Star
                                                      : TokenKind::Slash;
  node->args.push_back(std::move(target));
  node->args.push_back(std::move(copy));
  return node;
}

std::unique_ptr<ast::Expr> cloneExpr(const ast::Expr& expr) {
  auto copy = std::make_unique<ast::Expr>();
  copy->kind = expr.kind;
  copy->span = expr.span;
  copy->number = expr.number;
  copy->name = expr.name;
  copy->op = expr.op;
  for (const auto& arg : expr.args) copy->args.push_back(cloneExpr(*arg));
  return copy;
}

// `count()`, `count(A)`, `sum(x)`, `mean(A.x)`, `min(x)`, `max(x)`: one query per text.
int registerAggregate(CompileContext& ctx, const ast::Expr& call, DiagnosticSink& sink,
                      std::vector<AggregateQuery>& queries, int moduleScope) {
  const ast::Expr* arg = call.args.empty() ? nullptr : call.args[0].get();
  std::string argText = !arg                                   ? ""
                        : arg->kind == ast::Expr::Kind::Name   ? arg->name
                        : arg->kind == ast::Expr::Kind::Member ? memberPath(*arg)
                                                               : "?";
  std::string text = call.name + "(" + argText + ")";
  for (size_t i = 0; i < queries.size(); ++i)
    if (queries[i].text == text) return static_cast<int>(i);
  AggregateQuery query;
  query.text = text;
  query.kind = call.name == "count"  ? AggregateKind::Count
               : call.name == "sum"  ? AggregateKind::Sum
               : call.name == "mean" ? AggregateKind::Mean
               : call.name == "min"  ? AggregateKind::Min
                                     : AggregateKind::Max;
  auto findLabel = [&](const std::string& label, SourceSpan span) {
    int master = ctx.program->findMaster(label, moduleScope);
    if (master < 0) sink.error(span, "no cell is called '" + label + "'");
    return master;
  };
  if (query.kind == AggregateKind::Count) {
    if (arg) {
      if (arg->kind != ast::Expr::Kind::Name) {
        sink.error(arg->span, "count() takes a cell label, as in count(A), or nothing");
        return -1;
      }
      query.label = findLabel(arg->name, arg->span);
      if (query.label < 0) return -1;
    }
  } else {
    std::string variable;
    if (arg->kind == ast::Expr::Kind::Name) {
      variable = arg->name;
    } else if (!memberPath(*arg).empty()) {
      query.label = findLabel(arg->args[0]->name, arg->args[0]->span);
      if (query.label < 0) return -1;
      variable = arg->name;
    } else {
      sink.error(arg->span, "'" + call.name + "' over neighbours takes a state variable, as in " + call.name +
                                "(x) or " + call.name + "(A.x)");
      return -1;
    }
    bool any = false;
    for (size_t m = 0; m < ctx.program->masters.size(); ++m) {
      const auto& names = ctx.program->masters[m].stateNames;
      auto it = std::find(names.begin(), names.end(), variable);
      bool has = it != names.end() && (query.label < 0 || query.label == static_cast<int>(m));
      query.slotOf.push_back(has ? static_cast<int>(it - names.begin()) : -1);
      any = any || has;
    }
    if (!any) {
      sink.error(arg->span, query.label >= 0 ? "'" + ctx.program->masters[query.label].label +
                                                   "' has no state variable '" + variable + "'"
                                             : "no cell has a state variable '" + variable + "'");
      return -1;
    }
  }
  queries.push_back(std::move(query));
  return static_cast<int>(queries.size() - 1);
}

// `interpret SET X(a) { ... }` in an L-system: the block of the block's own symbol X,
// its parameters named as the pattern names them.
void compileSymbolInterpretations(CompileContext& ctx, const ast::System& system, const Scope& scope, int index) {
  for (const auto& item : system.interpretations) {
    int master = ctx.program->findMaster(item.symbol, index);
    if (master < 0 || ctx.program->masters[master].scope != index) {
      ctx.sink.error(item.symbolSpan, "'" + item.symbol + "' is not a symbol of L-system '" + system.name + "'");
      continue;
    }
    const MasterCell& target = ctx.program->masters[master];
    if (item.params.size() != target.stateCount()) {
      ctx.sink.error(item.symbolSpan, "'" + item.symbol + "' has " + std::to_string(target.stateCount()) +
                                          " parameter" + (target.stateCount() == 1 ? "" : "s") + ", but " +
                                          std::to_string(item.params.size()) + " are named here");
      continue;
    }
    if (target.interpretation(item.block.setName)) continue;  // the first block counts
    compileInterpretation(ctx, item.block, master, &item.params, &scope);
  }
}

void compileInterpretation(CompileContext& ctx, const ast::Interpretation& block, int master,
                           const std::vector<std::string>* params, const Scope* scope) {
  InterpretationBlock compiled;
  compiled.setName = block.setName;
  compiled.span = block.span;
  const CommandSetInfo* set = nullptr;
  if (!ctx.options.commandSets.empty()) {
    for (const auto& candidate : ctx.options.commandSets)
      if (candidate.name == block.setName) set = &candidate;
    if (!set) {
      std::string known;
      for (const auto& candidate : ctx.options.commandSets) known += (known.empty() ? "" : ", ") + candidate.name;
      ctx.sink.error(block.span, "unknown interpretation set '" + block.setName + "' (known: " + known + ")");
      return;
    }
  }
  const MasterCell& self = ctx.program->masters[master];
  const Scope& lookupScope = scope ? *scope : ctx.global;
  std::map<std::string, int, std::less<>> slots;
  for (uint32_t i = 0; i < self.stateCount(); ++i)
    slots[params ? (*params)[i] : self.stateNames[i]] = static_cast<int>(i);
  ctx.reader = Reader{master, -1};
  NameLookup names = ctx.frameLookup(slots, static_cast<int>(self.stateCount()), lookupScope);
  if (set && set->constant) {
    names.constant = [&lookupScope, set](std::string_view name) -> std::optional<double> {
      if (auto value = lookupScope.constants.find(name)) return value;
      return set->constant(name);
    };
  }
  for (const auto& module : block.instructions) {
    Instruction instruction;
    instruction.span = module.span;
    const std::string* equiv = lookupScope.findEquiv(module.label);
    instruction.command = equiv ? *equiv : module.label;
    if (set) {
      const CommandInfo* info = set->find(instruction.command);
      if (!info) {
        ctx.sink.error(module.span, "'" + module.label + "' is not a command of the '" + block.setName + "' set");
        continue;
      }
      int count = static_cast<int>(module.args.size());
      if (count < info->minArity || (info->maxArity >= 0 && count > info->maxArity)) {
        ctx.sink.error(module.span, "'" + module.label + "' takes " + std::to_string(info->minArity) +
                                        (info->maxArity == info->minArity ? ""
                                         : info->maxArity < 0             ? " or more"
                                                                          : " to " + std::to_string(info->maxArity)) +
                                        " arguments, given " + std::to_string(count));
        continue;
      }
    }
    for (const auto& arg : module.args) instruction.args.push_back(compileExpression(*arg, names, ctx.sink));
    compiled.instructions.push_back(std::move(instruction));
  }
  ctx.program->masters[master].interpretations.push_back(std::move(compiled));
}

// ---- finishing ----
void finishMasters(CompileContext& ctx) {
  for (auto& master : ctx.program->masters) {
    const Scope* scope = master.scope >= 0 ? ctx.scopes[master.scope].get() : &ctx.global;
    const std::string* equiv = scope->findEquiv(master.label);
    master.command = equiv ? *equiv : master.label;
    if (master.command == "[") master.symbolClass = kSymbolBranchOpen;
    if (master.command == "]") master.symbolClass = kSymbolBranchClose;
  }
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
  finishMasters(ctx);
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
