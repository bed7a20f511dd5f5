#include "core/rate_integrator.h"

#include <algorithm>
#include <type_traits>
#include <boost/numeric/odeint.hpp>

#include "core/parallel_for.h"
#include "core/salts.h"
#include "model/expression_batch.h"

namespace ontogen {

namespace {

bool draws(const CompiledRule& rule) {
  for (const StateCalculation& calculation : rule.calculations)
    if (calculation.isRate && calculation.value.isStochastic()) return true;
  return false;
}
}  // namespace

namespace {
// odeint's algebra with its loops split over the threads: each RK4 stage's sums are
// element by element, so slices give the same bits as one loop.
struct SlicedAlgebra {
  unsigned threads = 1;

  template <class Op, class First, class... Rest>
  void apply(Op op, First& first, Rest&... rest) const {
    parallelFor(
        first.size(), threads,
        [&](size_t begin, size_t end, unsigned) {
          for (size_t i = begin; i < end; ++i) op(first[i], rest[i]...);
        },
        size_t{1} << 15);
  }
  template <class S1, class Op>
  void for_each1(S1& s1, Op op) const { apply(op, s1); }
  template <class S1, class S2, class Op>
  void for_each2(S1& s1, S2& s2, Op op) const { apply(op, s1, s2); }
  template <class S1, class S2, class S3, class Op>
  void for_each3(S1& s1, S2& s2, S3& s3, Op op) const { apply(op, s1, s2, s3); }
  template <class S1, class S2, class S3, class S4, class Op>
  void for_each4(S1& s1, S2& s2, S3& s3, S4& s4, Op op) const { apply(op, s1, s2, s3, s4); }
  template <class S1, class S2, class S3, class S4, class S5, class Op>
  void for_each5(S1& s1, S2& s2, S3& s3, S4& s4, S5& s5, Op op) const { apply(op, s1, s2, s3, s4, s5); }
  template <class S1, class S2, class S3, class S4, class S5, class S6, class Op>
  void for_each6(S1& s1, S2& s2, S3& s3, S4& s4, S5& s5, S6& s6, Op op) const { apply(op, s1, s2, s3, s4, s5, s6); }
  template <class S1, class S2, class S3, class S4, class S5, class S6, class S7, class Op>
  void for_each7(S1& s1, S2& s2, S3& s3, S4& s4, S5& s5, S6& s6, S7& s7, Op op) const {
    apply(op, s1, s2, s3, s4, s5, s6, s7);
  }
};
}  // namespace

template <typename View>
struct RateIntegrator<View>::Rk4 {
  explicit Rk4(unsigned threads) : stepper(SlicedAlgebra{threads}) {}
  // always_resizer: the stages follow the state's size when the pool has grown.
  boost::numeric::odeint::runge_kutta4<StateArray, double, StateArray, double, SlicedAlgebra,
                                       boost::numeric::odeint::default_operations,
                                       boost::numeric::odeint::always_resizer>
      stepper;
};

template <typename View>
RateIntegrator<View>::RateIntegrator(const Program& program, uint64_t seed, unsigned threads)
    : program_(program), seed_(seed), threads_(std::max(1u, threads)), functions_(program.functionTable()) {
  for (const MasterCell& master : program.masters)
    for (const CompiledRule& rule : master.rules)
      if (rule.hasRate && (rule.hasContext() || !rule.predicate.empty() || !rule.probability.empty()))
        conditional_ = true;
}

template <typename View>
RateIntegrator<View>::~RateIntegrator() = default;

template <typename View>
void RateIntegrator<View>::activate(const Pool& pool, double t0) {
  const double* arena = pool.stateArena().data();
  chunkEquations_.resize(threads_);
  for (auto& chunk : chunkEquations_) chunk.clear();
  parallelFor(pool.size(), threads_, [&](size_t begin, size_t end, unsigned worker) {
    RuleEvaluator<View>& evaluator = *evaluators_[worker];
    LargeVector<Equation>& out = chunkEquations_[worker];
    for (CellCursor cell = pool.cursor(begin); cell.index() < end; cell.next()) {
      const size_t i = cell.index();
      const MasterCell& master = program_.masters[cell.master()];
      const size_t first = out.size();
      for (const CompiledRule& rule : master.rules) {
        if (!rule.hasRate) continue;
        double* frame = evaluator.load(i, arena, t0);
        if (!evaluator.bind(rule)) continue;
        RandomStream random(mixKey(mixKey(seed_ ^ kRateSalt, cell.id()), keyOf(t0)));
        EvalContext context{frame, EvalEnvironment{&random, seed_}, &functions_, &evaluator};
        context.ancestors = ancestors_;
        if (!rule.predicate.empty() && rule.predicate.evaluate(context) == 0.0) continue;
        for (const StateCalculation& calculation : rule.calculations) {
          if (!calculation.isRate) continue;
          // A later rule's rate for the same variable replaces an earlier one.
          auto same = std::find_if(out.begin() + first, out.end(),
                                   [&](const Equation& e) { return e.calculation->slot == calculation.slot; });
          if (same != out.end()) out.erase(same);
          out.push_back({static_cast<uint32_t>(i), &rule, &calculation, draws(rule)});
        }
      }
      // Group a cell's equations by rule, so one frame load serves each rule.
      std::stable_sort(out.begin() + first, out.end(),
                       [](const Equation& a, const Equation& b) { return a.rule < b.rule; });
    }
  });
  equations_.clear();
  for (const auto& chunk : chunkEquations_) equations_.insert(equations_.end(), chunk.begin(), chunk.end());
  // Which equations can be evaluated a batch of cells at a time: their expression reads
  // the cell's own state and its neighbours' aggregates only, and draws nothing.
  batchable_.resize(equations_.size());
  stateOf_.resize(equations_.size());
  // Equations come in cell order: one cursor finds where their cells' values start.
  CellCursor at = pool.cursor();
  for (size_t e = 0; e < equations_.size(); ++e) {
    const Equation& equation = equations_[e];
    if (at.index() > equation.cell) at = pool.cursor(equation.cell);
    while (at.index() < equation.cell) at.next();
    const MasterCell& master = program_.masters[at.master()];
    stateOf_[e] = static_cast<uint32_t>(at.stateOffset());
    batchable_[e] = !equation.draws &&
                    equation.calculation->value.batchable(static_cast<int>(master.stateCount()));
  }
}

template <typename View>
void RateIntegrator<View>::derivative(const Pool& pool, const StateArray& x, StateArray& dxdt, double t) {
  std::fill(dxdt.begin(), dxdt.end(), 0.0);
  parallelFor(equations_.size(), threads_, [&](size_t begin, size_t end, unsigned worker) {
    RuleEvaluator<View>& evaluator = *evaluators_[worker];
    RandomStream random;
    EvalContext context{nullptr, EvalEnvironment{&random, seed_}, &functions_, &evaluator};
    context.ancestors = ancestors_;
    uint32_t loadedCell = UINT32_MAX;
    const CompiledRule* loadedRule = nullptr;
    for (size_t e = begin; e < end; ++e) {
      const Equation& equation = equations_[e];
      if (batchable_[e]) {
        // A run of the same equation over consecutive cells, evaluated together (a
        // stencil such as diffusion's sum(x) - count() * x, once per instruction).
        size_t lanes = 1;
        while (lanes < CompiledExpression::kBatchLanes && e + lanes < end && batchable_[e + lanes] &&
               equations_[e + lanes].calculation == equation.calculation)
          ++lanes;
        const Equation* run = &equations_[e];
        const uint32_t* states = &stateOf_[e];
        auto load = [&](int lane, int slot) { return x[states[lane] + static_cast<uint32_t>(slot)]; };
        auto aggregate = [&](int lane, int query) {
          const uint32_t cell = run[lane].cell;
          const NeighbourRef* around = neighbourRefs_.data() + neighbourOffsets_[cell];
          return aggregateOver(
              equation.rule->aggregates[static_cast<size_t>(query)],
              static_cast<int>(neighbourOffsets_[cell + 1] - neighbourOffsets_[cell]),
              [&](int k) -> const NeighbourRef& { return around[k]; }, x.data());
        };
        double values[CompiledExpression::kBatchLanes];
        equation.calculation->value.evaluateBatch(static_cast<int>(lanes), load, aggregate, context, values);
        for (size_t l = 0; l < lanes; ++l) dxdt[states[l] + run[l].calculation->slot] = values[l];
        e += lanes - 1;
        loadedCell = UINT32_MAX;  // the evaluator's frame is not the last equation's
        continue;
      }
      if (equation.cell != loadedCell || equation.rule != loadedRule) {
        context.frame = evaluator.load(equation.cell, x.data(), t);
        evaluator.bind(*equation.rule);  // the structure does not change while integrating
        if (equation.draws)
          random = RandomStream(mixKey(mixKey(seed_ ^ kRateSalt, pool.cells()[equation.cell].id), keyOf(t)));
        loadedCell = equation.cell;
        loadedRule = equation.rule;
      }
      dxdt[stateOf_[e] + equation.calculation->slot] = equation.calculation->value.evaluate(context);
    }
  });
}

template <typename View>
void RateIntegrator<View>::integrate(Pool& pool, const View& view, double t0, double t1) {
  tookStencils_ = false;
  if (!(t1 > t0)) return;
  if constexpr (std::is_same_v<View, GridPoolView>) {
    if (stencils_ && !conditional_ && program_.rateTolerance <= 0) {
      if (!stencil_) stencil_ = std::make_unique<RateStencil>();
      if (stencil_->prepare(program_, static_cast<const GridPool&>(pool))) {
        RandomStream random;  // never drawn from: the stencil's equations draw nothing
        EvalContext context{nullptr, EvalEnvironment{&random, seed_}, &functions_, nullptr};
        context.ancestors = ancestors_;
        stencil_->step(pool.stateValues(), t1 - t0, context, threads_);
        active_ = stencil_->equations();
        tookStencils_ = true;
        return;
      }
    }
  }
  while (evaluators_.size() < threads_) evaluators_.push_back(std::make_unique<RuleEvaluator<View>>(program_, view));
  if (view_ != &view) {
    // Evaluators hold the view they were made with.
    for (auto& evaluator : evaluators_) evaluator = std::make_unique<RuleEvaluator<View>>(program_, view);
    view_ = &view;
  }
  for (auto& evaluator : evaluators_) evaluator->useNeighbourTable(nullptr, nullptr);  // may be stale
  if (conditional_ || equationsPool_ != &pool || equationsVersion_ != pool.structureVersion()) {
    activate(pool, t0);
    equationsPool_ = &pool;
    equationsVersion_ = pool.structureVersion();
  }
  active_ = equations_.size();
  if (equations_.empty()) return;
  // The structure is fixed while integrating: find every cell's neighbours once, not
  // once per stage and equation, and keep them until it changes.
  bool aggregates = false;
  for (const Equation& equation : equations_)
    if (!equation.rule->aggregates.empty()) {
      aggregates = true;
      break;
    }
  if (aggregates && (tablePool_ != &pool || tableVersion_ != pool.structureVersion())) {
    tablePool_ = &pool;
    tableVersion_ = pool.structureVersion();
    if constexpr (requires { view.neighbourTable(neighbourOffsets_, neighbourCells_); }) {
      view.neighbourTable(neighbourOffsets_, neighbourCells_);  // a view that finds them faster at once
    } else {
      const size_t cells = pool.size();
      neighbourOffsets_.assign(cells + 1, 0);
      neighbourCells_.clear();
      neighbourCells_.reserve(cells * 4);
      std::vector<uint32_t> around;
      for (size_t i = 0; i < cells; ++i) {
        view.neighbours(i, around);
        neighbourCells_.insert(neighbourCells_.end(), around.begin(), around.end());
        neighbourOffsets_[i + 1] = static_cast<uint32_t>(neighbourCells_.size());
      }
    }
    // What the batches read of each neighbour, side by side rather than through its record.
    std::vector<NeighbourRef> refs(pool.size());
    for (CellCursor cell = pool.cursor(); !cell.done(); cell.next())
      refs[cell.index()] = NeighbourRef{cell.master(), static_cast<uint32_t>(cell.stateOffset())};
    neighbourRefs_.resize(neighbourCells_.size());
    for (size_t k = 0; k < neighbourCells_.size(); ++k) neighbourRefs_[k] = refs[neighbourCells_[k]];
  }
  for (auto& evaluator : evaluators_)
    evaluator->useNeighbourTable(aggregates ? neighbourOffsets_.data() : nullptr,
                                 aggregates ? neighbourCells_.data() : nullptr);
  namespace odeint = boost::numeric::odeint;
  auto system = [&](const StateArray& x, StateArray& dxdt, double t) { derivative(pool, x, dxdt, t); };
  StateArray& x = pool.stateValues();
  if (program_.rateTolerance > 0) {
    const double tolerance = program_.rateTolerance;
    odeint::integrate_adaptive(odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_dopri5<StateArray>()),
                               system, x, t0, t1, t1 - t0);
  } else {
    if (!rk4_) rk4_ = std::make_unique<Rk4>(threads_);
    rk4_->stepper.do_step(system, x, t0, t1 - t0);  // resizes its stages when the pool grew
  }
}

template class RateIntegrator<LinearPoolView>;
template class RateIntegrator<GridPoolView>;
template class RateIntegrator<SpatialPoolView>;

}  // namespace ontogen
