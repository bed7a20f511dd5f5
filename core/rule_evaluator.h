#pragma once
// Evaluates rules for one cell at a time against a pool view: loads the rule frame
// (state, internal state, context values) from a state arena, which is the pool's own
// or an integrator's intermediate stage, and answers the rule's neighbour aggregates
// from the same arena, so everything a rule reads comes from one instant.

#include <vector>

#include "core/pool_view.h"
#include "lang/program.h"

namespace ontogen {

class RuleEvaluator final : public NeighbourAggregates {
 public:
  RuleEvaluator(const Program& program, const PoolView& view);

  /// Starts on cell i at `time`, reading state values from `arena`. Returns the frame.
  double* load(size_t i, const double* arena, double time);
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
  const Program& program_;
  const PoolView& view_;
  const Pool& pool_;  // the view's, asked once
  std::vector<double> frame_;
  const double* arena_ = nullptr;
  size_t cell_ = 0;
  const CompiledRule* rule_ = nullptr;
  mutable int neighbourCount_ = -1;  // found on the first aggregate of a cell
  mutable std::vector<uint32_t> neighbours_;
  mutable const uint32_t* neighbourList_ = nullptr;
  const uint32_t* tableOffsets_ = nullptr;
  const uint32_t* tableCells_ = nullptr;
  uint32_t left_[64];
  uint32_t right_[64];
};

/// Frame slots any rule of the program needs.
size_t ruleFrameSize(const Program& program);

}  // namespace ontogen
