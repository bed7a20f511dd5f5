#pragma once
// The production pass of a large linear word on every core. Each thread takes a slice of
// the word; a first pass counts what each slice will write (the cells and state values
// of the successors its cells' chosen rules make), prefix sums give each slice its place
// in the next word, and a second pass writes every slice in place, choosing again. The
// next word is bit for bit the one the serial pass writes, whatever the thread count: a
// cell's choice, ids and random numbers derive from the cell and the old word alone.
//
// Two passes of the linear development come here:
//  - the context-free pass (rewriteContextFree), when every master's rules are of group
//    0 without context, neighbour aggregate or birth age (a condition or a chance is
//    evaluated in the cell's frame, a constant chance drawn without it); in a step where
//    no successor reaches its own terminal age before the step's end;
//  - the pass of one instant with context (rewriteAtInstant), when no rule reads the
//    word being written (`<<`, `>>`), aggregates neighbours or gives a birth age, and the
//    system has no decomposition. Masters without state whose rules only compare labels
//    (no condition, chance, calculation or bound value, successors without state) are
//    rewritten without loading a frame or a random stream.
// Neither applies with a cut symbol, with the lineage being logged, or when the new word
// would pass a limit: then the development takes its serial pass, which reports the
// limit as it always did. On one thread the slices are taken only when nothing is
// evaluated cell by cell: every master compares labels only (Koch, Thue-Morse, a signal),
// or, in the context-free pass, each master either compares labels only or has one rule
// without choice or calculation whose successors' arguments are evaluated for many cells
// at once (the benchmarks' parametric word). There two quick passes beat the general one;
// other words with state keep the serial pass. A compact word whose labels each do one
// thing when they expire (Koch, Thue-Morse) is walked run by run by a table
// (pools/table_rewrite.h) and written without counting first: in one pass on one thread,
// by slices placed by bounds on several. A compact word may hold values too, where every
// master with state evaluates its successors' arguments in batches without reading its
// place or parent (compactBatched_): its new successors go in one run, their values are
// left in place and written when the batch is evaluated. A word whose choices vary with
// the context is written in one pass too: where every rule writes one successor (a
// signal), each thread's slice knows its place and is written in place; else each thread
// writes a part of its own, copied into the word after. Which of these ways a word takes,
// and on how many threads, planRewrite alone decides (core/rewrite_plan.h).

#include <algorithm>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/development.h"
#include "core/rewrite_plan.h"
#include "core/successors.h"
#include "model/program.h"
#include "pools/compact_word.h"
#include "pools/linear_pool.h"
#include "pools/table_rewrite.h"

namespace ontogen {

class ParallelRewrite {
 public:
  ParallelRewrite(const Program& program, const SystemDefinition& system);

  bool appliesContextFree() const { return contextFree_; }
  bool appliesAtInstants() const { return atInstants_; }

  /// What the rules allow, for planRewrite (core/rewrite_plan.h). `compact`: the
  /// development may keep the word compact (appliesToCompactWords, and nothing else of
  /// the system needs the records).
  RewriteShape shape(bool compact) const;
  /// For tests only (WorldDef::testRewriteStrategy): the strategy to take where it applies.
  void force(std::optional<RewriteStrategy> strategy) { forced_ = strategy; }
  /// The strategy that wrote the last compact word (rewriteCompact), after any fallback.
  RewriteStrategy lastStrategy() const { return ran_; }

  /// The context-free pass of the step ending at `horizon`: rewrites `pool`'s word into
  /// `cells` and `state` (emptied first), with `parents` the me.parent value of each cell
  /// (null when no rule reads it). Returns false, leaving them empty, when the step needs
  /// the serial pass; else adds the step's events to `events` and `context.stats`.
  bool rewriteContextFree(const LinearPool& pool, double horizon, StepContext& context, const double* parents,
                          uint64_t& events, CellArray& cells, StateArray& state);

  /// The pass of the cells that expire by `instant` in a word with context (its branches
  /// indexed), with rule group `group` active; as rewriteContextFree otherwise.
  bool rewriteAtInstant(const LinearPool& pool, double instant, int group, StepContext& context, const double* parents,
                        uint64_t& events, CellArray& cells, StateArray& state);

  /// Whether rewriteCompact applies: every master's rules compare labels only, or are
  /// evaluated in batches without reading the cell's place (compactBatched_), and give no
  /// birth age; the system neither decomposes nor derives backward and has no cut symbol;
  /// and either no rule has a context (brackets are then labels like any other: a plant's
  /// F -> F [ + F ] F) or the word has no brackets or ignored modules and every context
  /// compares at most kPositionItems modules a side.
  bool appliesToCompactWords() const {
    return allCompact_ && atInstants_ && (!anyContext_ || (plain_ && allByPosition_));
  }

  /// Whether rewriteCompact walks the word by a table (pools/table_rewrite.h): every
  /// master has one rule of group 0 without context, chance or condition, or none, a
  /// rule's successors are all new, and their values, if any, each one operation on the
  /// cell's own (ValueOperation); at most 256 masters (Koch, Thue-Morse, the parametric
  /// A(x) -> A(x + 1) B(x * 0.5)).
  bool rewritesByTable() const { return byTable_; }
  /// The table, when rewritesByTable().
  const RewriteTable& table() const { return table_; }
  /// Whether rewriteCompact writes words rewritten by the table without ids
  /// (CompactWord::holdsIds; docs/COMPACT_WORDS.md, "Words without ids"). It then takes
  /// the table's walk for every word, small ones too, and accepts words held without ids.
  void writeWithoutIds(bool on) { withoutIds_ = on && byTable_; }
  bool writesWithoutIds() const { return withoutIds_; }

  /// Says whether the next word may be written, or go on being written: its modules, the
  /// events and the cells born, so far or in all, and the modules whose bytes are held
  /// meanwhile (more than `modules` where parts of the word are written apart and then
  /// copied into it). False: rewriteCompact gives the word up, so the caller can take a
  /// pass that reports the limit. Asked with growing figures, it must not refuse less
  /// figures than it accepted; it may be asked from several threads at once.
  using CompactFits = std::function<bool(uint64_t modules, uint64_t events, uint64_t born, uint64_t heldModules)>;

  /// The pass of rewriteAtInstant on a compact word (docs/COMPACT_WORDS.md), on at most
  /// `threads` threads by the strategy planRewrite picks: writes `next` from `word`. Every cell whose
  /// terminal age is at most `horizon` fires the rule it chooses, rule group `group` active,
  /// its context read in `word`, or renews itself; its successors are born at its terminal
  /// age, with the ids the other passes give them. Other cells are copied. Returns the
  /// number of events and of cells born, or nothing when `fits` refused the word;
  /// earliestDeath() gives the earliest terminal age in `next`. Needs
  /// appliesToCompactWords().
  struct CompactCounts {
    uint64_t events = 0, born = 0;
  };
  /// `seed` is the run's: a stochastic rule's draw comes from the cell's stream, as in
  /// the records' passes. `ancestors`: the values the cells' expressions read of their
  /// ancestors (StepContext::ancestors).
  std::optional<CompactCounts> rewriteCompact(const CompactWord& word, double horizon, int group, unsigned threads,
                                              CompactWord& next, const CompactFits& fits = {}, uint64_t seed = 0,
                                              const double* ancestors = nullptr);

  /// The earliest terminal age (birth + lifetime) in the word rewriteAtInstant wrote last,
  /// found while writing it, so the development need not look for it again.
  double earliestDeath() const { return earliestDeath_; }

  /// Words smaller than this go the serial way: threads would cost more than they save.
  static constexpr size_t kMinimumCells = kMinimumSliceCells;

 private:
  enum class Pass : uint8_t { ContextFree, AtInstant };
  // On cache lines of its own: a thread updates its slice's counts cell by cell.
  struct alignas(64) Slice {
    size_t begin = 0, end = 0;  // cells of the word
    uint64_t cells = 0, values = 0, events = 0, born = 0;
    bool chained = false;             // the context-free pass: a successor expires within the step
    double earliestDeath = kForever;  // of the cells it wrote
  };
  // The cells that fired one rule waiting for their successors' values (evaluatesInBatches_):
  // each lane's frame, and where each of its successors' values go in the next word.
  struct Batch {
    int lanes = 0;
    std::vector<double> frames;     // kBatchLanes frames of frameSize_
    std::vector<uint64_t> valueAt;  // per lane, per successor with values: its first value
  };
  struct Worker {
    explicit Worker(const Program& program) : successors(program) {}
    SuccessorWriter successors;
    std::vector<double> frame;
    std::vector<std::pair<const CompiledRule*, double>> candidates;
    uint32_t matched[kMaxContextItems];
    std::vector<Batch> batches;  // per master, for the context-free pass
  };
  /// What one pass reads besides the word.
  struct Step {
    const LinearPool& pool;
    double horizon;  // cells that die by it expire
    int group;
    const StepContext& context;
    const double* parents;
  };

  /// The facts of a rewrite of a word of `size` modules by `pass`, `threads` being the
  /// world's (WorldDef::threads): how many the rewrite takes, planRewrite alone decides.
  RewriteFacts facts(RewritePass pass, size_t size, unsigned threads, const StepContext* context) const;
  bool rewrite(Pass pass, const Step& step, StepContext& context, uint64_t& events, CellArray& cells,
               StateArray& state);
  void count(Pass pass, const Step& step, Slice& slice, Worker& worker);
  void write(Pass pass, const Step& step, Slice& slice, uint64_t firstCell, uint64_t firstValue, Worker& worker,
             CellArray& cells, StateArray& state) const;
  /// The rule cell i (whose values are `state`) chooses (null: it renews itself), with
  /// its frame loaded and its context's values bound; as LinearDevelopment::expire chooses.
  const CompiledRule* choose(Pass pass, const Step& step, size_t i, const double* state, double death, Worker& worker,
                             RandomStream& random, const EvalContext& evaluation) const;

  bool matchesLabels(const Step& step, const CompiledRule& rule, size_t i, Worker& worker) const;
  /// The rule a cell of `master` (drawsByChance_) with id `id` draws at `death`, or null.
  static const CompiledRule* drawByChances(const MasterCell& master, uint64_t seed, uint64_t id, double death);
  /// The rule a cell of `master` (label `label`), whose choice needs no frame, fires in the
  /// context-free pass: none, the first, or drawn by chances.
  const CompiledRule* contextFreeRule(const MasterCell& master, uint32_t label, uint64_t seed, uint64_t id,
                                      double death) const;
  /// The context-free pass's write of a cell of a master that evaluates in batches: its
  /// records now, at their places, and its frame in the master's batch, whose values are
  /// written when it is full (flushBatch) or at the end of the slice.
  template <class Put>
  void writeBatched(const Step& step, const CellRecord& cell, const double* state, double death, size_t i,
                    Worker& worker, double* outValues, uint64_t& valueAt, const Put& put) const;
  /// Evaluates the successors' arguments of every cell waiting in `batch` (master
  /// `master`), lane by lane over each argument's code, into `outValues`; `seed` and
  /// `ancestors` as StepContext's.
  void flushBatch(const CompiledRule& rule, Batch& batch, uint64_t seed, const double* ancestors,
                  double* outValues) const;
  /// The batch of rule `ruleIndex` (firstRule_) among `batches`, its frames made the first
  /// time.
  [[gnu::always_inline]] Batch& batchOf(std::vector<Batch>& batches, uint32_t ruleIndex,
                                        const CompiledRule& rule) const {
    if (batches.size() < batchedValues_.size()) [[unlikely]]
      batches.resize(batchedValues_.size());
    Batch& batch = batches[ruleIndex];
    if (batch.frames.empty()) [[unlikely]]
      makeFrames(batch, rule);
    return batch;
  }
  void makeFrames(Batch& batch, const CompiledRule& rule) const;
  /// flushBatch for every batch among `batches` (per rule, firstRule_) with cells waiting.
  void flushWaiting(std::vector<Batch>& batches, uint64_t seed, const double* ancestors, double* outValues) const;

  const Program& program_;
  const SystemDefinition& system_;
  bool contextFree_ = true;
  bool atInstants_ = true;
  std::vector<uint8_t> labelsOnly_;  // per master: its rules compare labels only
  bool plain_ = false;               // no symbol is a bracket, a cut or ignored
  bool anyContext_ = false;          // some terminal rule has a context
  // Per master whose rules compare labels only: its terminal rules in order, with what
  // the choice reads of them side by side.
  struct LabelRule {
    const CompiledRule* rule = nullptr;
    int group = 0;
    bool context = false;
    // A stochastic rule: its constant chance, and whether it continues the rule before it
    // (CompiledRule::variant).
    bool stochastic = false;
    double chance = 0;
    int variant = 0;
    // What the rule writes when it fires: cells, state values and cells born; each
    // successor's label and whether it keeps the cell's id (`me`, `=X`); the shortest
    // lifetime among them.
    uint32_t cells = 0, values = 0, born = 0;
    struct Written {
      uint32_t label;
      bool keepsId;
    };
    std::vector<Written> written;
    // The successors' labels when none keeps the cell's id and they fit in one run of a
    // compact word (CompactWord::Slice::appendFreshRun); else empty.
    std::vector<uint32_t> freshLabels;
    double shortestLife = kForever;
    // In a plain word, a context of at most kPositionItems modules a side compared by
    // position: per item the master expected there, or kAnyLabel, kEndLabel, kNoMatch.
    bool byPosition = false;
    uint8_t leftCount = 0, rightCount = 0;
    int32_t left[4] = {}, right[4] = {};
  };
  static constexpr size_t kPositionItems = 4;
  static constexpr int32_t kAnyLabel = -1, kEndLabel = -2, kNoMatch = -3;
  LabelRule labelRule(const Program& program, uint32_t master, const CompiledRule& rule) const;
  /// Whether the context-free pass evaluates `master`'s successors in batches.
  bool evaluatesInBatches(const Program& program, const MasterCell& master, bool draws) const;
  /// rewriteCompact on several threads for a word whose choices vary: each thread writes
  /// its share in one pass into a part of parts_, then copies it into the next word.
  std::optional<CompactCounts> rewriteInParts(const CompactWord& word, double horizon, int group, unsigned threads,
                                              CompactWord& next, const CompactFits& fits, uint64_t seed);
  /// rewriteCompact on several threads for a word whose choices vary and whose modules
  /// each write one (oneForOne_): each thread writes its slice in place in one pass.
  CompactCounts rewriteOneForOne(const CompactWord& word, double horizon, int group, unsigned threads,
                                 CompactWord& next, uint64_t seed, double expectedBirth);
  /// After every slice of `next` (rewritten from `word`) wrote: the runs of slices placed
  /// by bounds moved together (`closeGaps`), seams and births joined, the slices' runs
  /// renumbered on `threads`, the word finished; the earliest of `earliest` and the
  /// growth kept for the next rewrite.
  void joinWrittenSlices(const CompactWord& word, CompactWord& next, std::span<CompactWord::Slice> slices,
                         std::span<const double> earliest, bool closeGaps, unsigned threads);
  /// rewriteCompact on one thread in one pass, asking `fits` on the way (CompactSerial).
  std::optional<CompactCounts> rewriteSerially(const CompactWord& word, double horizon, int group, CompactWord& next,
                                               const CompactFits& fits, uint64_t seed, const double* ancestors);
  /// rewriteCompact by slices on `threads`: placed by the table's bounds first when
  /// `byBounds` (TableBounds), else counted then written (CompactSlices).
  std::optional<CompactCounts> rewriteBySlices(const CompactWord& word, double horizon, int group, unsigned threads,
                                               CompactWord& next, const CompactFits& fits, uint64_t seed,
                                               const double* ancestors, double expectedBirth, bool byBounds);
  /// rewriteCompact on one thread for a word rewritten by the table: one pass, no count.
  /// `expectedBirth`: the birth most new modules will likely have.
  std::optional<CompactCounts> rewriteByTableAlone(const CompactWord& word, double horizon, CompactWord& next,
                                                   const CompactFits& fits, double expectedBirth);
  /// What the expressions of a compact rewrite read besides the word: the run's seed and
  /// the ancestors' values; and the batches of one rewriteRange (compactBatched_).
  struct CompactEvaluation {
    uint64_t seed = 0;
    const double* ancestors = nullptr;
    std::vector<Batch> batches;  // per rule (firstRule_), made as they are needed
  };
  /// rewriteCompact's work on cells [begin, end) of `word`, written through `out`.
  /// kWithValues: withValues_; words of labels alone take the loop without values.
  template <bool kWithValues, class Out, class Labels, class Stop>
  CompactCounts rewriteRange(const CompactWord& word, size_t begin, size_t end, double horizon, int group,
                             const Labels& labels, Out& out, const Stop& stop, double& soonest,
                             CompactEvaluation& evaluation) const;
  /// rewriteRange<true>, out of line: inlined beside the loop without values, it made
  /// that loop keep its figures on the stack (the signal 8 % slower).
  template <class Out, class Labels, class Stop>
  CompactCounts rewriteRangeWithValues(const CompactWord& word, size_t begin, size_t end, double horizon, int group,
                                       const Labels& labels, Out& out, const Stop& stop, double& soonest,
                                       CompactEvaluation& evaluation) const;
  /// rewriteRange's event of `cell`, of a master of compactBatched_, dying at `death`:
  /// the rule it fires (or its renewal) written through `out` as writeBatched writes it,
  /// the successors' values left to `evaluation`'s batches while writing.
  template <class Out>
  void expireBatched(const CompactWordCursor& cell, uint32_t label, double death, Out& out, CompactCounts& counts,
                     double& soonest, CompactEvaluation& evaluation) const;
  /// Whether `choice`'s context matches around cell i of a plain word whose label at j
  /// is labels[j] (j below size).
  template <class Labels>
  [[gnu::always_inline]] static bool matchesByPosition(const Labels& labels, size_t size, const LabelRule& choice,
                                                       size_t i);
  /// The label-only rule cell i of master `master` chooses at an instant, all of whose
  /// contexts compare by position (null: it renews itself). A stochastic rule's choice
  /// calls `draw()` for the cell's first uniform draw.
  template <class Labels, class Draw>
  [[gnu::always_inline]] const LabelRule* chooseByPosition(const Labels& labels, size_t size, uint32_t master,
                                                           int group, size_t i, const Draw& draw) const;
  /// The draw among master `master`'s rule r and the later stochastic rules that apply.
  template <class Labels>
  const LabelRule* drawAmong(const Labels& labels, size_t size, uint32_t master, int group, size_t i, size_t r,
                             double uniform) const;
  // The most stochastic rules a master may have for its choice to be drawn by labels.
  static constexpr size_t kMostDrawn = 64;
  /// The rule of a master whose choice is fixed (fixedChoice_), or null.
  const LabelRule* fixedRule(uint32_t master) const {
    return labelRules_[master].empty() ? nullptr : &labelRules_[master].front();
  }
  /// The rule a master whose rules compare labels only chooses for cell i (null: it renews
  /// itself): no frame, no random stream.
  const LabelRule* chooseByLabels(Pass pass, const Step& step, size_t i, Worker& worker) const;
  std::vector<std::vector<LabelRule>> labelRules_;
  bool allLabelsOnly_ = true;
  bool allByPosition_ = true;  // every label-only rule with context compares by position
  // Per master that evaluates in batches (evaluatesInBatches_) and reads neither its place
  // nor its parent: a compact word holds its values, and rewriteCompact writes its
  // successors as writeBatched does (the benchmarks' parametric word). Its place is left
  // out because the context-free pass gives a successor that expires within the step its
  // ancestor's place at the start of the step, which the compact pass, instant by
  // instant, does not know.
  std::vector<uint8_t> compactBatched_;
  bool anyCompactBatched_ = false;
  // Per terminal rule (firstRule_) of a master of compactBatched_: what it writes.
  std::vector<LabelRule> batchedRules_;
  // Every master compares labels only, draws among rules of constant chances by labels,
  // or is of compactBatched_.
  bool allCompact_ = true;
  bool anyState_ = false;    // some master has state values
  bool withValues_ = false;  // anyState_ or anyCompactBatched_
  // Per master whose rules compare labels only and whose choice is the same for every
  // cell (one rule of group 0 without context, or none): that rule, or null.
  std::vector<uint8_t> fixedChoice_;
  bool anyChoiceVaries_ = false;
  // Every rule that acts writes one successor (`b < a -> b`, `a -> b : 0.5`): each module
  // of a word becomes one module, whichever rule it chooses, so a slice of the word knows
  // where its successors go before choosing (rewriteOneForOne).
  bool oneForOne_ = true;
  // Per cell of the word, for a master whose rules compare labels only and whose choice
  // varies: the rule the counting pass chose (1 + its index; 0: none), which the writing
  // pass takes as it is. Left empty when no master's choice varies (Koch, Thue-Morse).
  std::vector<uint16_t> chosen_;
  std::vector<double> shortestLife_;  // per master: the shortest lifetime of what its rule writes
  // Per master: its first rule has a chance, so the context-free pass draws among its rules
  // (each of group 0, without condition or context, with a constant chance or none).
  std::vector<uint8_t> drawsByChance_;
  // Per master: a rule has a condition or a chance that is an expression, so even the
  // context-free pass chooses in the cell's frame, as the serial pass does (choose).
  std::vector<uint8_t> choosesInFrame_;
  // Per master with state whose terminal rules (one, or several drawn by constant chances)
  // are of group 0 without condition, calculation or birth age, and whose successors'
  // arguments are straight-line code without a draw (CompiledExpression::batchable): the
  // context-free pass evaluates those arguments for kBatchLanes cells of a rule at once.
  // With every master so or label-only, the context-free pass takes the slices on one
  // thread too: nothing is left to evaluate cell by cell.
  std::vector<uint8_t> evaluatesInBatches_;
  // Per terminal rule of every master, masters in order (firstRule_: each master's first):
  // the values its successors take. Batches are kept per rule.
  std::vector<uint32_t> batchedValues_;
  std::vector<uint32_t> firstRule_;
  bool allInBatchesOrLabelsOnly_ = true;
  FunctionTable functions_;
  std::vector<Slice> slices_;
  std::vector<CompactWord::Slice> compactSlices_;
  // Parts of a word whose choices vary, written each by a thread of its own and copied
  // into the next word by it; kept from step to step. On cache lines of their own: a writer
  // updates its word's size and tail module by module.
  struct alignas(64) Part {
    CompactWord word;
  };
  std::vector<Part> parts_;
  std::vector<CompactWord::PartPlace> partPlaces_;  // where parts_ go in the next word
  std::vector<double> lifetimes_;                   // per master, for rewriteCompact (MasterCell is large)
  // Every master does the same whenever it expires (one label-only rule or none, or one
  // rule computing its successors' values by ValueOperations), and successors, if any,
  // are all new (no `me`, no `=X`), in a word of one-byte labels: what each label
  // becomes, so that rewriteCompact walks the word by a table (pools/table_rewrite.h).
  // tableEntry adds master m's entry, or says it has none.
  bool tableEntry(const Program& program, uint32_t m);
  bool byTable_ = false;
  RewriteTable table_;
  bool withoutIds_ = false;  // writeWithoutIds
  // Set once slices placed by their bounds wrote less than the bounds: from then on the
  // slices of this development count first.
  bool boundsMissed_ = false;
  // How much the last compact rewrite grew its word (next / old), modules, runs and
  // values; 0: none yet. The one-thread pass reserves by it.
  struct Growth {
    double modules = 0, runs = 0, values = 0;
    static Growth of(const CompactWord& word, const CompactWord& next) {
      if (word.empty() || word.runCount() == 0) return {};
      return {static_cast<double>(next.size()) / static_cast<double>(word.size()),
              static_cast<double>(next.runCount()) / static_cast<double>(word.runCount()),
              word.valueCount() == 0 ? 0.0
                                     : static_cast<double>(next.valueCount()) / static_cast<double>(word.valueCount())};
    }
    /// Room for `count` grown by `ratio`, a sixteenth more, at most 8 times `count`: a
    /// word growing faster grows its arrays as it goes, at the cost of a copy.
    static size_t room(size_t count, double ratio) {
      return static_cast<size_t>(static_cast<double>(count) * std::min(ratio, 8.0) * (17.0 / 16.0)) + 64;
    }
  };
  Growth lastGrowth_;
  std::vector<std::unique_ptr<Worker>> workers_;
  size_t frameSize_ = 0;
  double earliestDeath_ = kForever;
  std::optional<RewriteStrategy> forced_;
  RewriteStrategy ran_ = RewriteStrategy::CompactSerial;
};

}  // namespace ontogen
