#include "core/rate_stencil.h"

#include <algorithm>

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
  equationOf_.assign(stride_, -1);
  for (size_t e = 0; e < equations_.size(); ++e) {
    const StateCalculation& calculation = *equations_[e].calculation;
    if (calculation.slot < 0 || calculation.slot >= static_cast<int>(stride_)) return false;
    equationOf_[static_cast<size_t>(calculation.slot)] = static_cast<int>(e);
    if (equations_[e].rule->aggregates.size() > kMaxQueries) return false;
    std::vector<Query>& queries = queries_.emplace_back();
    for (const AggregateQuery& query : equations_[e].rule->aggregates) {
      const bool matches = query.label < 0 || query.label == static_cast<int>(master_);
      const int slot = master_ < query.slotOf.size() ? query.slotOf[master_] : -1;
      queries.push_back({&query, matches, slot});
    }
  }
  const GridShape& shape = grid.shape();
  dimensions_ = shape.dimensions;
  size_ = shape.size;
  deltas_.clear();
  for (const GridCoordinates& offset : grid.offsets())
    deltas_.push_back(offset[0] + offset[1] * int64_t{size_[0]} + offset[2] * int64_t{size_[0]} * size_[1]);
  cells_ = cells.size();
  applies_ = true;
  return true;
}

// A cell whose neighbours are all inside the grid: each at its fixed distance.
double RateStencil::inside(const Query& q, size_t cell, const double* in) const {
  const AggregateQuery& query = *q.query;
  const int64_t here = static_cast<int64_t>(cell);
  if (query.kind == AggregateKind::Count) return q.matches ? static_cast<double>(deltas_.size()) : 0.0;
  if (query.kind == AggregateKind::Sum) {
    if (!q.matches || q.slot < 0) return 0.0;
    double sum = 0;  // in the neighbourhood's order, from 0, as aggregateOver sums
    for (int64_t delta : deltas_) sum += in[static_cast<size_t>(here + delta) * stride_ + static_cast<size_t>(q.slot)];
    return sum;
  }
  return aggregateOver(
      query, static_cast<int>(deltas_.size()),
      [&](int k) {
        return NeighbourRef{master_, static_cast<uint32_t>(static_cast<size_t>(here + deltas_[k]) * stride_)};
      },
      in);
}

// A cell at an edge: the grid's boundary says which sites are its neighbours.
double RateStencil::atEdge(const Query& q, size_t cell, const double* in) const {
  uint32_t sites[GridPool::kMaxNeighbours];
  NeighbourRef around[GridPool::kMaxNeighbours];
  const int offsets = grid_->neighbourSites(static_cast<uint32_t>(cell), sites);  // full: site i holds cell i
  int count = 0;
  for (int k = 0; k < offsets; ++k)
    if (sites[k] != GridPool::kEmpty) around[count++] = NeighbourRef{master_, grid_->cellAt(sites[k]) * stride_};
  return aggregateOver(*q.query, count, [&](int k) -> const NeighbourRef& { return around[k]; }, in);
}

void RateStencil::gather(const Query& q, size_t first, int lanes, bool allInside, bool rowInside,
                         const double* in, double* out) const {
  const AggregateQuery& query = *q.query;
  if (allInside && query.kind == AggregateKind::Count) {
    const double count = q.matches ? static_cast<double>(deltas_.size()) : 0.0;
    for (int lane = 0; lane < lanes; ++lane) out[lane] = count;
    return;
  }
  if (allInside && query.kind == AggregateKind::Sum && q.matches && q.slot >= 0) {
    // Lane by lane, each lane's neighbours added in the neighbourhood's order from 0, as
    // aggregateOver sums: the loop over lanes is the one that vectorises.
    for (int lane = 0; lane < lanes; ++lane) out[lane] = 0;
    for (int64_t delta : deltas_) {
      const double* from = in + static_cast<size_t>(static_cast<int64_t>(first) + delta) * stride_ +
                           static_cast<size_t>(q.slot);
      if (stride_ == 1)
        for (int lane = 0; lane < lanes; ++lane) out[lane] += from[lane];
      else
        for (int lane = 0; lane < lanes; ++lane) out[lane] += from[static_cast<size_t>(lane) * stride_];
    }
    return;
  }
  const size_t width = size_[0], x0 = first % width;
  for (int lane = 0; lane < lanes; ++lane) {
    const size_t at = x0 + static_cast<size_t>(lane), cell = first + static_cast<size_t>(lane);
    out[lane] = allInside || (rowInside && at >= 1 && at + 1 < width) ? inside(q, cell, in) : atEdge(q, cell, in);
  }
}

void RateStencil::rates(size_t first, int lanes, const double* in, const EvalContext& context,
                        double (*values)[CompiledExpression::kBatchLanes]) const {
  const size_t width = size_[0], height = size_[1], depth = size_[2];
  const size_t x0 = first % width, row = first / width, y = row % height, z = row / height;
  const bool rowInside =
      (dimensions_ < 2 || (y >= 1 && y + 1 < height)) && (dimensions_ < 3 || (z >= 1 && z + 1 < depth));
  const bool allInside = rowInside && x0 >= 1 && x0 + static_cast<size_t>(lanes) < width;
  double aggregates[kMaxQueries][CompiledExpression::kBatchLanes];
  auto load = [&](int lane, int slot) {
    return in[(first + static_cast<size_t>(lane)) * stride_ + static_cast<size_t>(slot)];
  };
  for (size_t e = 0; e < equations_.size(); ++e) {
    const std::vector<Query>& queries = queries_[e];
    for (size_t q = 0; q < queries.size(); ++q) gather(queries[q], first, lanes, allInside, rowInside, in, aggregates[q]);
    equations_[e].calculation->value.evaluateBatch(
        lanes, load, [&](int lane, int q) { return aggregates[q][lane]; }, context, values[e]);
  }
}

template <RateStencil::Stage which>
void RateStencil::stage(const double* in, double* x, double dt, const EvalContext& context, size_t begin,
                        size_t end) {
  // odeint's runge_kutta4 coefficients (a, b) times dt, as its generic_rk_scale_sum makes them.
  const double half = 0.5 * dt, zero = 0.0 * dt, whole = 1.0 * dt, sixth = (1.0 / 6.0) * dt, third = (1.0 / 3.0) * dt;
  double* a = stageA_.data();
  double* zeros = zeroSum_.data();
  double* result = result_.data();
  const size_t width = size_[0];
  double values[kMaxEquations][CompiledExpression::kBatchLanes];
  for (size_t first = begin; first < end;) {
    // A batch stays within a row, so that the cells inside are known at once, and the
    // first and last cell of a row go alone, so that the others are all inside.
    const size_t rowEnd = (first / width + 1) * width;
    size_t count = std::min({size_t{CompiledExpression::kBatchLanes}, end - first, rowEnd - first});
    if (first % width == 0)
      count = 1;
    else if (first + count == rowEnd && count > 1)
      --count;
    const int lanes = static_cast<int>(count);
    rates(first, lanes, in, context, values);
    for (size_t slot = 0; slot < stride_; ++slot) {
      const int e = equationOf_[slot];
      for (int lane = 0; lane < lanes; ++lane) {
        const double k = e >= 0 ? values[e][lane] : 0.0;  // a constant's derivative, as the general path's fill
        const size_t i = (first + static_cast<size_t>(lane)) * stride_ + slot;
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
        } else {  // x + dt (k1 / 6 + k2 / 3 + k3 / 3 + k4 / 6), summed left to right
          x[i] = result[i] + sixth * k;
        }
      }
    }
    first += static_cast<size_t>(lanes);
  }
}

void RateStencil::step(StateArray& x, double dt, const EvalContext& context, unsigned threads) {
  // Every element is written by the first pass before any is read.
  resizeForOverwrite(stageA_, x.size());
  resizeForOverwrite(zeroSum_, x.size());
  resizeForOverwrite(result_, x.size());
  double* state = x.data();
  parallelFor(cells_, threads, [&](size_t begin, size_t end, unsigned) {
    stage<Stage::First>(state, state, dt, context, begin, end);
  });
  parallelFor(cells_, threads, [&](size_t begin, size_t end, unsigned) {
    stage<Stage::Second>(stageA_.data(), state, dt, context, begin, end);
  });
  parallelFor(cells_, threads, [&](size_t begin, size_t end, unsigned) {
    stage<Stage::Third>(state, state, dt, context, begin, end);
  });
  parallelFor(cells_, threads, [&](size_t begin, size_t end, unsigned) {
    stage<Stage::Fourth>(stageA_.data(), state, dt, context, begin, end);
  });
}

}  // namespace ontogen
