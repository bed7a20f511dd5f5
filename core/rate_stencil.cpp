#include "core/rate_stencil.h"

#include <algorithm>
#include <type_traits>

#include "core/parallel_for.h"
#include "core/rule_evaluator.h"
#include "model/expression_batch.h"

namespace ontogen {

namespace {
// A batch's rates live on the stack, one row of lanes per equation; a master with more
// rate variables than this (none of the models comes near) takes the general path.
constexpr size_t kMaxEquations = 16;
// The same for the neighbour aggregates of one rule.
constexpr size_t kMaxQueries = 16;
// A batch's state is read a variable at a time up to this many variables a cell (every
// model's cells hold fewer), else in place.
constexpr size_t kMaxTransposed = 16;
}  // namespace

bool RateStencil::prepare(const Program& program, const GridPool& grid) {
  if (grid_ == &grid && version_ == grid.structureVersion()) return applies_;
  grid_ = &grid;
  version_ = grid.structureVersion();
  applies_ = false;
  equations_.clear();
  queries_.clear();
  const auto cells = grid.cells();
  if (cells.empty() || cells.size() != grid.siteCount()) return false;
  master_ = cells[0].master;
  const MasterCell& master = program.masters[master_];
  stride_ = master.stateCount();
  if (grid.stateArena().size() != cells.size() * stride_) return false;
  for (size_t i = 0; i < cells.size(); ++i)
    if (cells[i].master != master_ || cells[i].state != i * stride_) return false;
  // Every cell's equations, as RateIntegrator::activate finds them for one cell.
  for (const CompiledRule& rule : master.rules) {
    if (!rule.hasRate) continue;
    if (rule.hasContext() || !rule.predicate.empty() || !rule.probability.empty()) return false;
    for (const StateCalculation& calculation : rule.calculations) {
      if (!calculation.isRate) continue;
      if (!calculation.value.batchable(static_cast<int>(stride_))) return false;
      // A later rule's rate for the same variable replaces an earlier one.
      std::erase_if(equations_, [&](const Equation& e) { return e.calculation->slot == calculation.slot; });
      equations_.push_back({&rule, &calculation});
    }
  }
  if (equations_.empty() || equations_.size() > kMaxEquations) return false;
  code_.clear();
  equationOf_.assign(stride_, -1);
  for (size_t e = 0; e < equations_.size(); ++e) {
    const StateCalculation& calculation = *equations_[e].calculation;
    if (calculation.slot < 0 || calculation.slot >= static_cast<int>(stride_)) return false;
    equationOf_[static_cast<size_t>(calculation.slot)] = static_cast<int>(e);
    if (equations_[e].rule->aggregates.size() > kMaxQueries) return false;
    if (stride_ <= kMaxTransposed &&
        !code_.emplace_back().compile(calculation.value, static_cast<int>(stride_),
                                      static_cast<int>(equations_[e].rule->aggregates.size())))
      return false;
    std::vector<Query>& queries = queries_.emplace_back();
    for (const AggregateQuery& query : equations_[e].rule->aggregates) {
      const bool matches = query.label < 0 || query.label == static_cast<int>(master_);
      const int slot = master_ < query.slotOf.size() ? query.slotOf[master_] : -1;
      queries.push_back({&query, matches, slot});
    }
  }
  // A variable at a time when every aggregate is a sum or a count (the sums over
  // neighbours and the equations' operands are then runs of consecutive values); cell
  // after cell, as the grid holds them, when a rule asks for a mean, a minimum or a maximum.
  byVariable_ = stride_ <= kMaxTransposed;
  for (const std::vector<Query>& queries : queries_)
    for (const Query& q : queries)
      if (q.query->kind != AggregateKind::Sum && q.query->kind != AggregateKind::Count) byVariable_ = false;
  cells_ = cells.size();
  cellStep_ = byVariable_ ? 1 : stride_;
  slotStep_ = byVariable_ ? cells_ : 1;
  const GridShape& shape = grid.shape();
  dimensions_ = shape.dimensions;
  size_ = shape.size;
  deltas_.clear();
  strideDeltas_.clear();
  for (const GridCoordinates& offset : grid.offsets()) {
    deltas_.push_back(offset[0] + offset[1] * int64_t{size_[0]} + offset[2] * int64_t{size_[0]} * size_[1]);
    strideDeltas_.push_back(deltas_.back() * static_cast<int64_t>(cellStep_));
  }
  // The neighbours of the cells at an edge, found once: the structure does not change
  // while the plan holds, and asking the grid for them in every stage cost more than the
  // rates of a small grid. A row inside has its first and last cell at an edge.
  edgeCells_.clear();
  edgeStart_.assign(1, 0);
  edgeRefs_.clear();
  uint32_t sites[GridPool::kMaxNeighbours];
  auto addEdge = [&](size_t cell) {
    const int offsets = grid.neighbourSites(static_cast<uint32_t>(cell), sites);  // full: site i holds cell i
    for (int k = 0; k < offsets; ++k)
      if (sites[k] != GridPool::kEmpty)
        edgeRefs_.push_back(NeighbourRef{master_, static_cast<uint32_t>(grid.cellAt(sites[k]) * cellStep_)});
    edgeCells_.push_back(static_cast<uint32_t>(cell));
    edgeStart_.push_back(static_cast<uint32_t>(edgeRefs_.size()));
  };
  const size_t width = size_[0];
  for (size_t first = 0; first < cells_; first += width) {
    if (rowInside(first)) {
      addEdge(first);
      if (width > 1) addEdge(first + width - 1);
    } else {
      for (size_t cell = first; cell < first + width; ++cell) addEdge(cell);
    }
  }
  applies_ = true;
  return true;
}

uint64_t RateStencil::edgeTableBytes(const GridShape& shape) {
  // prepare()'s edge cells: the first and last of a row inside the grid along y and z,
  // every cell of another row.
  const uint64_t width = shape.size[0], height = shape.size[1], depth = shape.size[2];
  const uint64_t insideY = shape.dimensions < 2 ? height : (height > 2 ? height - 2 : 0);
  const uint64_t insideZ = shape.dimensions < 3 ? depth : (depth > 2 ? depth - 2 : 0);
  const uint64_t rowsInside = insideY * insideZ;
  const uint64_t edges = rowsInside * std::min<uint64_t>(width, 2) + (height * depth - rowsInside) * width;
  uint64_t neighbours = 2 * static_cast<uint64_t>(shape.dimensions);  // von Neumann
  if (shape.neighbourhood == GridNeighbourhood::Moore) {
    neighbours = 1;
    for (int axis = 0; axis < shape.dimensions; ++axis) neighbours *= 3;
    --neighbours;
  }
  return (2 * edges + 1) * sizeof(uint32_t) + edges * neighbours * sizeof(NeighbourRef);
}

// Whether the row that starts at cell `first` is inside the grid along y and z (the
// neighbourhoods reach one site along each axis).
bool RateStencil::rowInside(size_t first) const {
  const size_t width = size_[0], height = size_[1], depth = size_[2];
  const size_t row = first / width, y = row % height, z = row / height;
  return (dimensions_ < 2 || (y >= 1 && y + 1 < height)) && (dimensions_ < 3 || (z >= 1 && z + 1 < depth));
}

// A cell whose neighbours are all inside the grid: each at its fixed distance.
double RateStencil::inside(const Query& q, size_t cell, const double* in) const {
  const AggregateQuery& query = *q.query;
  const int64_t here = static_cast<int64_t>(cell);
  if (query.kind == AggregateKind::Count) return q.matches ? static_cast<double>(deltas_.size()) : 0.0;
  if (query.kind == AggregateKind::Sum) {
    if (!q.matches || q.slot < 0) return 0.0;
    double sum = 0;  // in the neighbourhood's order, from 0, as aggregateOver sums
    for (int64_t delta : deltas_)
      sum += in[static_cast<size_t>(here + delta) * cellStep_ + static_cast<size_t>(q.slot) * slotStep_];
    return sum;
  }
  return aggregateOver(
      query, static_cast<int>(deltas_.size()),
      [&](int k) {
        return NeighbourRef{master_, static_cast<uint32_t>(static_cast<size_t>(here + deltas_[k]) * stride_)};
      },
      in);
}

// The edge cell edgeCells_[edge]: its neighbours as the grid's boundary gave them to prepare().
double RateStencil::atEdge(const Query& q, size_t edge, const double* in) const {
  const NeighbourRef* around = edgeRefs_.data() + edgeStart_[edge];
  const int count = static_cast<int>(edgeStart_[edge + 1] - edgeStart_[edge]);
  const AggregateQuery& query = *q.query;
  // aggregateOver's sum and count, for neighbours all of the grid's master.
  if (query.kind == AggregateKind::Sum) {
    double sum = 0;
    if (q.matches && q.slot >= 0)
      for (int k = 0; k < count; ++k) sum += in[around[k].state + static_cast<size_t>(q.slot) * slotStep_];
    return sum;
  }
  if (query.kind == AggregateKind::Count) return q.matches ? count : 0;
  return aggregateOver(
      query, count, [&](int k) -> const NeighbourRef& { return around[k]; }, in);
}

void RateStencil::gather(const Query& q, size_t first, int lanes, bool insideRow, size_t firstEdge, const double* in,
                         double* out) const {
  // The lanes [lo, hi) have every neighbour at its fixed distance: in a row inside, all
  // but a first or last cell of the row.
  const size_t width = size_[0], x0 = first % width;
  int lo = lanes, hi = lanes;
  if (insideRow) {
    lo = x0 == 0 ? 1 : 0;
    hi = std::max(lo, x0 + static_cast<size_t>(lanes) == width ? lanes - 1 : lanes);
  }
  // The lanes at an edge are the batch's edge cells, in order.
  size_t edge = firstEdge;
  for (int lane = 0; lane < lo; ++lane) out[lane] = atEdge(q, edge++, in);
  for (int lane = hi; lane < lanes; ++lane) out[lane] = atEdge(q, edge++, in);
  const AggregateQuery& query = *q.query;
  if (query.kind == AggregateKind::Count) {
    const double count = q.matches ? static_cast<double>(deltas_.size()) : 0.0;
    for (int lane = lo; lane < hi; ++lane) out[lane] = count;
    return;
  }
  if (query.kind == AggregateKind::Sum && q.matches && q.slot >= 0) {
    // Lane by lane, each lane's neighbours added in the neighbourhood's order from 0, as
    // aggregateOver sums: the loop over lanes is the one that vectorises.
    const double* at = in + first * cellStep_ + static_cast<size_t>(q.slot) * slotStep_;
    const int64_t* delta = strideDeltas_.data();
    if (strideDeltas_.size() == 4) {  // von Neumann in 2-D: the sum in registers
      const int64_t d0 = delta[0], d1 = delta[1], d2 = delta[2], d3 = delta[3];
      auto sum = [&](auto stride) {  // a stride known to the compiler vectorises
        for (int lane = lo; lane < hi; ++lane) {
          const double* cell = at + static_cast<size_t>(lane) * stride;
          out[lane] = 0.0 + cell[d0] + cell[d1] + cell[d2] + cell[d3];
        }
      };
      if (cellStep_ == 1)
        sum(std::integral_constant<size_t, 1>{});
      else if (cellStep_ == 2)
        sum(std::integral_constant<size_t, 2>{});
      else
        sum(size_t{cellStep_});
      return;
    }
    for (int lane = lo; lane < hi; ++lane) out[lane] = 0;
    for (int64_t d : strideDeltas_) {
      const double* from = at + d;
      if (cellStep_ == 1)
        for (int lane = lo; lane < hi; ++lane) out[lane] += from[lane];
      else
        for (int lane = lo; lane < hi; ++lane) out[lane] += from[static_cast<size_t>(lane) * cellStep_];
    }
    return;
  }
  for (int lane = lo; lane < hi; ++lane) out[lane] = inside(q, first + static_cast<size_t>(lane), in);
}

void RateStencil::rates(size_t first, int lanes, const double* in, const EvalContext& context,
                        double (*values)[kLanes]) const {
  const bool inside = rowInside(first);
  const size_t firstEdge = static_cast<size_t>(
      std::lower_bound(edgeCells_.begin(), edgeCells_.end(), static_cast<uint32_t>(first)) - edgeCells_.begin());
  double aggregates[kMaxQueries][kLanes];
  const double* aggregateLanes[kMaxQueries];
  for (size_t q = 0; q < kMaxQueries; ++q) aggregateLanes[q] = aggregates[q];
  const double* cells = in + first * stride_;  // cell after cell
  if (stride_ > kMaxTransposed) {
    for (size_t e = 0; e < equations_.size(); ++e) {
      const std::vector<Query>& queries = queries_[e];
      for (size_t q = 0; q < queries.size(); ++q)
        gather(queries[q], first, lanes, inside, firstEdge, in, aggregates[q]);
      for (int from = 0; from < lanes; from += CompiledExpression::kBatchLanes)
        equations_[e].calculation->value.evaluateBatch(
            std::min(lanes - from, CompiledExpression::kBatchLanes),
            [&](int lane, int slot) {
              return cells[static_cast<size_t>(from + lane) * stride_ + static_cast<size_t>(slot)];
            },
            [&](int lane, int q) { return aggregates[q][from + lane]; }, context, values[e] + from);
    }
    return;
  }
  // The equations' code reads each variable's lanes where they are; cell after cell, the
  // batch's state is copied a variable at a time first.
  double variables[kMaxTransposed][kLanes];
  const double* slotLanes[kMaxTransposed];
  for (size_t slot = 0; slot < stride_; ++slot)
    slotLanes[slot] = byVariable_ ? in + slot * slotStep_ + first : variables[slot];
  if (!byVariable_)
    for (int lane = 0; lane < lanes; ++lane)
      for (size_t slot = 0; slot < stride_; ++slot)
        variables[slot][lane] = cells[static_cast<size_t>(lane) * stride_ + slot];
  for (size_t e = 0; e < equations_.size(); ++e) {
    const std::vector<Query>& queries = queries_[e];
    for (size_t q = 0; q < queries.size(); ++q) gather(queries[q], first, lanes, inside, firstEdge, in, aggregates[q]);
    code_[e].evaluate(lanes, slotLanes, aggregateLanes, context, values[e]);
  }
}

template <RateStencil::Stage which>
void RateStencil::stage(const double* in, double* x, double* out, double dt, const EvalContext& context, size_t begin,
                        size_t end) {
  // odeint's runge_kutta4 coefficients (a, b) times dt, as its generic_rk_scale_sum makes them.
  const double half = 0.5 * dt, zero = 0.0 * dt, whole = 1.0 * dt, sixth = (1.0 / 6.0) * dt, third = (1.0 / 3.0) * dt;
  double* a = stageA_.data();
  double* zeros = zeroSum_.data();
  double* result = result_.data();
  const size_t width = size_[0];
  double values[kMaxEquations][kLanes];
  for (size_t first = begin; first < end;) {
    // A batch stays within a row, so that whether its row is inside is known at once.
    const size_t rowEnd = (first / width + 1) * width;
    const int lanes = static_cast<int>(std::min({size_t{kLanes}, end - first, rowEnd - first}));
    rates(first, lanes, in, context, values);
    // A constant's derivative is 0, as the general path's fill.
    static constexpr double kConstant[kLanes] = {};
    auto sums = [&](auto cellStep) {  // a step known to the compiler vectorises
      for (size_t slot = 0; slot < stride_; ++slot) {
        const int e = equationOf_[slot];
        const double* rate = e >= 0 ? values[e] : kConstant;
        const size_t base = first * cellStep + slot * slotStep_;
        for (int lane = 0; lane < lanes; ++lane) {
          const double k = rate[lane];
          const size_t i = base + static_cast<size_t>(lane) * cellStep;
          if constexpr (which == Stage::First) {  // x + a1 dt k1
            a[i] = 1.0 * x[i] + half * k;
            zeros[i] = 1.0 * x[i] + zero * k;
            result[i] = 1.0 * x[i] + sixth * k;
          } else if constexpr (which == Stage::Second) {  // x + 0 dt k1 + a2 dt k2, into x
            x[i] = zeros[i] + half * k;
            zeros[i] = zeros[i] + zero * k;
            result[i] = result[i] + third * k;
          } else if constexpr (which == Stage::Third) {  // x + 0 dt k1 + 0 dt k2 + dt k3
            a[i] = zeros[i] + whole * k;
            result[i] = result[i] + third * k;
          } else {  // x + dt (k1 / 6 + k2 / 3 + k3 / 3 + k4 / 6), summed left to right, into the grid
            out[(first + static_cast<size_t>(lane)) * stride_ + slot] = result[i] + sixth * k;
          }
        }
      }
    };
    if (cellStep_ == 1)
      sums(std::integral_constant<size_t, 1>{});
    else if (cellStep_ == 2)
      sums(std::integral_constant<size_t, 2>{});
    else
      sums(size_t{cellStep_});
    first += static_cast<size_t>(lanes);
  }
}

void RateStencil::step(StateArray& x, double dt, const EvalContext& context, unsigned threads) {
  // Every element is written by the first pass before any is read.
  resizeForOverwrite(stageA_, x.size());
  resizeForOverwrite(zeroSum_, x.size());
  resizeForOverwrite(result_, x.size());
  double* grid = x.data();
  // The step's input in the stencil's layout: the grid's own state when the layouts agree.
  double* state = grid;
  if (cellStep_ != stride_) {
    resizeForOverwrite(stateByVariable_, x.size());
    state = stateByVariable_.data();
    parallelFor(cells_, threads, [&](size_t begin, size_t end, unsigned) {
      for (size_t slot = 0; slot < stride_; ++slot)
        for (size_t cell = begin; cell < end; ++cell) state[slot * slotStep_ + cell] = grid[cell * stride_ + slot];
    });
  }
  parallelFor(cells_, threads, [&](size_t begin, size_t end, unsigned) {
    stage<Stage::First>(state, state, grid, dt, context, begin, end);
  });
  parallelFor(cells_, threads, [&](size_t begin, size_t end, unsigned) {
    stage<Stage::Second>(stageA_.data(), state, grid, dt, context, begin, end);
  });
  parallelFor(cells_, threads, [&](size_t begin, size_t end, unsigned) {
    stage<Stage::Third>(state, state, grid, dt, context, begin, end);
  });
  parallelFor(cells_, threads, [&](size_t begin, size_t end, unsigned) {
    stage<Stage::Fourth>(stageA_.data(), state, grid, dt, context, begin, end);
  });
}

}  // namespace ontogen
