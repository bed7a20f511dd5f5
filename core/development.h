#pragma once
// The development of one pool over a step, behind one interface: a world owns one
// Development, made once for its system's pool kind, which owns the pool and the buffers
// it reuses from step to step. What every kind shares lives beside it, once: the frame
// loader (core/cell_frame.h), the successor writer (core/successors.h), the per-step
// rule pass (RuleEvaluator::fireStepRules), salts (core/salts.h) and limits
// (core/limits.h). Each kind adds only what is its own: where successors go, how
// neighbours are found, when rates are integrated.
//
// The world hands a step what it may read and write of itself in a StepContext, so no
// development reaches into the world.

#include <array>
#include <memory>
#include <vector>

#include "core/limits.h"
#include "core/rewrite_plan.h"
#include "core/successors.h"
#include "model/program.h"
#include "pools/pool.h"

namespace ontogen {

/// Tolerance for "at the same instant": events within it of each other or of a step's
/// end count as simultaneous. Relative, so long runs keep the same meaning.
inline double timeTolerance(double t) {
  return 1e-9 * (t < 1 ? 1 : t);
}

/// Counts a world keeps about its development.
struct WorldStats {
  uint64_t steps = 0;
  uint64_t events = 0;       ///< terminal-age events
  uint64_t ruleFirings = 0;  ///< per-step rules that fired an action or a calculation
  uint64_t cellsBorn = 0;
  uint64_t crowded = 0;        ///< grid successors that found no free site and were not born
  uint64_t rateEquations = 0;  ///< rate equations integrated in the last step
  uint64_t stencilSteps = 0;   ///< rate steps of full grids taken as stencils (core/rate_stencil.h)
  /// Linear words rewritten by each strategy, indexed by RewriteStrategy (core/rewrite_plan.h).
  RewriteCounts rewrites{};
};

/// Cells and bytes held: by a pool, by a world and its nested systems, or by everything
/// of a world but one pool.
struct WorldHeld {
  uint64_t cells = 0;
  uint64_t bytes = 0;
};

/// What a step (or the seeding of a pool) may read and write of its world.
struct StepContext {
  const Program& program;
  const SystemDefinition& system;
  uint64_t seed = 1;
  unsigned threads = 1;
  const WorldLimits& limits;
  double time = 0;                      ///< the world's time at the start (seconds)
  const double* ancestors = nullptr;    ///< Program::ancestorRefs as this pool's cells read them
  WorldStats& stats;
  std::vector<LineageRecord>* lineage = nullptr;  ///< births are logged here when not null
  uint64_t idSalt = 0;                  ///< ids of the axiom's cells derive from it
  double systemCellId = -1;             ///< idValue of this pool's system cell, -1 for the root pool
  /// What the rest of the world holds while this pool develops: the other pools of the
  /// world and its systems, and what the world's owner holds outside them (a run's
  /// frames). checkGrowth counts it with the pool's own.
  WorldHeld elsewhere{};
  bool rewriteBySlices = true;  ///< WorldDef::rewriteBySlices
  bool rateStencils = true;     ///< WorldDef::rateStencils
  bool wordsWithoutIds = true;  ///< WorldDef::wordsWithoutIds
  std::optional<RewriteStrategy> forcedRewrite = std::nullopt;  ///< WorldDef::testRewriteStrategy
};

/// Throws LimitError when a pool that holds `cells` cells and `bytes` bytes (its pool and
/// the buffers of the step in progress), with what the rest of the world holds, passes
/// the cell or memory limit, and GrowthCancelled when the growth was cancelled. Pools call
/// it as they make cells, not only between steps.
void checkGrowth(const StepContext& context, uint64_t cells, uint64_t bytes);

/// Cells made between two growth checks of a pool: often enough that a step stops near
/// the limit it passes (within an eighth of the cell limit, an eighth of the memory limit
/// in bare cells, and 64 Ki cells), rarely enough to cost nothing.
inline uint64_t growthCheckInterval(const WorldLimits& limits) {
  const uint64_t cells = limits.maxCells / 8;
  const uint64_t bytes = limits.maxMemoryBytes / 8 / sizeof(CellRecord);
  const uint64_t interval = cells < bytes ? cells : bytes;
  return interval < 1 ? 1 : interval > (1u << 16) ? (1u << 16) : interval;
}

class Development {
 public:
  virtual ~Development() = default;
  /// A deep copy: the pool and its state (a copied world develops on its own).
  virtual std::unique_ptr<Development> clone() const = 0;
  virtual const Pool& pool() const = 0;
  /// The pool, for the world to write its environment's answers into (query modules).
  virtual Pool& pool() = 0;

  /// Fills the empty pool from its system's axiom (and placements) at context.time.
  virtual void seed(StepContext& context) = 0;
  /// Develops the pool from context.time to t1; per-step rules fire at the start when
  /// `stepRules` (the world decides: only on its step grid).
  virtual void step(StepContext& context, double t1, bool stepRules) = 0;
  /// Position of the i-th cell: its index (linear), grid coordinates or spatial x, y, z.
  virtual std::array<double, 3> positionOf(size_t i) const = 0;
  /// Bytes the development holds between steps, for the memory limit: its pool's and what
  /// it keeps to reuse (a linear pool's previous word, a spatial pool's index).
  virtual uint64_t heldBytes() const { return pool().bytes(); }
};

/// The development for `system`'s pool kind, with an empty pool.
std::unique_ptr<Development> makeDevelopment(const Program& program, const SystemDefinition& system);

/// Appends the system's axiom to an empty linear or spatial pool, in text order, with ids
/// from context.idSalt.
void seedFromAxiom(Pool& pool, StepContext& context);

/// An axiom cell's values; those that read the enclosing systems are evaluated now.
std::vector<double> axiomValues(const Program& program, const AxiomCell& axiom, uint64_t seed,
                                const double* ancestors);

}  // namespace ontogen
