#include "core/homomorphism.h"

#include "core/cell_frame.h"
#include "core/linear_context.h"
#include "core/rule_choice.h"
#include "core/rule_evaluator.h"
#include "core/salts.h"

namespace ontogen {

HomomorphismImage::HomomorphismImage(const World& world)
    : world_(world), successors_(world.program()), frames_(static_cast<size_t>(world.rootSystem().homomorphismDepth) + 1) {
  group_ = activeGroup(world.program(), world.rootSystem(), world.time(), world.seed());
  const Pool& pool = world.rootPool();
  // Rules with context read the word around the module: a copy with its branches indexed
  // (the world's own index may be older than its word).
  if (pool.kind() == PoolKind::Linear)
    for (const MasterCell& master : world.program().masters)
      for (const CompiledRule& rule : master.homomorphismRules)
        if (rule.hasContext() && !word_) {
          word_ = std::make_unique<LinearPool>(static_cast<const LinearPool&>(pool));
          word_->indexBranches(world.rootSystem().symbolClass);
        }
  cells_.reserve(pool.size());
  for (CellCursor cell = pool.cursor(); !cell.done(); cell.next())
    rewrite(moduleOf(cell.view()), cell.state(), cell.index(), 1);
}

void HomomorphismImage::push(const ModuleValue& cell, const double* state, size_t source) {
  const uint32_t n = world_.program().masters[cell.master].stateCount();
  CellRecord copy = recordOf(cell);
  copy.state = static_cast<uint32_t>(state_.size());
  state_.insert(state_.end(), state, state + n);
  cells_.push_back(copy);
  sources_.push_back(source);
}

void HomomorphismImage::rewrite(const ModuleValue& cell, const double* state, size_t source, int depth) {
  const Program& program = world_.program();
  const MasterCell& master = program.masters[cell.master];
  if (master.homomorphismRules.empty() || depth > world_.rootSystem().homomorphismDepth) {
    push(cell, state, source);
    return;
  }
  std::vector<double>& frameAtDepth = frames_[static_cast<size_t>(depth)];
  frameAtDepth.resize(ruleFrameSize(program));
  double* frame = frameAtDepth.data();
  const double time = world_.time();
  const uint64_t id = cell.id();
  loadCellFrame(frame, master, CellView{cell.master, state, cell.birth, id, source}, time, world_.positionOf(source),
                -1);
  RandomStream random(mixKey(mixKey(world_.seed() ^ kHomomorphismSalt, id), keyOf(time)));
  const FunctionTable functions = program.functionTable();
  EvalContext context{frame, EvalEnvironment{&random, world_.seed()}, &functions};
  context.ancestors = world_.ancestorValues();
  // Context is read around the module in the developing word; what a rule makes has no
  // place there, so rules with context do not apply to it.
  const SystemDefinition& system = world_.rootSystem();
  auto contextHolds = [&](const CompiledRule& rule) {
    rule.clearUnbound(frame);
    if (!rule.hasContext()) return true;
    if (depth > 1 || !word_) return false;
    const auto& classOf = rule.symbolClasses < 0 ? system.symbolClass : system.ruleClasses[rule.symbolClasses];
    return matchLinearContext(program, rule, *word_, source, WrittenWord{}, classOf, frame, matched_);
  };
  auto matches = [&](const CompiledRule& rule) {
    return contextHolds(rule) && (rule.predicate.empty() || rule.predicate.evaluate(context) != 0.0);
  };
  const CompiledRule* rule = chooseRule(master.homomorphismRules, group_, matches, context, random, candidates_);
  if (!rule) {
    push(cell, state, source);
    return;
  }
  if (!rule->probability.empty()) contextHolds(*rule);  // rebind its values
  // The image's modules stand for the module they come from: its birth, ids of its own
  // (salted apart from the ids of its real successors).
  const ModuleValue salted{cell.master, ModuleValue::kOwnId, cell.birth, id ^ kHomomorphismSalt};
  // Keyed by the birth, not the time, so the image's ids stay the same from frame to frame.
  successors_.write(*rule, salted, frame, cell.birth, BirthCause::Terminal, context,
                    [&](const ModuleValue& made, const double* values, uint32_t) {
                      ModuleValue image = made;
                      image.birth = cell.birth;
                      rewrite(image, values, source, depth + 1);
                    });
}

}  // namespace ontogen
