#include "core/rule_evaluator.h"

#include "core/cell_frame.h"

#include <algorithm>
#include <limits>

namespace ontogen {

size_t ruleFrameSize(const Program& program) {
  size_t size = FrameSlot::kCount;
  for (const MasterCell& master : program.masters) {
    size = std::max<size_t>(size, master.stateCount() + FrameSlot::kCount);
    for (const auto& rule : master.rules) size = std::max<size_t>(size, rule.frameSize);
    for (const auto& rule : master.terminalRules) size = std::max<size_t>(size, rule.frameSize);
  }
  return size;
}

RuleEvaluator::RuleEvaluator(const Program& program, const PoolView& view)
    : program_(program), view_(view), pool_(view.pool()), frame_(ruleFrameSize(program)) {}

double* RuleEvaluator::load(size_t i, const double* arena, double time) {
  cell_ = i;
  arena_ = arena;
  neighbourCount_ = -1;
  rule_ = nullptr;
  const CellRecord& cell = pool_.cells()[i];
  const MasterCell& master = program_.masters[cell.master];
  // Positions cost a lookup in grids and spatial pools: only for masters that read them.
  const std::array<double, 3> position = master.readsPosition ? view_.position(i) : std::array<double, 3>{};
  double* frame = loadCellFrame(frame_.data(), master, cell, arena + cell.state, time, position);
  return frame;
}

bool RuleEvaluator::bind(const CompiledRule& rule) {
  rule_ = &rule;
  if (!rule.hasContext()) return true;
  if (!view_.matchContext(rule, cell_, left_, right_)) return false;
  const auto cells = pool_.cells();
  auto copy = [&](const std::vector<ContextBinding>& bindings, const uint32_t* matched) {
    for (size_t k = 0; k < bindings.size(); ++k) {
      const ContextBinding& binding = bindings[k];
      if (binding.count == 0) continue;
      const double* values = arena_ + cells[matched[k]].state;
      std::copy(values, values + binding.count, frame_.data() + binding.firstSlot);
    }
  };
  copy(rule.left, left_);
  copy(rule.right, right_);
  return true;
}

const CompiledRule* RuleEvaluator::fireStepRules(const MasterCell& master, const EvalContext& context,
                                                RandomStream& random, uint64_t& firings) {
  double* frame = frame_.data();
  for (const CompiledRule& rule : master.rules) {
    if (!rule.hasDiscrete) continue;  // rate-only rules act while integrating
    if (!bind(rule)) continue;
    if (!rule.predicate.empty() && rule.predicate.evaluate(context) == 0.0) continue;
    if (!rule.probability.empty() && !(random.uniform() < rule.probability.evaluate(context))) continue;
    for (const StateCalculation& calculation : rule.calculations)
      if (!calculation.isRate) frame[calculation.slot] = calculation.value.evaluate(context);
    ++firings;
    if (rule.hasAction) return &rule;
  }
  return nullptr;
}

double RuleEvaluator::aggregate(int query) const {
  if (neighbourCount_ < 0) {
    if (tableOffsets_) {
      neighbourList_ = tableCells_ + tableOffsets_[cell_];
      neighbourCount_ = static_cast<int>(tableOffsets_[cell_ + 1] - tableOffsets_[cell_]);
    } else {
      view_.neighbours(cell_, neighbours_);
      neighbourList_ = neighbours_.data();
      neighbourCount_ = static_cast<int>(neighbours_.size());
    }
  }
  const AggregateQuery& q = rule_->aggregates[query];
  const auto cells = pool_.cells();
  if (q.kind == AggregateKind::Sum && q.label < 0) {
    // The common case (diffusion): a plain sum, without the bookkeeping of the others.
    double sum = 0;
    for (int k = 0; k < neighbourCount_; ++k) {
      const CellRecord& neighbour = cells[neighbourList_[k]];
      if (neighbour.master < q.slotOf.size() && q.slotOf[neighbour.master] >= 0)
        sum += arena_[neighbour.state + q.slotOf[neighbour.master]];
    }
    return sum;
  }
  if (q.kind == AggregateKind::Count && q.label < 0) return neighbourCount_;
  double count = 0, sum = 0;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (int k = 0; k < neighbourCount_; ++k) {
    const CellRecord& neighbour = cells[neighbourList_[k]];
    if (q.label >= 0 && neighbour.master != static_cast<uint32_t>(q.label)) continue;
    if (q.kind == AggregateKind::Count) {
      ++count;
      continue;
    }
    if (neighbour.master >= q.slotOf.size() || q.slotOf[neighbour.master] < 0) continue;
    const double value = arena_[neighbour.state + q.slotOf[neighbour.master]];
    ++count;
    sum += value;
    low = std::min(low, value);
    high = std::max(high, value);
  }
  switch (q.kind) {
    case AggregateKind::Count:
      return count;
    case AggregateKind::Sum:
      return sum;
    case AggregateKind::Mean:
      return count > 0 ? sum / count : 0.0;
    case AggregateKind::Min:
      return count > 0 ? low : 0.0;
    case AggregateKind::Max:
      return count > 0 ? high : 0.0;
  }
  return 0.0;
}

}  // namespace ontogen
