#pragma once
// The rates of a full grid integrated as stencils over its state array. When every site
// holds a cell of one master, cell i's state starts at i * n and every cell integrates the
// same equations (no rate rule has a condition), the neighbour at an offset of the grid is
// a fixed distance away in the state array from every cell not at an edge: sums and
// counts over neighbours are read there, without a table of neighbours; cells at an edge
// ask the grid, whose boundary decides.
//
// RK4's stages are fused with the evaluation of the rates: each pass over the cells
// evaluates the derivative at one stage and, in the same pass, writes the next stage's
// input and adds the stage to the step's result. No derivative array is kept; three
// arrays the size of the state are, and a copy of the state where the stencil holds it a
// variable at a time, from step to step (and, through the large block cache, from world
// to world): a step allocates nothing.
//
// Where every aggregate is a sum or a count, the stencil's arrays hold the state a
// variable at a time (all cells' u, then all cells' v): a neighbour sum is then a run of
// consecutive values and each equation's code (model/expression_batch.h) reads its
// operands where they lie. The grid's state is copied in at the start of a step and the
// last stage writes it back.
//
// The arithmetic is Boost.Odeint's runge_kutta4, operation for operation, zero
// coefficients included (1.0 * x + 0.0 * k is not x when x is -0 or k is not finite),
// and each rate is the batch evaluation of the general path with aggregates of the same
// bits: the result is the general path's to the bit, whatever the thread count.

#include <array>
#include <cstdint>
#include <vector>

#include "core/rule_evaluator.h"
#include "model/expression.h"
#include "model/expression_batch.h"
#include "model/program.h"
#include "pools/grid_pool.h"

namespace ontogen {

class RateStencil {
 public:
  /// Plans the integration of `grid` as it is now (kept while its structure does not
  /// change). False when the plan does not apply: a site is empty, two masters share the
  /// grid, the state is not laid out cell after cell, or an equation has a condition,
  /// draws random numbers or reads more than its cell's state and its neighbours'
  /// aggregates. The caller then takes the general path.
  bool prepare(const Program& program, const GridPool& grid);
  /// Bytes of the tables of edge cells and their neighbours prepare() makes for a full
  /// grid of `shape`, at most (a closed boundary leaves out the neighbours it has not).
  static uint64_t edgeTableBytes(const GridShape& shape);
  /// Bytes of the prepared grid's edge tables.
  uint64_t edgeTableBytes() const {
    return (edgeCells_.size() + edgeStart_.size()) * sizeof(uint32_t) + edgeRefs_.size() * sizeof(NeighbourRef);
  }
  /// Rate equations of the prepared grid: its cells times its master's rate variables.
  size_t equations() const { return cells_ * equations_.size(); }
  /// One classic RK4 step of length dt of the prepared grid's state `x`, in place.
  /// `context` gives the evaluation's seed, random stream and ancestors' values.
  void step(StateArray& x, double dt, const EvalContext& context, unsigned threads);

 private:
  /// Cells a batch takes at most: a batch stays within a row of the grid.
  static constexpr int kLanes = BatchCode::kLanes;
  struct Equation {
    const CompiledRule* rule;
    const StateCalculation* calculation;
  };
  /// Neighbour aggregate of a rule, with the master's variable it reads.
  struct Query {
    const AggregateQuery* query;
    bool matches;  ///< neighbours (all of the master) pass the query's label
    int slot;      ///< the variable summed in a neighbour's state, -1: none
  };
  enum class Stage : uint8_t { First, Second, Third, Fourth };
  /// One stage over cells [begin, end): their rates from `in`, then the stage's sums, the
  /// last into the grid's state `out`.
  template <Stage which>
  void stage(const double* in, double* x, double* out, double dt, const EvalContext& context, size_t begin,
             size_t end);
  /// The rates of `lanes` cells from `first`, within one row of the grid, from `in`.
  void rates(size_t first, int lanes, const double* in, const EvalContext& context,
             double (*values)[BatchCode::kLanes]) const;
  /// Aggregate `q` of the lanes from `first` (within one row) into out[lane]: a stencil
  /// over the state for the lanes whose neighbours are inside the grid, the neighbours
  /// the grid gave prepare() for the lanes at an edge.
  /// `firstEdge`: the first of edgeCells_ at or after `first`.
  void gather(const Query& q, size_t first, int lanes, bool insideRow, size_t firstEdge, const double* in,
              double* out) const;
  /// Aggregate `q` of a cell whose neighbours are all inside the grid, or of edge cell
  /// edgeCells_[edge].
  double inside(const Query& q, size_t cell, const double* in) const;
  double atEdge(const Query& q, size_t edge, const double* in) const;
  bool rowInside(size_t first) const;

  const GridPool* grid_ = nullptr;
  uint64_t version_ = UINT64_MAX;
  bool applies_ = false;
  uint32_t master_ = 0;
  uint32_t stride_ = 0;  // state values per cell
  size_t cells_ = 0;
  // The stencil's arrays hold variable s of cell i at i * cellStep_ + s * slotStep_: a
  // variable at a time (1, cells_) where byVariable_, else as the grid does (stride_, 1).
  bool byVariable_ = false;
  size_t cellStep_ = 1, slotStep_ = 1;
  std::vector<Equation> equations_;
  std::vector<BatchCode> code_;                // per equation: its rate as batch code (read a variable at a time)
  std::vector<int> equationOf_;                // per state slot: its equation, -1: constant while integrating
  std::vector<std::vector<Query>> queries_;    // per equation: its rule's aggregates
  std::vector<int64_t> deltas_;                // per neighbourhood offset: cells away
  std::vector<int64_t> strideDeltas_;          // the same in state values
  std::vector<uint32_t> edgeCells_;       // the cells with a neighbour across an edge, in order
  std::vector<uint32_t> edgeStart_;       // per edge cell and one more: where its neighbours start in edgeRefs_
  std::vector<NeighbourRef> edgeRefs_;    // their neighbours, in the grid's order
  std::array<uint32_t, 3> size_{1, 1, 1};
  int dimensions_ = 1;
  // The input of stages 2 and 4 (the state itself holds stage 3's: after the first pass
  // the step needs x only through the two sums), the running zero-coefficient sum
  // odeint's stages 2 and 3 start from, and the step's result being summed.
  StateArray stageA_, zeroSum_, result_;
  // The state at the step's start a variable at a time, where the grid's layout is not the stencil's.
  StateArray stateByVariable_;
};

}  // namespace ontogen
