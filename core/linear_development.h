#pragma once
// Development of a linear pool over one step: per-step rules at the start, then the
// terminal-age events of the interval in time order. The word is rebuilt into a second
// buffer (parallel rewriting: every cell reads the word as it was), then swapped in.

#include <vector>

#include "core/pool_view.h"
#include "core/rule_evaluator.h"
#include "core/world.h"

namespace ontogen {

class LinearDevelopment {
 public:
  explicit LinearDevelopment(World& world);

  /// Develops the world's root pool from world.time() to t1; per-step rules fire at
  /// the start when `stepRules` (the world decides: only on its step grid).
  void step(double t1, bool stepRules);

 private:
  void applyStepRules(double t);
  void integrateAndExpire(double t, double t1);
  void expireUntil(double t1);
  void expireContextFree(double t1);
  void expireInTimeOrder(double t1);

  /// Fires the terminal rules of a cell that reached its terminal age at `when`.
  /// `index` is its position in the current word (for context), or -1 for a newborn.
  /// `position` is the index of the cell (or its ancestor) in the word at the step's start.
  void expire(const CellRecord& cell, const double* state, double when, int64_t index, int64_t position);
  void fireStepRules(const CellRecord& cell, const double* state, double t, size_t index);

  double* loadFrame(const CellRecord& cell, const double* state, double when, int64_t position);
  bool matchContext(const CompiledRule& rule, size_t index, double* frame);
  const CompiledRule* chooseRule(const std::vector<CompiledRule>& rules, int64_t index, double* frame,
                                 RandomStream& random, const EvalContext& context);
  void emitSuccessors(const CompiledRule& rule, const CellRecord& cell, const double* frame, double when, bool renewMe,
                      const EvalContext& context);
  void emit(const CellRecord& cell, const double* values, uint32_t count);
  void pushCell(const CellRecord& cell);
  void beginWord();
  void finishWord();
  void checkLimits(size_t cells);
  [[noreturn]] void modelError(const SourceSpan& span, const std::string& message) const;

  World& world_;
  const Program& program_;
  const SystemDefinition& system_;
  LinearPool& pool_;
  FunctionTable functions_;
  std::vector<double> frame_;
  // The word being built and, for context-free expansion, a stack of cells still to expire.
  CellArray& nextCells_;
  StateArray& nextState_;
  // Where emit() writes: the next word, or the scratch list of a context-free expansion.
  CellArray* outCells_ = nullptr;
  StateArray* outState_ = nullptr;
  CellArray expandedCells_;
  StateArray expandedState_;
  std::vector<double> values_;
  std::vector<std::pair<const CompiledRule*, double>> candidates_;  // stochastic alternatives
  CellArray work_;                                                  // cells still to expire, last = next
  StateArray workState_;
  uint64_t eventsThisStep_ = 0;
  LinearPoolView view_;
  RuleEvaluator aggregates_;  // answers count(), sum(x) ... for the cell being evaluated
  uint32_t matched_[64];      // cells matched by the context being tested (patterns are short)
};

}  // namespace ontogen
