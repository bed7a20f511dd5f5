// Cells, rules and productions: a declared cell's master (state, defaults, lifetime) and
// its rules, an L-system's productions as terminal rules of its symbols. A rule's
// context pattern binds its neighbours' state into the frame; its calculations,
// successors and probability compile against that frame, and its neighbour aggregates
// (`count(A)`, `sum(x)` ...) become queries the engine answers.

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "lang/compile_stages.h"
#include "lang/expression_compiler.h"
#include "model/message_number.h"

namespace ontogen::detail {

namespace {

std::unique_ptr<ast::Expr> cloneExpr(const ast::Expr& expr) {
  auto copy = std::make_unique<ast::Expr>();
  copy->kind = expr.kind;
  copy->span = expr.span;
  copy->number = expr.number;
  copy->name = expr.name;
  copy->op = expr.op;
  copy->height = expr.height;
  for (const auto& arg : expr.args) copy->args.push_back(cloneExpr(*arg));
  return copy;
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
    int master = ctx.findMaster(label, moduleScope);
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

// The names of a rule's frame as they bind: the cell's state (in an L-system, the
// predecessor's parameters) first, then the parameters of its context modules.
struct RuleFrame {
  RuleFrame(CompileContext& ctx, int master, int moduleScope)
      : ctx(ctx),
        moduleScope(moduleScope),
        label(ctx.program->masters[master].label),
        stateNames(ctx.program->masters[master].stateNames),
        nextSlot(stateCount() + FrameSlot::kCount) {}

  CompileContext& ctx;
  int moduleScope;  // where context labels resolve: the L-system's index, -1 for cells
  // Copies, not a reference: resolving context and successor labels may add masters.
  std::string label;
  std::vector<std::string> stateNames;
  SlotMap slots;
  std::map<std::string, SourceSpan, std::less<>> boundAt;  // the names this rule binds, where
  int nextSlot;
  // Value patterns, `A(3)`: the frame slot that must hold the value, and the value.
  std::vector<std::tuple<int, double, SourceSpan>> valueTests;

  // A pattern's parameter: a name binds the slot, a number tests it.
  void bindParameter(const ast::Expr& arg, int slot) {
    if (arg.kind == ast::Expr::Kind::Number)
      valueTests.push_back({slot, arg.number, arg.span});
    else
      bind(arg.name, slot, arg.span);
  }

  int stateCount() const { return static_cast<int>(stateNames.size()); }

  void bind(const std::string& name, int slot, SourceSpan span) {
    if (isReadOnlyName(name)) {
      ctx.sink.error(span, "'" + name + "' is read-only internal state and cannot be a parameter name");
      return;
    }
    if (slots.emplace(name, slot).second) {
      boundAt[name] = span;
    } else if (!boundAt.count(name)) {
      ctx.sink.error(span, "'" + name + "' is already a state variable of '" + label + "'");
    } else {
      ctx.sink.error(span, "'" + name + "' is already bound in this rule (at line " +
                               std::to_string(boundAt[name].line()) + ":" + std::to_string(boundAt[name].column()) +
                               ")");
    }
  }

  ContextBinding contextBinding(const ast::Module& module, bool leftSide) {
    ContextBinding binding;
    if (module.label == "*") {
      binding.item.kind = ContextItem::Kind::Any;  // the wildcard: any module
      if (module.hasArgs) {
        // `*(x, y)`: any module with two parameters, bound to x and y.
        binding.arity = static_cast<int>(module.args.size());
        binding.count = binding.arity;
        if (binding.count > 0) binding.firstSlot = nextSlot;
        for (const auto& arg : module.args) bindParameter(*arg, nextSlot++);
      }
      return binding;
    }
    if (module.label == "∅") {
      binding.item.kind = ContextItem::Kind::End;  // nothing more on this side
      return binding;
    }
    if (module.label == "[" && leftSide && moduleScope >= 0) {
      binding.item.kind = ContextItem::Kind::BranchOpen;  // the module starts a branch
      return binding;
    }
    if (module.label == "[" || module.label == "]") {
      if (leftSide)
        ctx.sink.error(module.span, moduleScope >= 0
                                        ? "a left context cannot contain ']'; it follows the path to the root (a "
                                          "'[' says that the module starts a branch)"
                                        : "a left context cannot contain brackets; it follows the path to the root");
      binding.item.kind = module.label == "[" ? ContextItem::Kind::BranchOpen : ContextItem::Kind::BranchClose;
      return binding;
    }
    int contextMaster = ctx.resolveModule(module, moduleScope);
    binding.item.master = static_cast<uint32_t>(contextMaster);
    if (!module.args.empty()) {
      binding.firstSlot = nextSlot;
      binding.count = static_cast<int>(module.args.size());
      if (binding.count != static_cast<int>(ctx.program->masters[contextMaster].stateCount()))
        ctx.sink.error(module.span, "'" + module.label + "' has " +
                                        std::to_string(ctx.program->masters[contextMaster].stateCount()) +
                                        " state values; a context binds all of them or none");
      for (const auto& arg : module.args) bindParameter(*arg, nextSlot++);
    }
    return binding;
  }
};

// One combination of a rule's context alternatives: each side as a flat sequence of
// patterns in text order (`(B | C D) < A` gives `B < A` and `C D < A`).
struct ContextVariant {
  std::vector<const ast::Module*> left, right, newLeft, newRight;
};

// Most rules the alternatives of one context may make: each is tried in turn, and a
// product of alternatives grows fast; more is a context nobody means.
constexpr size_t kMaxContextVariants = 64;

// Every flat sequence a side's patterns stand for, in the order they are tried.
std::vector<std::vector<const ast::Module*>> expandSide(const std::vector<ast::Module>& items) {
  std::vector<std::vector<const ast::Module*>> result(1);
  for (const ast::Module& item : items) {
    if (item.alternatives.empty()) {
      for (auto& sequence : result) sequence.push_back(&item);
      continue;
    }
    std::vector<std::vector<const ast::Module*>> next;
    for (const auto& prefix : result)
      for (const auto& alternative : item.alternatives)
        for (const auto& tail : expandSide(alternative)) {
          if (next.size() > kMaxContextVariants) return next;
          next.push_back(prefix);
          next.back().insert(next.back().end(), tail.begin(), tail.end());
        }
    result = std::move(next);
  }
  return result;
}

std::vector<ContextVariant> contextVariants(const ast::Rule& rule) {
  std::vector<ContextVariant> variants;
  const auto lefts = expandSide(rule.left);
  const auto rights = expandSide(rule.right);
  const auto newLefts = expandSide(rule.newLeft);
  const auto newRights = expandSide(rule.newRight);
  for (const auto& newLeft : newLefts)
    for (const auto& newRight : newRights)
      for (const auto& left : lefts)
        for (const auto& right : rights) {
          if (variants.size() > kMaxContextVariants) return variants;
          variants.push_back({left, right, newLeft, newRight});
        }
  return variants;
}

// The names a side's patterns bind, alternatives included, in text order.
void patternNames(const std::vector<ast::Module>& items, std::vector<const ast::Expr*>& names) {
  for (const ast::Module& item : items) {
    for (const auto& arg : item.args)
      if (arg->kind == ast::Expr::Kind::Name) names.push_back(arg.get());
    for (const auto& alternative : item.alternatives) patternNames(alternative, names);
  }
}

// `∅` is the far end of a side: first on the left, last on the right.
void checkEnds(DiagnosticSink& sink, const std::vector<const ast::Module*>& side, bool leftSide) {
  for (size_t k = 0; k < side.size(); ++k) {
    const bool farthest = leftSide ? k == 0 : k + 1 == side.size();
    if (side[k]->label == "∅" && !farthest)
      sink.error(side[k]->span, leftSide ? "'∅' (nothing: the start of the word) stands first in a left context"
                                         : "'∅' (nothing: the end of the branch or the word) stands last in a "
                                           "right context");
  }
}

// `A < me > B`, `(A) (B me C) (D)`: the modules around the cell and the frame slots
// their parameters take.
void compileContext(RuleFrame& frame, const ast::Rule& rule, const ContextVariant& variant, CompiledRule& compiled) {
  DiagnosticSink& sink = frame.ctx.sink;
  checkEnds(sink, variant.left, true);
  checkEnds(sink, variant.right, false);
  checkEnds(sink, variant.newLeft, true);
  checkEnds(sink, variant.newRight, false);
  // Left context nearest first.
  for (auto it = variant.left.rbegin(); it != variant.left.rend(); ++it)
    compiled.left.push_back(frame.contextBinding(**it, true));
  for (const auto* module : variant.right) compiled.right.push_back(frame.contextBinding(*module, false));
  for (auto it = variant.newLeft.rbegin(); it != variant.newLeft.rend(); ++it)
    compiled.newLeft.push_back(frame.contextBinding(**it, true));
  for (const auto* module : variant.newRight) compiled.newRight.push_back(frame.contextBinding(*module, false));
  // Names that other alternatives bind read 0 in this one.
  std::vector<const ast::Expr*> names;
  for (const auto* side : {&rule.left, &rule.right, &rule.newLeft, &rule.newRight}) patternNames(*side, names);
  for (const ast::Expr* name : names) {
    if (frame.slots.count(name->name)) continue;
    frame.slots[name->name] = frame.nextSlot;
    frame.boundAt[name->name] = name->span;
    compiled.unboundSlots.push_back(frame.nextSlot++);
  }
  compiled.contextDimensions = rule.contextDimensions;
  for (size_t k = 0; k < rule.offsets.size() && k < compiled.right.size(); ++k) {
    compiled.right[k].offset = rule.offsets[k];
    if (compiled.right[k].item.kind != ContextItem::Kind::Module)
      sink.error(rule.right[k].span,
                 "brackets have no place in a context of " + std::to_string(rule.contextDimensions) + " dimensions");
  }
  compiled.frameSize = frame.nextSlot;
  for (const auto& binding : compiled.left) compiled.leftItems.push_back(binding.item);
  for (const auto& binding : compiled.right) compiled.rightItems.push_back(binding.item);
  for (const auto& binding : compiled.newLeft) compiled.newLeftItems.push_back(binding.item);
  for (const auto& binding : compiled.newRight) compiled.newRightItems.push_back(binding.item);
  if (compiled.leftItems.size() > kMaxContextItems || compiled.rightItems.size() > kMaxContextItems ||
      compiled.newLeftItems.size() > kMaxContextItems || compiled.newRightItems.size() > kMaxContextItems)
    sink.error(rule.span, "a context has at most " + std::to_string(kMaxContextItems) + " modules on each side");
}

// `x = e`, `x += e`, `rate(x) = e`: a cell writes its own state only.
void compileCalculations(const RuleFrame& frame, const ast::Rule& rule, bool lsystem, const NameLookup& names,
                         CompiledRule& compiled) {
  DiagnosticSink& sink = frame.ctx.sink;
  for (const auto& assignment : rule.calculations) {
    StateCalculation calculation;
    calculation.span = assignment.span;
    if (assignment.isRate) {
      if (lsystem) {
        sink.error(assignment.span, "'rate' belongs to the cell language; write the module as a cell");
        continue;
      }
      if (rule.terminal) {
        sink.error(assignment.span, "'rate' integrates while a cell lives; a terminal rule fires once");
        continue;
      }
      if (assignment.op != TokenKind::Equal) {
        sink.error(assignment.span, "write 'rate(x) = e': the rate is the derivative itself");
        continue;
      }
      calculation.isRate = true;
    }
    if (isReadOnlyName(assignment.target) || internalSlot(assignment.target) >= 0) {
      sink.error(assignment.targetSpan, "'" + assignment.target + "' is read-only internal state");
      continue;
    }
    auto it = std::find(frame.stateNames.begin(), frame.stateNames.end(), assignment.target);
    if (lsystem || it == frame.stateNames.end()) {
      sink.error(assignment.targetSpan,
                 frame.slots.count(assignment.target)
                     ? "'" + assignment.target + "' belongs to a neighbour; a cell writes only its own state"
                     : "'" + assignment.target + "' is not a state variable of '" + frame.label + "'");
      continue;
    }
    calculation.slot = static_cast<int>(it - frame.stateNames.begin());
    calculation.value = compileExpression(*combine(assignment), names, sink);
    (calculation.isRate ? compiled.hasRate : compiled.hasDiscrete) = true;
    compiled.calculations.push_back(std::move(calculation));
  }
}

// `-> me B(x / 2) (C, 0.5)`: the cells a rule makes, at most one keeping the identity.
void compileSuccessors(CompileContext& ctx, const ast::Rule& rule, int moduleScope, bool lsystem,
                       const NameLookup& names, CompiledRule& compiled) {
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
    int successorMaster = ctx.resolveModule(successor, moduleScope);
    result.master = static_cast<uint32_t>(successorMaster);
    const MasterCell& target = ctx.program->masters[successorMaster];
    for (uint32_t i = 0; i < target.stateCount(); ++i) {
      if (i < successor.args.size())
        result.args.push_back(compileExpression(*successor.args[i], names, ctx.sink));
      else
        result.args.push_back(CompiledExpression::constant(target.defaults[i]));
    }
    if (successor.age) {
      result.birthAge = compileExpression(*successor.age, names, ctx.sink);
      // A constant age that no cell can be born with fails every time the rule fires:
      // say so here, as `check` should, not only when the model runs.
      if (result.birthAge.isConstant()) {
        const double age = result.birthAge.constantValue();
        if (!(age >= 0) || !std::isfinite(age))
          ctx.sink.error(successor.age->span, "'" + successor.label + "' cannot be born with age " + messageNumber(age) +
                                                   "; ages are finite and ≥ 0");
      }
    }
    bool bornAtZero =
        result.birthAge.empty() || (result.birthAge.isConstant() && result.birthAge.constantValue() == 0.0);
    result.stateless = target.stateCount() == 0 && bornAtZero && target.lifetime > 0;
    compiled.successors.push_back(std::move(result));
  }
}

CompiledRule compileRule(CompileContext& ctx, const ast::Rule& rule, int master, int scopeIndex, const Scope& scope,
                         bool lsystem, const ContextVariant& variant) {
  ctx.reader = Reader{master, -1};
  CompiledRule compiled;
  compiled.name = rule.name;
  compiled.group = rule.group;
  compiled.symbolClasses = rule.filter;  // -1, or the filter's index: classifySymbols makes them
  compiled.span = rule.span;
  const int moduleScope = lsystem ? scopeIndex : -1;
  RuleFrame frame(ctx, master, moduleScope);
  if (lsystem) {
    for (size_t i = 0; i < rule.predecessor.args.size(); ++i)
      frame.bindParameter(*rule.predecessor.args[i], static_cast<int>(i));
  } else {
    for (int i = 0; i < frame.stateCount(); ++i) frame.slots[frame.stateNames[i]] = i;
    if (rule.predecessor.isMe && rule.predecessor.hasArgs)
      ctx.sink.error(rule.predecessor.span, "'me' takes no parameters; the cell's state is read by name");
  }
  compileContext(frame, rule, variant, compiled);

  NameLookup names = ctx.frameLookup(frame.slots, frame.stateCount(), scope);
  names.aggregate = [&ctx, &compiled, moduleScope](const ast::Expr& call, DiagnosticSink& sink) {
    return registerAggregate(ctx, call, sink, compiled.aggregates, moduleScope);
  };
  // Value patterns test their slots before the condition: `A(3) : x > 1` is
  // `A(#) : # == 3 && x > 1`, with `#` a name no program can write.
  std::unique_ptr<ast::Expr> predicate = rule.predicate ? cloneExpr(*rule.predicate) : nullptr;
  for (auto it = frame.valueTests.rbegin(); it != frame.valueTests.rend(); ++it) {
    const auto& [slot, value, span] = *it;
    const std::string hidden = "#" + std::to_string(slot);
    frame.slots[hidden] = slot;
    auto name = std::make_unique<ast::Expr>();
    name->kind = ast::Expr::Kind::Name;
    name->name = hidden;
    name->span = span;
    auto number = std::make_unique<ast::Expr>();
    number->number = value;
    number->span = span;
    auto test = std::make_unique<ast::Expr>();
    test->kind = ast::Expr::Kind::Binary;
    test->op = TokenKind::EqualEqual;
    test->span = span;
    test->args.push_back(std::move(name));
    test->args.push_back(std::move(number));
    if (predicate) {
      auto both = std::make_unique<ast::Expr>();
      both->kind = ast::Expr::Kind::Binary;
      both->op = TokenKind::AmpAmp;
      both->span = span;
      both->args.push_back(std::move(test));
      both->args.push_back(std::move(predicate));
      predicate = std::move(both);
    } else {
      predicate = std::move(test);
    }
  }
  if (predicate) compiled.predicate = compileExpression(*predicate, names, ctx.sink);
  compileCalculations(frame, rule, lsystem, names, compiled);
  compiled.hasAction = rule.hasAction;
  if (rule.hasAction) compiled.hasDiscrete = true;
  compileSuccessors(ctx, rule, moduleScope, lsystem, names, compiled);
  if (rule.probability) {
    compiled.probability = compileExpression(*rule.probability, names, ctx.sink);
    if (compiled.probability.isConstant() && !(compiled.probability.constantValue() >= 0))
      ctx.sink.error(rule.probability->span, "a probability must be ≥ 0");
  }
  return compiled;
}

// A rule with its context as written; the alternatives of an L-system context make one
// rule per combination (CompiledRule::variant), whose diagnostics are reported once.
std::vector<CompiledRule> compileRuleVariants(CompileContext& ctx, const ast::Rule& rule, int master, int scopeIndex,
                                              const Scope& scope, bool lsystem) {
  const std::vector<ContextVariant> variants = contextVariants(rule);
  std::vector<CompiledRule> compiled;
  if (variants.size() > kMaxContextVariants) {
    ctx.sink.error(rule.span, "the alternatives of this context make more than " + std::to_string(kMaxContextVariants) +
                                  " combinations; split the production");
    return compiled;
  }
  ctx.sink.beginRepeats();
  for (size_t v = 0; v < variants.size(); ++v) {
    compiled.push_back(compileRule(ctx, rule, master, scopeIndex, scope, lsystem, variants[v]));
    compiled.back().variant = static_cast<int>(v);
  }
  ctx.sink.endRepeats();
  return compiled;
}

}  // namespace

void declareCells(CompileContext& ctx) {
  for (const auto& cell : ctx.tree.cells) {
    if (ctx.findMaster(cell.name, -1) >= 0) {
      ctx.sink.error(cell.nameSpan, "cell '" + cell.name + "' is defined twice (also at " +
                                        where(ctx.program->masters[ctx.findMaster(cell.name, -1)].span) + ")");
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

void compileCells(CompileContext& ctx) {
  for (const auto& cell : ctx.tree.cells) {
    auto it = ctx.cellMaster.find(&cell);
    if (it == ctx.cellMaster.end()) continue;
    int master = it->second;
    bool anyTerminal = false;
    for (const auto& rule : cell.rules) {
      ctx.readsPosition = ctx.readsParent = false;
      ContextVariant variant;
      for (const auto& module : rule.left) variant.left.push_back(&module);
      for (const auto& module : rule.right) variant.right.push_back(&module);
      CompiledRule compiled = compileRule(ctx, rule, master, -1, ctx.global, /*lsystem=*/false, variant);
      if (ctx.readsPosition) ctx.program->masters[master].readsPosition = true;
      if (ctx.readsParent) ctx.program->masters[master].readsParent = true;
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

namespace {

// `maximum depth: N`: a whole number from 1 to kMaxRewriteDepth.
int rewriteDepth(CompileContext& ctx, const ast::ExprPtr& expr, const Scope& scope) {
  if (!expr) return 1;
  auto value = evaluateConstant(*expr, ctx.constantLookup(scope), ctx.sink, "a maximum depth");
  if (!value) return 1;
  if (!(*value >= 1) || *value != std::floor(*value) || *value > kMaxRewriteDepth) {
    ctx.sink.error(expr->span, "a maximum depth is a whole number from 1 to " + std::to_string(kMaxRewriteDepth) +
                                   ", not " + messageNumber(*value));
    return 1;
  }
  return static_cast<int>(*value);
}

// Decomposition and homomorphism rules: context-free rewriting of one module.
void compileRewriting(CompileContext& ctx, const ast::System& system, Scope& scope, int index) {
  SystemDefinition& definition = ctx.program->systems[index];
  definition.decompositionDepth = rewriteDepth(ctx, system.decompositionDepth, scope);
  definition.homomorphismDepth = rewriteDepth(ctx, system.homomorphismDepth, scope);
  for (const auto& rule : system.productions) {
    if (rule.kind == ast::RuleKind::Production) continue;
    const bool decomposition = rule.kind == ast::RuleKind::Decomposition;
    const char* what = decomposition ? "a decomposition rule" : "a homomorphism rule";
    if (rule.predecessor.age) {
      ctx.sink.error(rule.predecessor.age->span, std::string(what) + " has no terminal age; it rewrites at once");
      continue;
    }
    if (!decomposition && !rule.newLeft.empty()) {
      ctx.sink.error(rule.span,
                     "a homomorphism rule reads the word as it developed; a new left context '<<' "
                     "belongs to productions and decomposition rules");
      continue;
    }
    if (!rule.newRight.empty()) {
      ctx.sink.error(rule.newRightSpan, std::string(what) +
                                            " rewrites the word left to right, so a new right "
                                            "context '>>' has nothing produced yet to match; write '>'");
      continue;
    }
    int master = ctx.resolveModule(rule.predecessor, index, /*predecessor=*/true);
    ctx.readsPosition = ctx.readsParent = false;
    std::vector<CompiledRule> variants = compileRuleVariants(ctx, rule, master, index, scope, /*lsystem=*/true);
    if (!variants.empty() && !variants.front().aggregates.empty())
      ctx.sink.error(rule.span, std::string(what) + " does not read neighbours (count, sum, mean, min, max)");
    if (ctx.readsParent) ctx.sink.error(rule.span, std::string(what) + " does not read me.parent");
    if (ctx.readsPosition) ctx.program->masters[master].readsPosition = true;
    auto& rules = decomposition ? ctx.program->masters[master].decompositionRules
                                : ctx.program->masters[master].homomorphismRules;
    for (auto& compiled : variants) rules.push_back(std::move(compiled));
    (decomposition ? definition.decomposes : definition.homomorphism) = true;
  }
}

// Rule groups (L-Py): the active group's rules are tried before group 0's, which apply
// whatever group is active. Each list keeps its text order within the groups, with the
// numbered groups' rules first, so filtering by the active group gives that order.
void orderGroups(CompileContext& ctx, const ast::System& system, Scope& scope, int index) {
  SystemDefinition& definition = ctx.program->systems[index];
  if (system.useGroup) {
    std::map<std::string, int, std::less<>> none;
    ctx.reader = Reader{-1, index};
    NameLookup names = ctx.frameLookup(none, 0, scope);
    definition.useGroup = compileExpression(*system.useGroup, names, ctx.sink);
    definition.useGroupSpan = system.useGroup->span;
    if (definition.useGroup.isStochastic())
      ctx.sink.error(system.useGroup->span, "'use group' is evaluated once per step and draws no random numbers");
  }
  for (MasterCell& master : ctx.program->masters) {
    if (master.scope != index) continue;
    for (auto* rules : {&master.terminalRules, &master.decompositionRules, &master.homomorphismRules})
      std::stable_partition(rules->begin(), rules->end(), [](const CompiledRule& rule) { return rule.group != 0; });
  }
}

}  // namespace

void compileProductions(CompileContext& ctx, const ast::System& system, Scope& scope, int index) {
  // Terminal ages: one per symbol; untimed productions live one time unit.
  std::map<int, std::pair<double, SourceSpan>> terminal;
  std::vector<std::pair<int, const ast::Rule*>> productions;
  for (const auto& production : system.productions) {
    if (production.kind != ast::RuleKind::Production) continue;
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
                     "'" + production.predecessor.label + "' has terminal age " + messageNumber(age) + " here but " +
                         messageNumber(it->second.first) + " at line " + std::to_string(it->second.second.line()) +
                         "; a symbol has one terminal age");
      continue;
    }
    productions.push_back({master, &production});
  }
  // One direction per block: `>>` derives right to left, where nothing left of a module
  // is produced yet for a `<<` to match.
  const ast::Rule* newRight = nullptr;
  const ast::Rule* newLeft = nullptr;
  for (const auto& [master, production] : productions) {
    if (!production->newRight.empty() && !newRight) newRight = production;
    if (!production->newLeft.empty() && !newLeft) newLeft = production;
  }
  if (newRight) ctx.program->systems[index].backward = true;
  if (newRight && newLeft)
    ctx.sink.error(newLeft->span,
                   "a new left context '<<' needs the block to derive left to right, but the '>>' "
                   "at line " +
                       std::to_string(newRight->newRightSpan.line()) +
                       " makes it derive right to left; a block has one or the other");
  for (auto& [master, age] : terminal) {
    ctx.program->masters[master].lifetime = age.first;
    ctx.program->masters[master].declared = true;
  }
  for (auto& [master, production] : productions) {
    ctx.readsPosition = ctx.readsParent = false;
    std::vector<CompiledRule> variants = compileRuleVariants(ctx, *production, master, index, scope, /*lsystem=*/true);
    if (ctx.readsPosition) ctx.program->masters[master].readsPosition = true;
    if (ctx.readsParent) ctx.program->masters[master].readsParent = true;
    for (auto& rule : variants) ctx.program->masters[master].terminalRules.push_back(std::move(rule));
  }
  compileRewriting(ctx, system, scope, index);
  orderGroups(ctx, system, scope, index);
}

}  // namespace ontogen::detail
