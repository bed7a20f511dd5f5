#pragma once
// A world grows one compiled program (paper 002: the world creates, removes and
// interprets cells). It owns one Development (core/development.h), made once for its
// system's pool kind, which owns the pool; and the global time. Nothing is global:
// many worlds share one compiled program side by side, and a world is cheap to make,
// copy and move.
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
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/development.h"
#include "core/environment_process.h"
#include "core/limits.h"
#include "core/successors.h"
#include "model/program.h"
#include "pools/grid_pool.h"
#include "pools/linear_pool.h"
#include "pools/spatial_pool.h"

namespace ontogen {

struct WorldDef {
  uint64_t seed = 1;  ///< seed of every stochastic choice and function
  WorldLimits limits{};
  /// Threads for rules and rates over large pools (0: all cores). The result does not
  /// depend on it.
  unsigned threads = 1;
  /// Keep a log of every birth (child, parent, time) for lineage(); off, it costs nothing.
  bool recordLineage = false;
  /// Rewrite large linear words by slices (core/parallel_rewrite.h) where it applies. Off,
  /// every word takes the one-pass serial rewriting; the result is the same bits, which is
  /// what tests compare.
  bool rewriteBySlices = true;
  /// Integrate the rates of a full grid of one master as stencils over its arrays
  /// (core/rate_stencil.h) where it applies. Off, every pool takes the general path; the
  /// result is the same bits, which is what tests compare.
  bool rateStencils = true;
  /// Grow words rewritten by a table (Koch, Thue-Morse: core/parallel_rewrite.h) without
  /// their ids, which are made again the first time a reader asks for the cells
  /// (docs/COMPACT_WORDS.md, "Words without ids"). Off, every word holds its ids as it
  /// grows; readers see the same cells either way, which is what tests compare.
  bool wordsWithoutIds = true;
  /// For tests only: rewrite linear words by this strategy wherever it applies
  /// (core/rewrite_plan.h), so that a test runs each against the serial pass; where it does
  /// not apply the usual plan is taken. WorldStats::rewrites says which ran.
  std::optional<RewriteStrategy> testRewriteStrategy = std::nullopt;
  /// Answers the query modules (`?P(x, y, z)` ...) after seeding and after every step
  /// (core/environment_process.h); null: they keep their values. Shared by copies.
  std::shared_ptr<const EnvironmentProcess> environment = nullptr;
};

class World {
 public:
  /// Bytes a world takes besides its pool's cells, counted with them against the memory
  /// limit and in held(): its development's rule evaluator, rewriter, frames and empty
  /// buffers, and its place among its parent's children. 65,535 nested worlds of a cell
  /// each took 11 KB a world at their peak resident size (docs/LANGUAGE.md 6), while
  /// their cells took 24 bytes.
  static constexpr uint64_t kWorldBytes = uint64_t{12} << 10;

  World(std::shared_ptr<const Program> program, WorldDef def = {});
  /// The world of a system cell `cell` (state included) in `parent`'s pool, seeded from
  /// its system's axiom at the parent's current time. `tree`, when given, is what the
  /// whole world holds so far; the new world's pools are checked with it and added to it.
  World(const World& parent, const CellView& cell, WorldHeld* tree = nullptr);
  /// A deep copy that develops on its own.
  World(const World& other);
  World& operator=(const World&) = delete;
  /// Moves are cheap (no cell is copied); a moved-from world may only be destroyed or
  /// assigned to.
  World(World&& other) noexcept;
  World& operator=(World&& other) noexcept;
  ~World();

  const Program& program() const { return *program_; }
  /// The system this world grows: the program's root system, or a nested one.
  const SystemDefinition& rootSystem() const { return program_->systems[system_]; }
  /// This world's pool (the root system's for the world made from a program), whatever its kind.
  const Pool& rootPool() const { return *pool_; }
  /// The world of the system cell `cell` of this world's pool, or null (an ordinary cell).
  const World* childOf(const CellRecord& cell) const { return childOf(cell.id); }
  /// The same, by the cell's id.
  const World* childOf(uint64_t id) const;
  /// The enclosing system's world, null for the root.
  const World* parent() const { return parent_; }
  /// Cells in this world's pool and in all nested pools.
  uint64_t totalCells() const;
  /// Cells and bytes of this world's pool and of all nested pools, and the bytes of the
  /// copy of the world kept at the last grid instant while a stop lies between two.
  WorldHeld held() const;
  /// Bytes the world's owner holds for it outside the pools (a run's frames, a picture),
  /// counted against the memory limit as the pools grow.
  void holdOutside(uint64_t bytes) { heldOutside_ = bytes; }
  uint64_t heldOutside() const { return heldOutside_; }
  /// Values of Program::ancestorRefs as cells of this pool read them (`parent.x` is this
  /// system's own state), at the current time.
  const double* ancestorValues() const { return ancestorValues_.data(); }
  /// The pool as its kind; a std::logic_error when the pool is of another kind.
  const LinearPool& linearPool() const;
  const GridPool& gridPool() const;
  const SpatialPool& spatialPool() const;
  /// The id of this world's system cell in its parent's pool (0 for the root world).
  uint64_t systemCellId() const { return cellId_; }
  /// Every birth in this world's pool since it was made, in the order of the
  /// development, when WorldDef::recordLineage is on (the cells of a nested pool's axiom
  /// have its system cell as parent); empty otherwise.
  const std::vector<LineageRecord>& lineage() const { return lineage_; }
  double time() const { return time_; }
  uint64_t seed() const { return def_.seed; }
  const WorldStats& stats() const { return stats_; }

  /// Develops until `target` (no-op if target ≤ time()) in steps on the grid k · dt:
  /// per-step rules fire at grid instants only, so stopping at other times (frames)
  /// does not change the development. A world that integrates `rate` variables shows a
  /// stop between grid instants by a step of its own from the last grid instant, which
  /// the development does not keep: the next advance starts again from that instant, so
  /// integration steps are never split by where a run stops.
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
  /// The same for a cell whose state is not in the pool (a homomorphism's image).
  void developedValues(const CellRecord& cell, const double* state, std::vector<double>& out) const;
  /// The same for a cell as a cursor gives it (its state wherever it is).
  void developedValues(const CellView& cell, std::vector<double>& out) const;

 private:
  void seedPool(WorldHeld& tree);
  /// `tree`: what the whole world holds, this world's pools as they are now; updated.
  void developStep(double t1, bool stepRules, WorldHeld& tree);
  void developChildren(double t1, bool stepRules, bool step, WorldHeld& tree);
  /// A step of the root world: what the world holds is counted once, then kept up to date.
  void developRootStep(double t1, bool stepRules);
  /// What this world holds besides its nested systems: its pool, what its development
  /// keeps between steps (the previous word) and its own kWorldBytes.
  WorldHeld heldHere() const { return {pool_->size(), development_->heldBytes() + kWorldBytes}; }
  /// A world with nested systems stops as soon as what it holds, `tree`, passes the cell
  /// or memory limit, while its systems' pools are made (each makes its own).
  void checkTree(const WorldHeld& tree) const;
  void updateAncestorValues();
  /// Writes the environment's answers into the query modules of this world's pool.
  void answerQueries();
  StepContext stepContext(const WorldHeld& elsewhere);
  /// Value of a system's variable (`age` or a state name) for the world `level` systems up.
  double systemValue(int level, const std::string& name) const;
  uint64_t idSalt() const;
  /// Whether a stop between grid instants would split an integration step here or in a
  /// nested system (some system of the program integrates rates).
  bool integratesRates() const;
  /// Back to the state kept at the last grid instant, when a stop between grid
  /// instants left the world off the grid.
  void returnToGrid();

  std::shared_ptr<const Program> program_;
  WorldDef def_;
  int system_ = 0;                    ///< index of this world's SystemDefinition
  const World* parent_ = nullptr;     ///< the enclosing system's world
  uint64_t cellId_ = 0;               ///< id of this system's cell in the parent's pool
  double cellBirth_ = 0;              ///< birth time of that cell (the root: 0)
  std::vector<double> cellState_;     ///< its state (systems have no rules: it stays as born)
  std::vector<double> ancestorValues_;
  bool checksFinite_ = false;  ///< checksFiniteState(program): state is checked after each step
  /// Child worlds by the id of their system cell.
  std::unordered_map<uint64_t, std::unique_ptr<World>> children_;
  std::unique_ptr<Development> development_;  ///< made once; owns the pool
  const Pool* pool_ = nullptr;                ///< development_->pool(), asked once (read per cell)
  double time_ = 0;
  uint64_t heldOutside_ = 0;  ///< holdOutside(), root only
  WorldStats stats_;
  std::vector<LineageRecord> lineage_;
  /// The world as it was at the last grid instant, while a stop between grid instants
  /// shows a step that the development does not keep (rate-integrating worlds only).
  std::unique_ptr<World> onGrid_;
};

}  // namespace ontogen
