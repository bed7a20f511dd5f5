#pragma once
// The one per-step rule pass of the pools that develop in parallel (grid and spatial):
// every cell, in chunks over the threads, loads its frame, draws from its own stream
// keyed by (seed ^ kStepRuleSalt, id, t) and fires its per-step rules
// (RuleEvaluator::fireStepRules); what becomes of the cell and its successors is the
// pool's own, in `place`. The linear pool fires the same rules through the same
// evaluator one cell at a time (its context is branch-aware and its word is rebuilt in
// order), in LinearDevelopment::fireStepRules.

#include <utility>
#include <vector>

#include "core/development.h"
#include "core/parallel_for.h"
#include "core/rule_evaluator.h"
#include "core/salts.h"
#include "core/successors.h"

namespace ontogen {

/// Runs the pass over `view`'s pool at context.time. `Chunk` is what one chunk of cells
/// produces, with at least `uint64_t firings` and `std::vector<LineageRecord> lineage`;
/// `results` gets one per worker. For each cell calls
/// `place(Chunk&, size_t i, const CellView&, double* frame, const CompiledRule* action,
///        const EvalContext&, SuccessorWriter&)`, `action` null when no rule with an action fired.
/// `table`, when given, holds every cell's neighbours as compressed rows (offsets, cells),
/// found once for the pass (RuleEvaluator::useNeighbourTable).
template <typename View, typename Chunk, typename Place>
void runStepRules(const Program& program, const StepContext& context, const View& view, std::vector<Chunk>& results,
                  Place&& place, const std::pair<const uint32_t*, const uint32_t*>& table = {nullptr, nullptr}) {
  const double t = context.time;
  const Pool& pool = view.pool();
  const double* arena = pool.stateArena().data();
  const uint64_t seed = context.seed;
  const FunctionTable functions = program.functionTable();
  results.assign(context.threads, Chunk{});
  parallelFor(pool.size(), context.threads, [&](size_t begin, size_t end, unsigned worker) {
    Chunk& out = results[worker];
    RuleEvaluator<View> evaluator(program, view);
    evaluator.useParent(context.systemCellId);
    evaluator.useNeighbourTable(table.first, table.second);
    SuccessorWriter successors(program);
    if (context.lineage) successors.recordLineage(&out.lineage);
    for (CellCursor cursor = pool.cursor(begin); cursor.index() < end; cursor.next()) {
      const size_t i = cursor.index();
      const CellView cell = cursor.view();
      double* frame = evaluator.load(i, arena, t);
      RandomStream random(mixKey(mixKey(seed ^ kStepRuleSalt, cell.id), keyOf(t)));
      EvalContext evaluation{frame, EvalEnvironment{&random, seed}, &functions, &evaluator};
      evaluation.ancestors = context.ancestors;
      const CompiledRule* action = evaluator.fireStepRules(program.masters[cell.master], evaluation, random, out.firings);
      place(out, i, cell, frame, action, evaluation, successors);
    }
  });
}

}  // namespace ontogen
