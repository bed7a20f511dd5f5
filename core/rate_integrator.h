#pragma once
// The `rate` operator (paper 002, section 2.3): `rate(x) = e` makes x a continuous
// variable. All rate variables of a pool form one ODE system, integrated with
// Boost.Odeint over each world step: classic Runge-Kutta 4 with one step per world step,
// or, with `#tolerance`, an adaptive Dormand-Prince stepper.
//
// When values are read (docs/LANGUAGE.md, "Order of events in a step"): a rule's rate
// equations are switched on for the step when its context and predicate hold in the
// state right after the step's discrete changes (at t+); while integrating, `e` reads
// the cell's and its neighbours' values at the integrator's own stage times, so
// coupled cells (diffusion) are integrated together, not one after the other.
//
// A full grid of one master with unconditional, batchable equations is integrated by
// core/rate_stencil.h instead: the same RK4, to the same bits, over the grid's arrays.

#include <memory>
#include <vector>

#include "core/development.h"
#include "core/pool_view.h"
#include "core/rate_stencil.h"
#include "core/rule_evaluator.h"
#include "model/program.h"
#include "pools/large_page_allocator.h"

namespace ontogen {

/// One per pool, owned by the pool's development, templated on its view (explicitly
/// made for the three views in rate_integrator.cpp).
template <typename View>
class RateIntegrator {
 public:
  RateIntegrator(const Program& program, uint64_t seed, unsigned threads);
  ~RateIntegrator();
  RateIntegrator(const RateIntegrator&) = delete;
  RateIntegrator& operator=(const RateIntegrator&) = delete;

  /// Integrates the pool's active rate variables from t0 to t1 in place.
  void integrate(Pool& pool, const View& view, double t0, double t1);
  /// The enclosing systems' values the equations read (World::ancestorValues).
  void setAncestors(const double* values) { ancestors_ = values; }
  /// Equations switched on in the last integration.
  size_t activeEquations() const { return active_; }
  /// Whether the last integration took the stencils of a full grid.
  bool tookStencils() const { return tookStencils_; }
  /// Whether a full grid may be integrated as stencils (core/rate_stencil.h); off, every
  /// pool takes the general path, to the same bits (WorldDef::rateStencils).
  void useStencils(bool on) { stencils_ = on; }

 private:
  struct Equation {
    uint32_t cell;
    const CompiledRule* rule;
    const StateCalculation* calculation;
    bool draws;  ///< the rule's rate expressions draw random numbers
  };
  void activate(const Pool& pool, double t0);
  void derivative(const Pool& pool, const StateArray& x, StateArray& dxdt, double t);

  const Program& program_;
  uint64_t seed_;
  const double* ancestors_ = nullptr;
  unsigned threads_;
  FunctionTable functions_;
  const View* view_ = nullptr;
  // Per cell or per equation, in buffers that the next world reuses (pools/large_block_cache.h).
  LargeVector<Equation> equations_;
  LargeVector<uint8_t> batchable_;  // per equation: evaluated with its neighbours in a batch
  LargeVector<uint32_t> stateOf_;   // per equation: where its cell's state starts
  std::vector<LargeVector<Equation>> chunkEquations_;
  std::vector<std::unique_ptr<RuleEvaluator<View>>> evaluators_;  // one per worker
  // The neighbours of every cell, and the switched-on equations when no rate rule has a
  // condition, are kept while the pool's structure does not change.
  LargeVector<uint32_t> neighbourOffsets_;
  LargeVector<uint32_t> neighbourCells_;
  LargeVector<NeighbourRef> neighbourRefs_;  // of neighbourCells_, rebuilt with it
  const Pool* tablePool_ = nullptr;
  uint64_t tableVersion_ = UINT64_MAX;
  const Pool* equationsPool_ = nullptr;
  uint64_t equationsVersion_ = UINT64_MAX;
  bool conditional_ = false;  // some rate rule has a context, predicate or probability
  // The RK4 stepper with its four stage arrays, kept from step to step: made fresh each
  // step, it took and zeroed the pool's state size four times over every step.
  struct Rk4;
  std::unique_ptr<Rk4> rk4_;
  bool stencils_ = true;
  std::unique_ptr<RateStencil> stencil_;  // grids only, made on the first step it may serve
  size_t active_ = 0;
  bool tookStencils_ = false;
};

/// One step of a pool's rates from t0 to t1: the development's integrator, made on the
/// first step that needs it, told the ancestors' values; counts the equations.
template <typename View>
void integrateRates(std::unique_ptr<RateIntegrator<View>>& rates, const Program& program, StepContext& context,
                    Pool& pool, const View& view, double t0, double t1) {
  if (!rates) rates = std::make_unique<RateIntegrator<View>>(program, context.seed, context.threads);
  rates->setAncestors(context.ancestors);
  rates->useStencils(context.rateStencils);
  rates->integrate(pool, view, t0, t1);
  context.stats.rateEquations = rates->activeEquations();
  if (rates->tookStencils()) ++context.stats.stencilSteps;
}

}  // namespace ontogen
