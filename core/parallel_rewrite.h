#pragma once
// The faster passes of a linear word kept compact (docs/COMPACT_WORDS.md): what a
// system's rules allow, found once from the program, and the executors of the compact
// strategies of core/rewrite_plan.h. Each writes, at one instant, the word the serial
// pass of records writes, bit for bit, whatever the thread count: a cell's choice, ids
// and random numbers derive from the cell and the old word alone.
//
// A word is kept compact where every master's rules compare labels only, draw among
// rules of constant chances by labels, or evaluate their successors' arguments in batches
// without reading their place or parent (compactBatched_); with context, only in a word
// without brackets or ignored modules whose contexts compare a few modules by position.
// A compact word whose labels each do one thing when they expire (Koch, Thue-Morse) is
// walked run by run by a table (pools/table_rewrite.h) and written without counting
// first: in one pass on one thread, by slices placed by bounds on several. A word whose
// choices vary with the context is written in one pass too: where every rule writes one
// successor (a signal), each thread's slice knows its place and is written in place; else
// each thread writes a part of its own, copied into the word after. Other words are
// counted, then written, by slices. Which of these ways a word takes, and on how many
// threads, planRewrite alone decides (core/rewrite_plan.h); a word of records takes the
// development's serial pass (core/linear_development.cpp).

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

  /// What the rules allow, for planRewrite (core/rewrite_plan.h). `compact`: the
  /// development may keep the word compact (appliesToCompactWords, and nothing else of
  /// the system needs the records).
  RewriteShape shape(bool compact) const;
  /// For tests only (WorldDef::testRewriteStrategy): the strategy to take where it applies.
  void force(std::optional<RewriteStrategy> strategy) { forced_ = strategy; }
  /// The strategy that wrote the last compact word (rewriteCompact), after any fallback.
  RewriteStrategy lastStrategy() const { return ran_; }

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

  /// The pass of one instant on a compact word (docs/COMPACT_WORDS.md), on at most
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

  /// Bytes kept from one rewrite to the next: the parts of a word whose
  /// choices vary (written apart, then copied in), the slices and the parts' places.
  uint64_t heldBytes() const;

  /// The earliest terminal age (birth + lifetime) in the word rewriteCompact wrote last,
  /// found while writing it, so the development need not look for it again.
  double earliestDeath() const { return earliestDeath_; }

  /// Words smaller than this go the serial way: threads would cost more than they save.
  static constexpr size_t kMinimumCells = kMinimumSliceCells;

 private:
  // The cells that fired one rule waiting for their successors' values (evaluatesInBatches_):
  // each lane's frame, and where each of its successors' values go in the next word.
  struct Batch {
    int lanes = 0;
    std::vector<double> frames;     // kBatchLanes frames of frameSize_
    std::vector<uint64_t> valueAt;  // per lane, per successor with values: its first value
  };
  /// The facts of a rewrite of a compact word of `size` modules, `threads` being the
  /// world's (WorldDef::threads): how many the rewrite takes, planRewrite alone decides.
  RewriteFacts facts(size_t size, unsigned threads) const;
  /// The rule a cell of `master` (drawsByChance_) with id `id` draws at `death`, or null.
  static const CompiledRule* drawByChances(const MasterCell& master, uint64_t seed, uint64_t id, double death);
  /// The rule a cell of `master` (label `label`), whose choice needs no frame, fires
  /// whatever its context: none, the first, or drawn by chances.
  const CompiledRule* contextFreeRule(const MasterCell& master, uint32_t label, uint64_t seed, uint64_t id,
                                      double death) const;
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
  bool atInstants_ = true;  // the rules may be rewritten at an instant: no cut, decomposition, `<<`, birth age ...
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
  /// Whether `master`'s successors' arguments may be evaluated in batches (compactBatched_).
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
  /// the rule it fires (or its renewal) written through `out` as the serial pass writes it,
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
  std::vector<std::vector<LabelRule>> labelRules_;
  bool allByPosition_ = true;  // every label-only rule with context compares by position
  // Per master with state whose terminal rules (one, or several drawn by constant chances)
  // are of group 0 without condition, calculation or birth age, whose successors'
  // arguments are straight-line code without a draw (CompiledExpression::batchable), and
  // which reads neither its place nor its parent: a compact word holds its values, and
  // rewriteCompact evaluates its successors' arguments for kBatchLanes cells of a rule at
  // once (the benchmarks' parametric word). Its place is left out because the serial
  // context-free pass gives a successor that expires within the step its ancestor's place
  // at the start of the step, which the compact pass, instant by instant, does not know.
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
  // Per master: its first rule has a chance, so its cells draw among its rules (each of
  // group 0, without condition or context, with a constant chance or none).
  std::vector<uint8_t> drawsByChance_;
  // Per terminal rule of every master, masters in order (firstRule_: each master's first):
  // the values its successors take. Batches are kept per rule.
  std::vector<uint32_t> batchedValues_;
  std::vector<uint32_t> firstRule_;
  FunctionTable functions_;
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
  size_t frameSize_ = 0;
  double earliestDeath_ = kForever;
  std::optional<RewriteStrategy> forced_;
  RewriteStrategy ran_ = RewriteStrategy::CompactSerial;
};

}  // namespace ontogen
