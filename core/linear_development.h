#pragma once
// Development of a linear pool over one step: per-step rules at the start, then the
// terminal-age events of the interval in time order (right to left in a block with a
// new right context `>>`). The word is rebuilt into a second
// buffer (parallel rewriting: every cell reads the word as it was), then swapped in; the
// buffers are kept from step to step.

#include <vector>

#include "core/development.h"
#include "core/parallel_rewrite.h"
#include "core/pool_view.h"
#include "core/rate_integrator.h"
#include "core/rule_evaluator.h"
#include "core/successors.h"
#include "pools/linear_pool.h"

namespace ontogen {

class LinearDevelopment final : public Development {
 public:
  LinearDevelopment(const Program& program, const SystemDefinition& system);
  LinearDevelopment(const LinearDevelopment& other);
  LinearDevelopment& operator=(const LinearDevelopment&) = delete;

  std::unique_ptr<Development> clone() const override { return std::make_unique<LinearDevelopment>(*this); }
  const Pool& pool() const override { return pool_; }
  Pool& pool() override { return pool_; }
  const LinearPool& linearPool() const { return pool_; }
  void seed(StepContext& context) override;
  void step(StepContext& context, double t1, bool stepRules) override;
  std::array<double, 3> positionOf(size_t i) const override { return {static_cast<double>(i), 0, 0}; }
  /// The pool's word, the previous one, kept to write the next word into, and the scratch
  /// buffers a step keeps for the next (scratchBytes).
  uint64_t heldBytes() const override;

 private:
  void applyStepRules(double t);
  void integrateAndExpire(double t, double t1);
  void expireUntil(double t, double t1);
  void expireContextFree(double t1);
  void expireInTimeOrder(double t, double t1);
  void expireBackward(double instant);
  /// The step of a label-only word kept compact (docs/COMPACT_WORDS.md): instant by instant
  /// as expireInTimeOrder, each instant rewritten by ParallelRewrite::rewriteCompact.
  void expireCompact(double t, double t1);

  /// Fires the terminal rules of a cell that reached its terminal age at `when`.
  /// `index` is its position in the current word (for context), or -1 for a newborn.
  /// `position` is the index of the cell (or its ancestor) in the word at the step's start.
  void expire(const CellRecord& cell, const double* state, double when, int64_t index, int64_t position);
  void fireStepRules(const CellRecord& cell, double t, size_t index);

  double* loadFrame(const CellRecord& cell, const double* state, double when, int64_t position);
  bool matchContext(const CompiledRule& rule, size_t index, double* frame);
  const CompiledRule* chooseRule(const std::vector<CompiledRule>& rules, int64_t index, double* frame,
                                 RandomStream& random, const EvalContext& context);
  /// The decomposition pass over the word just produced at `when` (docs/LANGUAGE.md 4.9).
  void decomposeWord(double when);
  /// Emits `cell` decomposed: rewritten by its first matching decomposition rule, its
  /// successors decomposed in turn while `depth` ≤ the system's maximum depth.
  void decompose(const CellRecord& cell, const double* state, double when, int64_t position, int depth);
  void emitSuccessors(const CompiledRule& rule, const CellRecord& cell, const double* frame, double when,
                      BirthCause cause, const EvalContext& context);
  void emit(const CellRecord& cell, const double* values, uint32_t count);
  /// Turns a compact word back into records, counted before they are made.
  void storeRecords();
  void beginWord();
  void finishWord();
  /// Checks the limits with what the word holds, and `copying` bytes more of an array
  /// being copied as it grows.
  void checkLimits(uint64_t copying = 0);
  /// The scratch buffers kept from step to step, by their capacity: the expansions within
  /// a step, the cells still to expire (with the values of a whole chain of cells born and
  /// expiring in one step) and the per-cell lists of a pass (parents, a cut's cells).
  /// The rule frames are of a fixed size, counted in World::kWorldBytes.
  uint64_t scratchBytes() const;

  const Program& program_;
  const SystemDefinition& system_;
  LinearPool pool_;
  StepContext* context_ = nullptr;  // of the step under way
  FunctionTable functions_;
  SuccessorWriter successors_;
  std::vector<double> frame_;
  std::vector<std::vector<double>> decompositionFrames_;  // one per level of the decomposition
  // The next word is built here and swapped with the pool's (kept to reuse the memory).
  CellArray nextCells_;
  StateArray nextState_;
  double lastGrowth_ = 1;  ///< size ratio of the last rebuilt word, to reserve the next
  // Where emit() writes: the next word, or the scratch list of a context-free expansion.
  CellArray* outCells_ = nullptr;
  StateArray* outState_ = nullptr;
  CellArray expandedCells_;
  StateArray expandedState_;
  std::vector<std::pair<const CompiledRule*, double>> candidates_;  // stochastic alternatives
  CellArray work_;                                                  // cells still to expire, last = next
  StateArray workState_;
  uint64_t eventsThisStep_ = 0;
  uint64_t checkInterval_ = 1;    // cells made between growth checks (growthCheckInterval)
  uint64_t sinceCheck_ = 0;       // cells made since the last check
  int activeGroup_ = 0;           // the rule group of the step under way (`use group:`)
  std::vector<uint8_t> dropped_;  // a backward pass: the cells a cut leaves out
  void findParents();
  /// The earliest birth + lifetime of the word's cells (kForever for an empty word).
  double earliestDeath();
  /// Whether a cell of the word reaches its terminal age by `horizon`.
  bool anyExpires(double horizon);
  bool readsParents_ = false;         // some rule reads me.parent
  std::vector<int64_t> parentIndex_;  // of the word at the start of the pass
  std::vector<double> parentValues_;  // me.parent of each cell of that word
  ParallelRewrite parallel_;          // the context-free pass of a large word on every core
  // Whether the word is kept compact between steps: every master's rules compare labels
  // only, without context in a word with brackets, or evaluate their successors' values
  // in batches (ParallelRewrite::appliesToCompactWords), and no per-step rule, rate,
  // me.parent or environment needs the records. Steps the compact pass cannot take
  // (lineage logged, slices turned off, a limit about to be passed) turn the word back
  // into records.
  bool compactWords_ = false;
  uint64_t compactModuleBound_ = 0;  // the most bytes a module of a compact word may take
  CompactWord nextWord_;             // the next compact word is written here, then swapped in
  // The earliest terminal age in the word, for the pool's structure version it was found
  // at: only a new word changes it, so most steps of an animation ask without a scan.
  double earliestDeath_ = kForever;
  uint64_t earliestVersion_ = UINT64_MAX;
  LinearPoolView view_;
  RuleEvaluator<LinearPoolView> evaluator_;                // per-step rules; count(), sum(x) ... for terminal rules too
  std::unique_ptr<RateIntegrator<LinearPoolView>> rates_;  // made on the first step that needs it; not copied
  uint32_t matched_[kMaxContextItems];                     // cells matched by the context being tested
};

}  // namespace ontogen
