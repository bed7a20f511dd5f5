#pragma once
// The context-free rewriting of a large linear word on every core. Each thread takes a
// slice of the word; a first pass counts what each slice will write (the cells and state
// values of its successors, which for a rule without condition, chance or context are
// fixed per master), prefix sums give each slice its place in the next word, and a second
// pass writes every slice in place. The next word is bit for bit the one the serial pass
// writes, whatever the thread count: ids and random streams derive from each cell alone.
//
// It applies when every master of the system rewrites without a choice: at most one
// terminal rule, of group 0, with no predicate, probability, context, neighbour
// aggregate or birth age, and no cut symbol; and in a step where no successor reaches its
// own terminal age before the step's end and the limits are not passed. Otherwise the
// development takes its serial pass (which reports a limit as it always did).

#include <cstdint>
#include <memory>
#include <vector>

#include "core/development.h"
#include "core/successors.h"
#include "lang/program.h"
#include "pools/linear_pool.h"

namespace ontogen {

class ParallelRewrite {
 public:
  ParallelRewrite(const Program& program, const SystemDefinition& system);

  /// Whether the system's rules allow it at all.
  bool applies() const { return applies_; }

  /// Rewrites `pool`'s word for the step ending at `horizon` into `cells` and `state`
  /// (emptied first), with `parents` the me.parent value of each cell (null when no rule
  /// reads it). Returns false, leaving them empty, when the step needs the serial pass;
  /// else adds the step's events and births to `events` and `context.stats`.
  bool rewrite(const LinearPool& pool, double horizon, StepContext& context, const double* parents,
               uint64_t& events, CellArray& cells, StateArray& state);

  /// Words smaller than this go the serial way: threads would cost more than they save.
  static constexpr size_t kMinimumCells = size_t{1} << 15;

 private:
  struct PerMaster {
    const CompiledRule* rule = nullptr;  // its only terminal rule; null: it renews itself
    uint32_t cells = 1;                  // cells written when it expires
    uint32_t values = 0;                 // state values written when it expires
    uint32_t born = 0;                   // new cells among them (not `me`)
    double shortestLife = kForever;      // the shortest lifetime among what it writes
  };
  struct Slice {
    size_t begin = 0, end = 0;    // cells of the word
    uint64_t cells = 0, values = 0, events = 0, born = 0;
    bool chained = false;         // a successor expires within the step
  };
  struct Worker {
    explicit Worker(const Program& program) : successors(program) {}
    SuccessorWriter successors;
    std::vector<double> frame;
  };

  void count(const LinearPool& pool, double horizon, Slice& slice) const;
  void write(const LinearPool& pool, double horizon, const StepContext& context, const double* parents,
             const Slice& slice, uint64_t firstCell, uint64_t firstValue, Worker& worker, CellArray& cells,
             StateArray& state) const;

  const Program& program_;
  bool applies_ = true;
  std::vector<PerMaster> masters_;
  FunctionTable functions_;
  std::vector<Slice> slices_;
  std::vector<std::unique_ptr<Worker>> workers_;
  size_t frameSize_ = 0;
};

}  // namespace ontogen
