#pragma once
// The compiled program: the one cell model every source form lowers to (paper 002).
// Cells, L-system modules and turtle symbols are all master cells; a system holds an
// axiom and a pool kind. Expressions are compiled against fixed frame layouts:
//
//   rule frame:        [state 0..n-1] [internal state] [context values...]
//   instruction frame: [state 0..n-1] [internal state]
//
// where the internal state is the slots of FrameSlot: age, terminal age, time, id and
// the cell's position in its pool.
//
// so evaluation is a walk over bytecode reading doubles from one small array.

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "model/expression.h"
#include "model/source.h"
#include "pools/cell_record.h"
#include "pools/grid_pool.h"
#include "pools/linear_pool.h"

namespace ontogen {

using MasterId = uint32_t;
/// Most modules one context pattern may have (`A B C < me > D E`): patterns are short,
/// and the engine matches them into fixed arrays of this size.
inline constexpr size_t kMaxContextItems = 64;
inline constexpr double kForever = std::numeric_limits<double>::infinity();
/// Largest `maximum depth` of a decomposition or homomorphism: the engine rewrites a
/// module recursively on its stack, one small frame per level.
inline constexpr int kMaxRewriteDepth = 256;

/// Read-only internal state, in the slots after a cell's state values.
struct FrameSlot {
  static constexpr int kAge = 0;          ///< `age`, `tau`, `me.age`
  static constexpr int kTerminalAge = 1;  ///< `beta`, `lifetime`
  static constexpr int kTime = 2;         ///< `time`: the global time
  static constexpr int kId = 3;           ///< `id`, `me.id`: the low 53 bits of the stable id
  static constexpr int kX = 4;            ///< `me.x`: index in a linear pool, first grid coordinate
  static constexpr int kY = 5;            ///< `me.y`: second grid coordinate (0 elsewhere)
  static constexpr int kZ = 6;            ///< `me.z`: third grid coordinate (0 elsewhere)
  static constexpr int kParent = 7;       ///< `me.parent`: the low 53 bits of the parent's id, -1 for none
  static constexpr int kCount = 8;
};

/// A reduction over the neighbours of a cell: `count()`, `count(A)`, `sum(x)`,
/// `mean(A.x)`, `min(x)`, `max(x)`.
enum class AggregateKind : uint8_t { Count, Sum, Mean, Min, Max };

struct AggregateQuery {
  AggregateKind kind = AggregateKind::Count;
  int label = -1;  ///< the master neighbours must have, -1: any
  /// Per master: index of the variable in its state, -1 where it has none (neighbours
  /// without the variable are left out). Empty for count.
  std::vector<int> slotOf;
  std::string text;  ///< as written, to share one query between uses
};

/// A module of a context pattern and where its state goes in the rule frame.
struct ContextBinding {
  ContextItem item;
  int firstSlot = -1;  ///< frame slot of its first state value, -1 when nothing is bound
  int count = 0;       ///< number of state values bound
  std::array<int, 3> offset{0, 0, 0};  ///< a 2-D or 3-D context: the site relative to `me`
  /// A wildcard with parameters, `*(x, y)`: the number of parameters the module must
  /// have; -1: any (`*`, or not a wildcard).
  int arity = -1;
};

/// A cell to create: `B(x / 2)`, `(C(j + 1), 0.5)` or `me`.
struct SuccessorTemplate {
  bool isMe = false;
  MasterId master = 0;
  std::vector<CompiledExpression> args;  ///< one per state value of the master (defaults filled in)
  CompiledExpression birthAge;           ///< empty: 0
  SourceSpan span;
  /// `=X`: the successor keeps its predecessor's identity (its id), so a joint or a rod
  /// stays the same one across rewrites. At most one successor of a rule, and not with `me`.
  bool keepsIdentity = false;
  /// Not `me`, no state and born at age 0: the engine copies it without evaluating.
  bool stateless = false;
};

struct StateCalculation {
  int slot = 0;  ///< state index of the cell (also its frame slot)
  bool isRate = false;
  CompiledExpression value;  ///< already combined for `+=` and friends
  SourceSpan span;
};

/// The scale of a module without one (L-Py's default): finer than every declared scale,
/// so that a multiscale context passes over it.
inline constexpr int32_t kUnscaled = INT32_MAX;

/// An L-system's module scales (`scale N:` lines) or levels (`level N:` lines).
struct ScaleTable {
  std::vector<int32_t> of;  ///< per master: its scale or level, kUnscaled where none is declared (brackets too)
  bool levels = false;      ///< levels: L-Py's multi-level matching, whose levels are not ordered
};

struct CompiledRule {
  std::string name;  ///< `p1`, or empty
  SourceSpan span;
  std::vector<ContextBinding> left;   ///< nearest first
  std::vector<ContextBinding> right;  ///< text order
  /// L-systems: L-Py's new left context `<<`, nearest first, matched against the word the
  /// step has produced so far (left of the module); and its items.
  std::vector<ContextBinding> newLeft;
  std::vector<ContextItem> newLeftItems;
  /// L-Py's new right context `>>`, text order, matched against the word the step has
  /// produced so far right of the module (the block derives right to left); its items.
  std::vector<ContextBinding> newRight;
  std::vector<ContextItem> newRightItems;
  std::vector<ContextItem> leftItems;   ///< the items of `left`, contiguous for the pool
  std::vector<ContextItem> rightItems;  ///< the items of `right`
  /// L-systems: the alternatives of a context, `(B(x) | C(y))`, make one rule per
  /// combination, tried in turn; `variant` > 0 continues the rule before it (a stochastic
  /// choice counts the rule once). `unboundSlots` are the slots of names only other
  /// variants bind: they read 0 when this one matches.
  int variant = 0;
  std::vector<int> unboundSlots;
  CompiledExpression predicate;       ///< empty: always true
  std::vector<StateCalculation> calculations;
  bool hasAction = false;
  int group = 0;  ///< L-systems: its rule group (0: applies whatever group is active)
  /// L-systems: which of SystemDefinition::ruleClasses its context matching sees (the
  /// `ignore:` / `consider:` line above it); -1: the system's symbolClass.
  int symbolClasses = -1;
  /// L-systems with `scale N:` or `level N:` lines: the scale of every master, shared by
  /// the block's rules with a context, which then match as a multiscale or multi-level
  /// tree (core/multiscale_context.h); null: the ordinary matching.
  std::shared_ptr<const ScaleTable> scales;
  std::vector<SuccessorTemplate> successors;
  CompiledExpression probability;  ///< empty: not stochastic
  std::vector<AggregateQuery> aggregates;  ///< read by OpCode::Aggregate in this rule's expressions
  int frameSize = 0;
  bool hasRate = false;      ///< some calculation is `rate(x) = e`
  bool hasDiscrete = false;  ///< some calculation is not a rate, or the rule has an action

  /// 1: `A me B` (left and right); 2 or 3: `(A) (B me C) (D)`, every module in `right`
  /// with its offset (paper 002, Fig. 3).
  int contextDimensions = 1;

  bool hasContext() const { return !left.empty() || !right.empty() || !newLeft.empty() || !newRight.empty(); }
  /// Sets the names only other alternatives bind to 0, before matching (a variant may
  /// have no context left at all: `A > (B |)`).
  void clearUnbound(double* frame) const {
    for (int slot : unboundSlots) frame[slot] = 0;
  }
};

/// An instruction of an interpretation block, e.g. `F(1 + age)`.
struct Instruction {
  std::string command;
  int commandId = -1;  ///< the command's number in its block's set (CommandInfo::id), -1: by name
  std::vector<CompiledExpression> args;
  SourceSpan span;
};

struct InterpretationBlock {
  std::string setName;
  std::vector<Instruction> instructions;
  SourceSpan span;
};

/// A development function g(params, tau, beta) (paper 000, section 3.3).
struct DevelopmentFunction {
  std::string name;
  int arity = 0;
  /// Where each parameter comes from when the function develops a module:
  /// kFromAge, kFromTerminalAge, or the index of a module parameter.
  std::vector<int> sources;
  static constexpr int kFromAge = -1;
  static constexpr int kFromTerminalAge = -2;
  SourceSpan span;
};

/// A read of an enclosing system's value: `parent.x` (level 1: the system whose pool
/// holds the cell), `parent.parent.x` (level 2) ..., or `root.x` (level 0). `age` reads
/// the system's age; other names its state.
struct AncestorRef {
  int level = 1;
  std::string name;
  bool operator==(const AncestorRef&) const = default;
};

struct MasterCell {
  std::string label;
  SourceSpan span;
  bool declared = false;  ///< a `cell` (or an L-system module with productions), not only a symbol
  int scope = -1;         ///< system index of the L-system that owns the symbol, -1: global
  std::vector<std::string> stateNames;
  std::vector<double> defaults;
  double lifetime = kForever;  ///< terminal age β, seconds
  /// Written with ages somewhere, `(X, 3)` or a cell's lifetime: words print it as
  /// `(X, age)`. Untimed L-system symbols print bare, as generations do.
  bool timedNotation = false;
  std::vector<CompiledRule> rules;          ///< evaluated once per step, in order
  std::vector<CompiledRule> terminalRules;  ///< evaluated when age reaches lifetime
  /// L-systems: rewrite the module right after the production step (decomposition) or
  /// only for interpretation (homomorphism), in order, first match (docs/LANGUAGE.md 4.9).
  std::vector<CompiledRule> decompositionRules;
  std::vector<CompiledRule> homomorphismRules;
  std::vector<InterpretationBlock> interpretations;
  int developmentFunction = -1;  ///< index into Program::functions
  std::string command;           ///< the instruction this symbol stands for (label or equiv)
  /// Per set of Program::commandSets, the number of `command` in it (CommandInfo::id):
  /// -1 where the set does not know it, -2 where it knows it by name only.
  std::vector<int> commandIds;
  uint8_t symbolClass = kSymbolModule;
  /// A query module of cpfg (ABOP 1.10): 'P', 'H', 'L' or 'U' for ?P, ?H, ?L, ?U (its
  /// label or equiv), 0 for any other. The environment writes into its parameters.
  char query = 0;
  /// A node of the axial tree (core/parents.h): a module named by a name, not a bracket
  /// or a punctuation symbol that only turns or sets the turtle.
  bool treeNode = true;
  bool readsPosition = false;  ///< a rule reads me.x, me.y or me.z (the engine fills them only then)
  bool readsParent = false;    ///< a rule reads me.parent (the engine finds parents only then)
  /// For a system cell: the index of its SystemDefinition (its cells grow in a pool of
  /// their own); -1 for an ordinary cell.
  int system = -1;

  const InterpretationBlock* interpretation(std::string_view set) const {
    for (const auto& block : interpretations)
      if (block.setName == set) return &block;
    return nullptr;
  }
  uint32_t stateCount() const { return static_cast<uint32_t>(stateNames.size()); }
};

/// How the music set places notes in time (#music; docs/LANGUAGE.md, "Music").
enum class MusicTime : uint8_t {
  Sequential,     ///< reading the word left to right, as the turtle reads it
  Developmental,  ///< a cell plays when it is born, following the development
};

/// Music settings of a system (#music, #tempo, #ppq, #midiformat, #timesig).
struct MusicSettings {
  MusicTime time = MusicTime::Sequential;
  double tempo = 120;  ///< quarter notes per minute at the start
  int ppq = 480;       ///< ticks per quarter note of the MIDI file
  int format = 1;      ///< MIDI file format 0 or 1
  int timeSignatureNumerator = 4;
  int timeSignatureDenominator = 4;
  /// #track C "NAME": the names of the channels' tracks; empty: the cells that play on it.
  std::array<std::string, 16> trackNames{};
};

/// `#surface ID "file.obj"`: a predefined surface the geometry set loads before the run.
struct SurfaceFile {
  int id = 0;            ///< 0..1023, the number surface(id) and blend name it by
  std::string path;      ///< resolved against the directory of the program file
  std::string location;  ///< "file:line:col" of the directive, for load errors
};

/// Interpretation settings of a system (`#angle`, `#length`, ...). Angles in the unit the
/// program chose (degrees unless #radians).
struct InterpretSettings {
  double angle = 90;
  double yawAngle = 90;
  double step = 1;    ///< default move length (#length)
  double radius = 0;  ///< default cylinder radius (#radius); 0 draws lines
  bool radians = false;
  double timestep = 0.002;  ///< the dynamics set's simulation step, seconds (#timestep)
  MusicSettings music{};
  std::vector<SurfaceFile> surfaces{};  ///< #surface directives, in order
};

struct AxiomCell {
  MasterId master = 0;
  std::vector<double> values;
  /// Values that read the enclosing systems (`axiom Trunk(parent.height)`), evaluated
  /// when the pool is seeded; empty, or one per value with the constant ones empty.
  std::vector<CompiledExpression> fromSystems;
  double age = 0;
};

/// `fill A(e)` (every site; values may read the site's `me.x`, `me.y`, `me.z`) or
/// `at(x, y) A(1)` (one site) in a grid system.
struct GridPlacement {
  bool fill = false;
  GridCoordinates at{0, 0, 0};
  MasterId master = 0;
  std::vector<CompiledExpression> values;  ///< frame: FrameSlot layout with no state values
  SourceSpan span;
};

struct SystemDefinition {
  std::string name;
  SourceSpan span;
  int master = -1;  ///< the master cell that stands for the system in a parent's pool
  bool isLSystem = false;
  PoolKind poolKind = PoolKind::Linear;
  GridShape grid;  ///< for a grid pool
  double spatialRadius = 1;  ///< for a spatial pool: the neighbourhood's radius
  std::vector<AxiomCell> axiom;
  std::vector<GridPlacement> placements;  ///< grid pools: after the axiom, in text order
  std::vector<uint8_t> symbolClass;  ///< per master: branch brackets and ignored symbols
  /// L-systems: per `ignore:` / `consider:` line, then one without either, the classes
  /// that the context of the rules below it sees (CompiledRule::symbolClasses).
  std::vector<std::vector<uint8_t>> ruleClasses;
  InterpretSettings settings;
  bool terminalContext = false;  ///< some terminal rule of this system's cells reads context
  bool sampledRules = false;     ///< some cell of this system has per-step rules
  bool rates = false;            ///< some cell of this system integrates `rate` variables
  bool stochastic = false;
  /// Recursion limits of the decomposition and the homomorphism (`maximum depth: N`):
  /// a module is rewritten at most this many times in a row. 1 as in L-Py.
  int decompositionDepth = 1;
  int homomorphismDepth = 1;
  /// `use group: EXPR`: the active rule group, over a frame of internal state only
  /// (reads `time`), evaluated at the start of every step; empty: group 0.
  CompiledExpression useGroup;
  SourceSpan useGroupSpan;
  /// Some production has a new right context `>>`: each production pass goes right to
  /// left, so that what stands right of a module is rewritten before it.
  bool backward = false;
  bool decomposes = false;    ///< some symbol of this system has decomposition rules
  bool homomorphism = false;  ///< some symbol of this system has homomorphism rules
};

/// A `#define` of the program and the value it has, for callers that list or vary them.
struct ProgramDefine {
  std::string name;
  double value = 0;         ///< the value in effect: the text's, or the one given from outside
  int system = -1;          ///< index into Program::systems of the block that holds it, -1: top level
  bool overridden = false;  ///< the value came from CompileOptions::defines
  SourceSpan span;          ///< the #define in the text
};

struct Program {
  std::vector<std::shared_ptr<const SourceFile>> sources;  ///< the texts spans point into
  std::vector<MasterCell> masters;
  std::vector<CompiledExpression> functionBodies;
  std::vector<DevelopmentFunction> functions;
  std::vector<SystemDefinition> systems;
  std::vector<AncestorRef> ancestorRefs;  ///< every `parent.x` / `root.x` read, once each
  /// The interpretation sets the program was checked against (CompileOptions::commandSets),
  /// in order: MasterCell::commandIds are indexed by them. Empty: commands go by name.
  std::vector<std::string> commandSets;
  /// Every #define with a value, in the order the compiler reads them: the top-level
  /// ones (an imported file's before its importer's), then each block's, block by block
  /// in the order of `systems`. A name may appear in several blocks.
  std::vector<ProgramDefine> defines;
  bool hasSystemCells = false;            ///< some system's cell can appear in another's pool
  bool hasQueries = false;  ///< some master is a query module (`?P` ...; core/environment_process.h)
  int root = 0;          ///< index of the root system
  uint64_t seed = 1;     ///< default seed (#seed), overridden by --seed
  bool hasSeed = false;
  double until = 10;     ///< default end of a run (#until), seconds of developmental time
  double dt = 1;         ///< default step (#dt); rules without a terminal age fire once per step
  double from = 0;       ///< time of a run's first frame (#from), seconds
  double framesPerSecond = 0;  ///< frames of a run per second (#fps); 0: one frame unless asked
  /// Seconds of developmental time a second of a run's movie shows (#speed); 0: not given.
  double speed = 0;
  /// The look of a run's pictures and movies (#look: light, dark, paper); empty: light.
  std::string look;
  std::vector<std::string> interpretSets;  ///< sets a run uses unless told (#interpret); empty: geometry
  /// #tolerance: integrate `rate` adaptively (Dormand-Prince) to this absolute and
  /// relative error; 0: classic Runge-Kutta 4, one step per world step.
  double rateTolerance = 0;
  /// #allow nonfinite: state may become an infinity or NaN; otherwise such a value stops
  /// the development (core/finite_state.h).
  bool allowsNonfinite = false;

  FunctionTable functionTable() const { return FunctionTable{functionBodies}; }
  const SystemDefinition& rootSystem() const { return systems[root]; }
  /// The index of a set in commandSets, or -1.
  int commandSetIndex(std::string_view set) const {
    for (size_t i = 0; i < commandSets.size(); ++i)
      if (commandSets[i] == set) return static_cast<int>(i);
    return -1;
  }
  /// The master with this label visible in a scope (an L-system's own symbols first).
  int findMaster(std::string_view label, int scope = -1) const;
};

}  // namespace ontogen
