#pragma once
// A world grows one compiled program (paper 002: the world creates, removes and
// interprets cells). It owns the root system's pool and the global time, and nothing
// global: several worlds can run side by side, and a world is cheap to copy.
//
// One step from t to t1 (docs/LANGUAGE.md, "Order of events in a step"):
//  1. at t, every alive cell evaluates its per-step rules against the word as it was at
//     t (parallel development); state calculations and actions take effect together;
//  2. over (t, t1], cells age; a cell whose age reaches its terminal age at t_e is
//     replaced at exactly t_e by its terminal rule's successors, which are born with
//     their birth age and age on for the rest of the step. Events at the same instant
//     happen together, each cell seeing its neighbours as they were just before.
// Ages are never stored: a cell keeps its birth time, so the word at time t does not
// depend on the step size for timed L-systems.
//
// Systems nest (paper 002, section 2.2): a system cell in this world's pool owns a child
// world that grows its system's pool from its axiom. The child is made at the end of
// the step in which its cell appears and develops from the next step on; it goes with
// its cell. Children step after their parent, over the same interval, in pool order.

#include <array>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "lang/program.h"
#include "pools/grid_pool.h"
#include "pools/linear_pool.h"
#include "pools/spatial_pool.h"

namespace ontogen {

/// Growth limits: a model that passes one stops with a LimitError, not an out-of-memory kill.
struct WorldLimits {
  /// Most cells in the root pool. 100 M cells take about 5 GB with double buffering.
  uint64_t maxCells = 100'000'000;
  /// Most bytes the pools may hold. 8 GiB leaves room on a 16 GB machine.
  uint64_t maxMemoryBytes = 8ull << 30;
  /// Most terminal events in one step: a lifetime far shorter than the step would
  /// otherwise spin for ever renewing one cell.
  uint64_t maxEventsPerStep = 200'000'000;
};

struct WorldDef {
  uint64_t seed = 1;  ///< seed of every stochastic choice and function
  WorldLimits limits{};
  /// Threads for rules and rates over large pools (0: all cores). The result does not
  /// depend on it.
  unsigned threads = 1;
};

/// A limit was passed; the message names the limit and how to raise it.
struct LimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// A model failed while it ran (e.g. a birth age not below the terminal age); the
/// message names the cell, the rule and its location like a compiler diagnostic.
struct ModelError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct WorldStats {
  uint64_t steps = 0;
  uint64_t events = 0;       ///< terminal-age events
  uint64_t ruleFirings = 0;  ///< per-step rules that fired an action or a calculation
  uint64_t cellsBorn = 0;
  uint64_t crowded = 0;        ///< grid successors that found no free site and were not born
  uint64_t rateEquations = 0;  ///< rate equations integrated in the last step
};

class RateIntegrator;

class World {
 public:
  World(std::shared_ptr<const Program> program, WorldDef def = {});
  /// The world of a system cell `cell` (whose state is `cellState`) in `parent`'s pool,
  /// seeded from its system's axiom at the parent's current time.
  World(const World& parent, const CellRecord& cell, const double* cellState);
  World(const World& other);
  World& operator=(const World&) = delete;
  ~World();

  const Program& program() const { return *program_; }
  /// The system this world grows: the program's root system, or a nested one.
  const SystemDefinition& rootSystem() const { return program_->systems[system_]; }
  /// This world's pool (the root system's for the world made from a program), whatever its kind.
  const Pool& rootPool() const;
  /// The world of the system cell `cell` of this world's pool, or null (an ordinary cell).
  const World* childOf(const CellRecord& cell) const;
  /// The enclosing system's world, null for the root.
  const World* parent() const { return parent_; }
  /// Cells in this world's pool and in all nested pools.
  uint64_t totalCells() const;
  /// Values of Program::ancestorRefs as cells of this pool read them (`parent.x` is this
  /// system's own state), at the current time.
  const double* ancestorValues() const { return ancestorValues_.data(); }
  const LinearPool& linearPool() const { return pool_; }
  const GridPool& gridPool() const { return grid_; }
  const SpatialPool& spatialPool() const { return spatial_; }
  double time() const { return time_; }
  uint64_t seed() const { return def_.seed; }
  const WorldStats& stats() const { return stats_; }

  /// Develops until `target` (no-op if target ≤ time()) in steps on the grid k · dt:
  /// per-step rules fire at grid instants only, so stopping at other times (frames)
  /// does not change the development.
  void advanceTo(double target, double dt);
  /// Develops one step of length dt from the current time, per-step rules included.
  void step(double dt);

  /// Position of the i-th cell of the root pool: its index (linear) or grid coordinates.
  std::array<double, 3> positionOf(size_t i) const;
  /// Age of a cell of the root pool at the current time.
  double ageOf(const CellRecord& cell) const { return time_ - cell.birth; }
  /// The parameters of a cell after its development function: λ' = g(λ, τ, β) · λ
  /// (paper 000, eq. 3). Equal to the state when the master has no function.
  void developedValues(const CellRecord& cell, std::vector<double>& out) const;

 private:
  friend class LinearDevelopment;
  friend class GridDevelopment;
  friend class SpatialDevelopment;
  void seedPool();
  std::vector<double> axiomValues(const AxiomCell& axiom) const;
  void seedAxiom();
  void seedGrid();
  void developStep(double t1, bool stepRules);
  void developChildren(double t1, bool stepRules, bool step);
  void updateAncestorValues();
  /// Value of a system's variable (`age` or a state name) for the world `level` systems up.
  double systemValue(int level, const std::string& name) const;
  uint64_t idSalt() const;
  RateIntegrator& rates();

  std::shared_ptr<const Program> program_;
  WorldDef def_;
  int system_ = 0;                    ///< index of this world's SystemDefinition
  const World* parent_ = nullptr;     ///< the enclosing system's world
  uint64_t cellId_ = 0;               ///< id of this system's cell in the parent's pool
  double cellBirth_ = 0;              ///< birth time of that cell (the root: 0)
  std::vector<double> cellState_;     ///< its state (systems have no rules: it stays as born)
  std::vector<double> ancestorValues_;
  /// Child worlds by the id of their system cell.
  std::unordered_map<uint64_t, std::unique_ptr<World>> children_;
  LinearPool pool_;
  GridPool grid_;
  SpatialPool spatial_;
  std::unique_ptr<RateIntegrator> rates_;  // made on first use; not copied
  double time_ = 0;
  WorldStats stats_;
  // The next word is built here and swapped with the pool's (kept to reuse the memory).
  CellArray scratchCells_;
  StateArray scratchState_;
  double lastGrowth_ = 1;  ///< size ratio of the last rebuilt word, to reserve the next
};

/// Tolerance for "at the same instant": events within it of each other or of a step's
/// end count as simultaneous. Relative, so long runs keep the same meaning.
inline double timeTolerance(double t) {
  return 1e-9 * (t < 1 ? 1 : t);
}

}  // namespace ontogen
