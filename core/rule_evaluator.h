#pragma once
// Evaluates rules for one cell at a time against a pool view: loads the rule frame
// (state, internal state, context values) from a state arena, which is the pool's own
// or an integrator's intermediate stage, and answers the rule's neighbour aggregates
// from the same arena, so everything a rule reads comes from one instant.
//
// A template on the pool's view (core/pool_view.h): the per-cell calls (position,
// context, neighbours) are direct calls, inlined where they are small. The expression
// interpreter asks for aggregates through NeighbourAggregates, once per aggregate read.

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <vector>

#include "core/cell_frame.h"
#include "core/pool_view.h"
#include "model/program.h"

namespace ontogen {

/// Frame slots any rule of the program needs.
size_t ruleFrameSize(const Program& program);

template <typename View>
class RuleEvaluator final : public NeighbourAggregates {
 public:
  RuleEvaluator(const Program& program, const View& view)
      : program_(program), view_(view), pool_(view.pool()), frame_(ruleFrameSize(program)) {}

  /// Starts on cell i at `time`, reading state values from `arena`. Returns the frame.
  double* load(size_t i, const double* arena, double time) {
    cell_ = i;
    arena_ = arena;
    neighbourCount_ = -1;
    rule_ = nullptr;
    const CellCursor& cell = cursorAt(i);
    const MasterCell& master = program_.masters[cell.master()];
    const uint32_t n = master.stateCount();
    double* frame = frame_.data();
    const double* state = arena + cell.stateOffset();
    std::copy(state, state + n, frame);
    loadAgeAndId(frame + n, cell.birth(), cell.id(), master.lifetime, time);
    // Positions cost a lookup in grids and spatial pools: only for masters that read them.
    if (master.readsPosition || master.readsParent)
      loadPlace(frame + n, master.readsPosition ? view_.position(i) : std::array<double, 3>{},
                parents_ ? parents_[i] : parent_);
    return frame;
  }
  /// What `me.parent` reads for every cell (grid and spatial pools: the system cell).
  void useParent(double parent) { parent_ = parent; }
  /// Or per cell, indexed like the pool (linear pools: the axial tree); null: useParent's.
  void useParents(const double* perCell) { parents_ = perCell; }
  /// Checks `rule`'s positional context around the loaded cell and copies the bound
  /// neighbour values into the frame; makes `rule` the one aggregates answer for.
  bool bind(const CompiledRule& rule);
  /// For callers with their own frame: aggregates of cell i, from `arena`, for `rule`.
  void focus(size_t i, const double* arena) {
    cell_ = i;
    arena_ = arena;
    neighbourCount_ = -1;
  }
  void useRule(const CompiledRule& rule) { rule_ = &rule; }
  /// Neighbours found once for a whole pass in which the pool's structure is fixed
  /// (compressed rows: cells offsets[i] .. offsets[i+1] of `cells`); null: ask the view.
  void useNeighbourTable(const uint32_t* offsets, const uint32_t* cells) {
    tableOffsets_ = offsets;
    tableCells_ = cells;
  }
  /// Fires the loaded cell's per-step rules in order against `context` (whose frame is
  /// this evaluator's): rate-only rules are left to the integrator; a rule whose context,
  /// predicate and probability hold writes its calculations into the frame, and the first
  /// one with an action ends the pass. Returns that rule, or null; counts firings.
  const CompiledRule* fireStepRules(const MasterCell& master, const EvalContext& context, RandomStream& random,
                                    uint64_t& firings);
  double aggregate(int query) const override;
  double* frame() { return frame_.data(); }
  size_t cell() const { return cell_; }

 private:
  // A cursor on cell i: the cursor of the last load steps on to the next cell (passes
  // load cells in index order); any other cell is found anew (in a pool that counts its
  // values, a walk in its block).
  const CellCursor& cursorAt(size_t i) {
    if (cursor_ && cursorVersion_ == pool_.structureVersion()) {
      if (cursor_->index() == i) return *cursor_;
      if (cursor_->index() + 1 == i) {
        cursor_->next();
        return *cursor_;
      }
    }
    cursor_.emplace(pool_.cursor(i));
    cursorVersion_ = pool_.structureVersion();
    return *cursor_;
  }
  // Where the values of cell j, a neighbour of the loaded cell, start: counted from the
  // loaded cell where the cursor is on it.
  size_t stateOffsetNear(size_t j) const {
    if (pool_.countsValues() && cursor_ && cursorVersion_ == pool_.structureVersion() && cursor_->index() == cell_)
      return pool_.stateOffsetNear(j, cell_, cursor_->stateOffset());
    return pool_.stateOffset(j);
  }

  const Program& program_;
  const View& view_;
  const Pool& pool_;  // the view's, asked once
  std::optional<CellCursor> cursor_;  // of the last load (cursorAt)
  uint64_t cursorVersion_ = 0;
  std::vector<double> frame_;
  const double* arena_ = nullptr;
  double parent_ = -1;
  const double* parents_ = nullptr;
  size_t cell_ = 0;
  const CompiledRule* rule_ = nullptr;
  mutable int neighbourCount_ = -1;  // found on the first aggregate of a cell
  mutable std::vector<uint32_t> neighbours_;
  mutable const uint32_t* neighbourList_ = nullptr;
  const uint32_t* tableOffsets_ = nullptr;
  const uint32_t* tableCells_ = nullptr;
  uint32_t left_[kMaxContextItems];
  uint32_t right_[kMaxContextItems];
};

template <typename View>
bool RuleEvaluator<View>::bind(const CompiledRule& rule) {
  rule_ = &rule;
  if (!rule.hasContext()) return true;
  if (!view_.matchContext(rule, cell_, left_, right_)) return false;
  auto copy = [&](const std::vector<ContextBinding>& bindings, const uint32_t* matched) {
    for (size_t k = 0; k < bindings.size(); ++k) {
      const ContextBinding& binding = bindings[k];
      if (binding.count == 0) continue;
      const double* values = arena_ + stateOffsetNear(matched[k]);
      std::copy(values, values + binding.count, frame_.data() + binding.firstSlot);
    }
  };
  copy(rule.left, left_);
  copy(rule.right, right_);
  return true;
}

template <typename View>
const CompiledRule* RuleEvaluator<View>::fireStepRules(const MasterCell& master, const EvalContext& context,
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

/// What an aggregate reads of a neighbour: its master and where its state starts.
struct NeighbourRef {
  uint32_t master;
  uint32_t state;
};

/// Neighbour aggregate `q` over `count` neighbours, at(k) the k-th (a NeighbourRef or a
/// CellRecord), their values in `arena`: what count(), sum(x), mean(x), min(x) and
/// max(x) answer.
template <typename At>
double aggregateOver(const AggregateQuery& q, int count, At&& at, const double* arena) {
  if (q.kind == AggregateKind::Sum && q.label < 0) {
    // The common case (diffusion): a plain sum, without the bookkeeping of the others.
    double sum = 0;
    for (int k = 0; k < count; ++k) {
      const auto& neighbour = at(k);
      if (neighbour.master < q.slotOf.size() && q.slotOf[neighbour.master] >= 0)
        sum += arena[neighbour.state + q.slotOf[neighbour.master]];
    }
    return sum;
  }
  if (q.kind == AggregateKind::Count && q.label < 0) return count;
  double counted = 0, sum = 0;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (int k = 0; k < count; ++k) {
    const auto& neighbour = at(k);
    if (q.label >= 0 && neighbour.master != static_cast<uint32_t>(q.label)) continue;
    if (q.kind == AggregateKind::Count) {
      ++counted;
      continue;
    }
    if (neighbour.master >= q.slotOf.size() || q.slotOf[neighbour.master] < 0) continue;
    const double value = arena[neighbour.state + q.slotOf[neighbour.master]];
    ++counted;
    sum += value;
    low = std::min(low, value);
    high = std::max(high, value);
  }
  switch (q.kind) {
    case AggregateKind::Count:
      return counted;
    case AggregateKind::Sum:
      return sum;
    case AggregateKind::Mean:
      return counted > 0 ? sum / counted : 0.0;
    case AggregateKind::Min:
      return counted > 0 ? low : 0.0;
    case AggregateKind::Max:
      return counted > 0 ? high : 0.0;
  }
  return 0.0;
}

template <typename View>
double RuleEvaluator<View>::aggregate(int query) const {
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
  const auto cells = pool_.cells();
  return aggregateOver(
      rule_->aggregates[query], neighbourCount_,
      [&](int k) {
        const uint32_t cell = neighbourList_[k];
        return NeighbourRef{cells[cell].master, static_cast<uint32_t>(stateOffsetNear(cell))};
      },
      arena_);
}

}  // namespace ontogen
