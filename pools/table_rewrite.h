#pragma once
// One rewrite of a compact word whose labels each do the same thing whenever they
// expire: they are renewed, or replaced by the same string of new successors (Koch,
// Thue-Morse, any D0L system without state), whose values, if any, are each one operation
// on the module's own (pools/value_operation.h: A(x) -> A(x + 1) B(x * 0.5)). It is the
// fast path of ParallelRewrite::rewriteCompact (core/parallel_rewrite.h) for such words.
//
// It walks the word a run at a time instead of a module at a time: the run's key, birth
// and first k are read once, and the first part of the hash that names the parent of new
// successors (mixKeyFirst of the run's key) is computed once per run, not once per
// module. It writes through a CompactWord::Slice, counting or writing, with the same
// canonical rule and the same encoding as the module-by-module pass: a kept or renewed
// module continues the run of the module before it by RunTail's rule, and the new
// successors of one event make one run that nothing continues.
//
// The walks that name the successors' parents are templates of the lineage (core's
// TerminalLineage), so they stay here; the rest is in pools/table_rewrite.cpp.

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "pools/compact_word.h"
#include "pools/mix_key.h"
#include "pools/value_operation.h"

namespace ontogen {

/// What each label does when one of its modules expires, the same for every module.
struct RewriteTable {
  struct Entry {
    /// The terminal age: a module expires when its birth plus this is at most the horizon.
    double lifetime = std::numeric_limits<double>::infinity();
    /// Renewed (the same id, born again at its death), or replaced by `count` new
    /// successors with the labels labels[first ..], as one run of fresh ids.
    bool renews = true;
    uint32_t first = 0, count = 0;
    /// The shortest lifetime among what it becomes (its own lifetime when renewed).
    double lifeAfter = std::numeric_limits<double>::infinity();
    /// The successors' labels as bytes, the first in the lowest, when there are at most
    /// eight of them: written with one store.
    uint64_t packed = 0;
    /// The successors' state values, each from the module's own by operations[first ..]
    /// (setOperations), one a value, successor after successor.
    uint32_t firstOperation = 0, operationCount = 0;
  };
  /// Sets the labels of `entry` (one byte each) and appends them to `labels`.
  void setSuccessors(Entry& entry, const std::vector<uint32_t>& successors);
  /// Sets how the successors of `entry` (setSuccessors) compute their state values from
  /// the module's: one operation a value, in the order of the successors and their values.
  void setOperations(Entry& entry, const std::vector<ValueOperation>& computed);
  /// After the last entry, once: the steps and bytes the walks read. `values`: each
  /// label's count of state values (none: a word of labels alone).
  void finish(std::vector<uint32_t> values = {});
  std::vector<Entry> entries;    // per label
  std::vector<uint32_t> labels;  // the successors' labels, every entry's in turn
  /// What a module does, kept (steps[2 * label]) or expiring (steps[2 * label + 1]):
  /// the labels it writes (bytes[source ..], count of them), the cells born, whether it
  /// is an event, and what its death adds to give the earliest death after it.
  ///
  /// `joins`: the module is timeless (its lifetime is forever) and kept. Without ids its
  /// birth is not written: it continues the run under way, whatever that run's birth (no
  /// walk reads the birth of a module that never expires, and the replay of the ids gives
  /// every module its own, docs/COMPACT_WORDS.md). Koch's turns so join the run of the F
  /// beside them.
  ///
  /// The values it writes: operations[firstOperation ..], operationCount of them, which
  /// read the module's own values.
  struct Step {
    uint32_t source = 0, count = 0, born = 0, event = 0;
    double soonAfter = 0;
    bool joins = false;
    uint32_t firstOperation = 0, operationCount = 0;
    /// Every operation is affine (ValueOperation::affine): x * multiplier + addend.
    bool affine = false;
  };
  std::vector<Step> steps;
  std::vector<double> lifetimes;  // per label
  /// Every label that expires has the same lifetime (runLifetime), with at most 16
  /// successors, and the others are timeless: the modules of a run of the old word that
  /// can expire all expire at one instant, or none does; runSteps[label] is the step each
  /// label takes when they do.
  bool oneLifetime = false;
  double runLifetime = kForever;
  std::vector<uint32_t> runSteps;
  bool anyTimeless = false;  // some label never expires
  /// State values: per label how many a module holds (stateCounts), and the most its step
  /// writes, kept or expiring (boundValues); how successors compute theirs (operations).
  bool withValues = false;
  std::vector<uint32_t> stateCounts, boundValues;
  std::vector<ValueOperation> operations;
  static constexpr double kForever = std::numeric_limits<double>::infinity();
  /// The successors' labels as bytes, then each label itself, then kBytesPadding zeros:
  /// up to 16 labels of a step are copied with one store of 16 bytes.
  static constexpr size_t kBytesPadding = 16;
  std::vector<uint8_t> bytes;
};

/// What modules [begin, end) of a word write at most by a table, if each that can expire
/// does: modules, events and cells born.
struct TableBound {
  uint64_t modules = 0, events = 0, born = 0, values = 0;
};

/// What one table rewrite did: events (modules that expired), modules born, and the
/// earliest death among the modules it wrote.
struct TableRewriteCounts {
  uint64_t events = 0, born = 0;
  double soonest = std::numeric_limits<double>::infinity();
};

class TableRewrite {
 public:
  /// Rewrites modules [begin, end) of `from` (one-byte labels) by
  /// `table` at `horizon` into `out`, which counts or writes (CompactWord::Slice). The
  /// new successors of a module with id `parent` dying at `death` take the lineage key
  /// `lineage(parentFirst, death)`, where parentFirst is mixKeyFirst(parent).
  ///
  /// `withIds` false writes the word without ids (CompactWord::holdsIds): no key is
  /// computed, a module continues the run of the module before it whenever both are born
  /// at the same instant, and `lineage` is not called. `from` may then be held without
  /// ids too.
  template <class Lineage>
  static TableRewriteCounts rewrite(CompactWord::Slice& out, const CompactWord& from, size_t begin, size_t end,
                                    const RewriteTable& table, double horizon, Lineage& lineage, bool withIds = true) {
    if (table.withValues) {
      if (withIds)
        return out.writing() ? walkValues<true, true>(out, from, begin, end, table, horizon, lineage)
                             : walkValues<false, true>(out, from, begin, end, table, horizon, lineage);
      return out.writing() ? walkValues<true, false>(out, from, begin, end, table, horizon, lineage)
                           : walkValues<false, false>(out, from, begin, end, table, horizon, lineage);
    }
    if (!withIds) {
      // Steps noted a run when runs are long (Thue-Morse: 54 against 63 ms); Koch's runs
      // of five modules or so pay more for the note than for the minima (20 against 19 ms).
      if (table.steps.size() <= 64 && from.size() >= 8 * from.runCount())
        return out.writing() ? walkWithoutIds<true, true>(out, from, begin, end, table, horizon)
                             : walkWithoutIds<false, true>(out, from, begin, end, table, horizon);
      return out.writing() ? walkWithoutIds<true, false>(out, from, begin, end, table, horizon)
                           : walkWithoutIds<false, false>(out, from, begin, end, table, horizon);
    }
    return out.writing() ? walk<true>(out, from, begin, end, table, horizon, lineage)
                         : walk<false>(out, from, begin, end, table, horizon, lineage);
  }

  /// What modules [begin, end) of `from` write at most by `table`, from the counts of
  /// their labels (pools/label_counts.h). Modules and values are exact where every module
  static TableBound bound(const CompactWord& from, size_t begin, size_t end, const RewriteTable& table);

 private:
  // The first run start after module i in `starts`, before `end`, or `end`.
  static size_t nextRunStart(const uint64_t* starts, size_t i, size_t end) {
    for (size_t w = (i + 1) / CompactWord::kBlock, last = (end - 1) / CompactWord::kBlock; w <= last; ++w) {
      uint64_t word = starts[w];
      if (w == (i + 1) / CompactWord::kBlock) word &= ~uint64_t{0} << ((i + 1) % CompactWord::kBlock);
      if (word != 0) return std::min(end, w * CompactWord::kBlock + static_cast<size_t>(std::countr_zero(word)));
    }
    return end;
  }
  // mixKeyFirst of the id (key, k) of a parent: the first half of the hash its successors'
  // lineage key takes. mixKeyFirst(key) is computed once a run (keyFirst, once known).
  static uint64_t parentFirstOf(uint64_t key, uint32_t k, uint64_t& keyFirst, bool& keyFirstKnown) {
    if (k == IdKey::kWhole) return mixKeyFirst(key);
    if (!keyFirstKnown) {
      keyFirst = mixKeyFirst(key);
      keyFirstKnown = true;
    }
    return mixKeyFirst(mixKeyJoin(keyFirst, mixKeySecond(k)));
  }

  // What the walk keeps of the slice it writes, in locals rather than in the slice: a
  // label is written through a byte pointer, which may alias anything, so the compiler
  // would read every field of the slice again after each one. Without ids (kWithIds
  // false) a run keeps its birth alone.
  template <bool kWithIds>
  struct Writer {
    explicit Writer(CompactWord::Slice& slice)
        : slice(slice),
          at(slice.firstModule_ + slice.written_),
          sliceEnd(slice.firstModule_ + slice.modules_),
          runs(slice.runs_),
          runJ(slice.runJ_),
          bits(slice.bits_),
          bitsWord(slice.bitsWord_),
          labels(slice.out_.labels8),
          keys(slice.out_.keys),
          birthIndex(slice.out_.birthIndex),
          firstK(slice.out_.firstK),
          values(slice.out_.values),
          valueAt(slice.firstValue_ + slice.writtenValues_) {
      if (slice.word_ && slice.word_->stateless_) {  // writing a word without values
        runStarts = slice.word_->runStarts_.data();
        blockRuns = slice.word_->blockRuns_.data();
        blockJ = slice.word_->blockJ_.data();
      }
    }
    // Gives the slice back its state, before one of its own calls and at the end.
    void store() {
      slice.written_ = at - slice.firstModule_;
      slice.runs_ = runs;
      slice.runJ_ = runJ;
      slice.bits_ = bits;
      slice.bitsWord_ = bitsWord;
      slice.writtenValues_ = valueAt - slice.firstValue_;
    }
    void load() {
      at = slice.firstModule_ + slice.written_;
      valueAt = slice.firstValue_ + slice.writtenValues_;
      runs = slice.runs_;
      runJ = slice.runJ_;
      bits = slice.bits_;
      bitsWord = slice.bitsWord_;
    }
    // As CompactWord::Slice::put, for a module without values.
    void put(uint32_t label, IdKey key, bool continues, uint32_t index) {
      if (at % CompactWord::kBlock == 0 || bitsWord == SIZE_MAX) [[unlikely]] {
        store();
        slice.startBlock(at);
        load();
      }
      if (!continues) {
        bits |= uint64_t{1} << (at % CompactWord::kBlock);
        birthIndex[runs] = index;
        if constexpr (kWithIds) {
          keys[runs] = key.key;
          firstK[runs] = CompactWord::storedK(key.k);
          if (key.k != IdKey::kWhole && key.k >= CompactWord::kWideMark) [[unlikely]]
            slice.wideK_.push_back({static_cast<uint32_t>(runs), key.k});
        }
        ++runs;
        runJ = 0;
      } else {
        ++runJ;
      }
      labels[at] = static_cast<uint8_t>(label);
      ++at;
    }
    // As CompactWord::Slice::appendFreshRun, with the labels also as packed bytes and as
    // bytes padded for a store of 16 (RewriteTable::bytes).
    void putFresh(const uint32_t* successors, uint64_t packed, const uint8_t* padded, uint32_t n, uint64_t key,
                  uint32_t index, double birth) {
      const size_t place = at % CompactWord::kBlock;
      // Most runs: sixteen labels or fewer (Koch's nine), inside the bitmap word under way
      // (not the first of the slice, which starts one), with room in the slice for a store
      // of eight or sixteen bytes (the bytes past n are written over next).
      if (n <= 16 && place != 0 && place + n <= CompactWord::kBlock && bitsWord != SIZE_MAX && at + 16 <= sliceEnd)
          [[likely]] {
        bits |= uint64_t{1} << place;
        keys[runs] = key;
        birthIndex[runs] = index;
        firstK[runs] = 1;
        ++runs;
        if (n <= 8)
          std::memcpy(labels + at, &packed, 8);
        else
          std::memcpy(labels + at, padded, 16);
        at += n;
        runJ = n - 1;
        return;
      }
      store();
      slice.appendFreshRun(successors, n, 0, key, birth);
      load();
    }

    // `count` labels from `source` (padded: 16 bytes may be read), the first starting a
    // run born at births[index] when `starts`, the others continuing it.
    void putWithoutIds(const uint8_t* source, uint32_t count, bool starts, uint32_t index) {
      if (at % CompactWord::kBlock == 0 || bitsWord == SIZE_MAX) [[unlikely]] {
        store();
        slice.startBlock(at);
        load();
      }
      if (starts) {  // a slice counted first has room for just its runs
        bits |= uint64_t{1} << (at % CompactWord::kBlock);
        birthIndex[runs++] = index;
      }
      if (count <= 16 && at + 16 <= sliceEnd) [[likely]] {
        std::memcpy(labels + at, source, 16);  // the bytes past count are written over next
      } else {
        std::memcpy(labels + at, source, count);
      }
      size_t blockEnd = (at / CompactWord::kBlock + 1) * CompactWord::kBlock;
      at += count;
      startBlocksBefore(blockEnd);
    }

    // Starts the blocks from `blockEnd` (the start of a block) on that begin before the
    // module at `at`, inside labels just written: their first module continues the run
    // under way. `blockEnd` is left at the next block to start.
    [[gnu::always_inline]] void startBlocksBefore(size_t& blockEnd) {
      if (blockEnd < at) [[unlikely]]
        startBlocks(blockEnd);
    }
    // Out of line: in the loops of a copy a module it made Thue-Morse's 17 % slower.
    [[gnu::noinline]] void startBlocks(size_t& blockEnd) {
      for (; blockEnd < at; blockEnd += CompactWord::kBlock) {
        runJ = 0;  // read only for words with ids
        const size_t w = blockEnd / CompactWord::kBlock;
        // Inside the slice, where the bitmap word under way is the slice's alone: as
        // Slice::startBlock, in line (out of line it took a fifth of Koch's walk).
        if (blockRuns && bitsWord + 1 == w && blockEnd - CompactWord::kBlock >= slice.firstModule_ &&
            blockEnd <= sliceEnd) [[likely]] {
          runStarts[bitsWord] = bits;
          blockRuns[w] = static_cast<uint32_t>(slice.firstRun_ + runs);
          blockJ[w] = 1;  // runJ + 1
          bitsWord = w;
          bits = 0;
          continue;
        }
        store();
        slice.startBlock(blockEnd);
        load();
      }
    }

    // Starts the blocks from `blockEnd` on that begin before the module at `at`, inside the
    // labels of one step just written from module `stepModule` and value `stepValue`: the
    // block index counts the values before each. Their first module continues the run
    // under way. `blockEnd` is left at the next block to start.
    [[gnu::noinline]] void startValueBlocks(size_t& blockEnd, size_t stepModule, size_t stepValue,
                                            const uint32_t* stateCounts) {
      const size_t valueAfter = valueAt;
      for (; blockEnd < at; blockEnd += CompactWord::kBlock) {
        size_t value = stepValue;
        for (size_t m = stepModule; m < blockEnd; ++m) value += stateCounts[labels[m]];
        runJ = 0;  // read only for words with ids
        valueAt = value;
        store();
        slice.startBlock(blockEnd);
        load();
      }
      valueAt = valueAfter;
    }

    CompactWord::Slice& slice;
    size_t at, sliceEnd, runs;
    uint32_t runJ;
    uint64_t bits;
    size_t bitsWord;
    uint8_t* labels;
    uint64_t* keys;
    uint32_t* birthIndex;
    uint16_t* firstK;
    // The word's values, and where the next module's go (walkValues).
    double* values;
    size_t valueAt;
    // The word's bitmap and block index, when writing a word without values.
    uint64_t* runStarts = nullptr;
    uint32_t* blockRuns = nullptr;
    uint16_t* blockJ = nullptr;
  };

  // The walk without ids: each module takes its step, kept or expiring, from the table
  // (what it writes, bears and adds to the earliest death), and a run starts where the
  // birth written changes. The old word is read run by run: a run's birth is read once.
  // Expiry is a branch, not a select: in Koch kept turns and expiring F alternate in a
  // pattern the predictor learns (a select made Koch 13 % slower, bench/README.md).
  //
  // The earliest death after the word is a minimum over its modules, each of (birth +
  // lifetime) + what its step adds: a chain of minima 4 cycles a module. With at most 64
  // steps (kFewSteps) the walk notes which steps a run of the old word took, and takes
  // the minimum over those once the run ends, with the same sums: the same result.
  template <bool kWriting, bool kFewSteps>
  static TableRewriteCounts walkWithoutIds(CompactWord::Slice& out, const CompactWord& from, size_t begin, size_t end,
                                           const RewriteTable& table, double horizon);

  // The loop of a step a module of walkValues, for modules of one run of the old word that
  // all take their step at one death: each module's labels copied with one store of 16
  // bytes, its values by its step's operations. Its state lives in locals (the walk's
  // would be reloaded around every store through a byte pointer).
  struct StepsWithValues {
    const uint8_t* labels;
    const uint32_t* runSteps;
    const RewriteTable::Step* steps;
    const uint8_t* bytes;
    const ValueOperation* operations;
    const uint32_t* stateCounts;
    const double* in;
    uint8_t* outLabels;
    double* outValues;
    struct State {
      size_t i, at, valueAt, value;
      uint64_t events, born, seen;  // seen: bit s, step s taken
      size_t stepModule = 0, stepValue = 0;
    };
    // Modules from state.i up to `end`, while what is written starts before `stop`, until a
    // step writes past `blockEnd` (the next block to start).
    [[gnu::noinline]] void run(State& state, size_t end, size_t stop, size_t blockEnd) const;
    // The modules from[0 ..] up to `room` of them while their label is `label`, each
    // holding one value x and writing the labels `writes` (count of them) and kWritten
    // values x * multiplier + addend. Returns how many.
    template <uint32_t kWritten>
    static size_t stretchOfOne(const uint8_t* from, size_t room, uint32_t label, const uint8_t* writes, uint32_t count,
                               const ValueOperation* operation, const double* own, uint8_t* labelsOut,
                               double* valuesOut);
    // After run() stopped past a block start: the module and value the last step wrote
    // from, found again from its label in the old word (module state.i - 1).
    void lastStep(State& state) const {
      const RewriteTable::Step& step = steps[runSteps[labels[state.i - 1]]];
      state.stepModule = state.at - step.count;
      state.stepValue = state.valueAt - step.operationCount;
    }
  };

  // The walk of a word with state values, with ids or without: module by module, each
  // taking its step from the table as walkWithoutIds does, and writing its values by the
  // step's operations on its own values (a kept or renewed module copies them). With ids,
  // runs follow RunTail's rule as in walk(); without, a run starts where the birth written
  // changes, timeless modules joining the run under way.
  template <bool kWriting, bool kWithIds, class Lineage>
  static TableRewriteCounts walkValues(CompactWord::Slice& out, const CompactWord& from, size_t begin, size_t end,
                                       const RewriteTable& table, double horizon,
                                       [[maybe_unused]] Lineage& lineage) {
    TableRewriteCounts counts;
    end = std::min(end, from.size());
    if (begin >= end) return counts;
    const uint8_t* labels = from.labels8_.data();
    const uint64_t* starts = from.runStarts_.data();
    const RewriteTable::Step* steps = table.steps.data();
    const double* lifetimes = table.lifetimes.data();
    const uint8_t* bytes = table.bytes.data();
    const uint32_t* stateCounts = table.stateCounts.data();
    const ValueOperation* operations = table.operations.data();
    const double* in = from.values_.data();

    const CompactWord::Place place = from.locate(begin);
    size_t run = place.run, value = place.value;
    // With ids only: the run's key, first k and the module's place j in it.
    [[maybe_unused]] uint32_t j = place.j;
    [[maybe_unused]] uint64_t key = 0, keyFirst = 0;
    [[maybe_unused]] uint32_t firstK = 0;
    [[maybe_unused]] bool keyFirstKnown = false;
    uint64_t birthBits = 0;
    uint32_t birthIndex = 0;
    double birth = 0;
    auto loadRun = [&] {
      if constexpr (kWithIds) {
        key = from.keys_[run];
        firstK = from.firstKOf(run);
        keyFirstKnown = false;
      }
      birthIndex = from.birthIndex_[run];
      birth = from.births_[birthIndex];
      birthBits = std::bit_cast<uint64_t>(birth);
    };
    loadRun();

    Writer<kWithIds> writer(out);
    constexpr uint64_t kNone = ~uint64_t{0};  // the bits of no birth (a NaN)
    // The last module written: its birth bits, and with ids its key and k (none after new
    // successors, which nothing continues).
    uint64_t tailBits = kNone;
    [[maybe_unused]] uint64_t tailKey = 0;
    [[maybe_unused]] uint32_t tailK = IdKey::kWhole;
    uint64_t deathBits = kNone;
    uint32_t deathIndex = 0;
    uint64_t modules = 0, runs = 0, values = 0;

    // Module i, of the run loaded.
    auto visit = [&](size_t i) {
      const uint32_t label = labels[i];
      const double death = birth + lifetimes[label];
      uint32_t taken = 2 * label;  // the step, kept; expiring is the next
      uint64_t bits = birthBits;
      [[maybe_unused]] uint32_t index = birthIndex;
      if (death <= horizon) {
        ++taken;
        bits = std::bit_cast<uint64_t>(death);
        if constexpr (kWriting) {
          if (bits != deathBits) [[unlikely]] {
            deathBits = bits;
            deathIndex = out.birthIndexOf(death);
          }
          index = deathIndex;
        }
      } else if constexpr (!kWithIds) {
        if (steps[taken].joins && tailBits != kNone) bits = tailBits;
      }
      const RewriteTable::Step& step = steps[taken];
      counts.events += step.event;
      counts.born += step.born;
      counts.soonest = std::min(counts.soonest, death + step.soonAfter);
      // Whether the first module written starts a run, and the ids of what is written.
      bool startsRun;
      [[maybe_unused]] uint64_t writtenKey = 0;
      [[maybe_unused]] uint32_t writtenK = 1;
      if constexpr (kWithIds) {
        const uint32_t k = firstK == IdKey::kWhole ? IdKey::kWhole : firstK + j;
        if (step.born == 0) {  // kept or renewed: its own id
          writtenKey = key;
          writtenK = k;
          startsRun = !(tailK != IdKey::kWhole && k != IdKey::kWhole && key == tailKey && k == tailK + 1 &&
                        (k & 0xFFFFu) != 0 && bits == tailBits);
          tailKey = key;
          tailK = k;
        } else {  // new successors, one run of fresh ids
          startsRun = true;
          if constexpr (kWriting) {
            writtenKey = lineage(parentFirstOf(key, k, keyFirst, keyFirstKnown), death);
          }
          tailK = IdKey::kWhole;
        }
      } else {
        startsRun = bits != tailBits;
      }
      tailBits = bits;
      if constexpr (kWriting) {
        const double* own = in + value;
        const ValueOperation* operation = operations + step.firstOperation;
        for (uint32_t s = 0; s < step.count; ++s) {
          const uint32_t written = bytes[step.source + s];
          writer.put(written, IdKey{writtenKey, step.born == 0 ? writtenK : s + 1}, !(s == 0 && startsRun), index);
          double* to = writer.values + writer.valueAt;
          for (uint32_t v = 0, n = stateCounts[written]; v < n; ++v) to[v] = operation[v].applyQuickly(own);
          operation += stateCounts[written];
          writer.valueAt += stateCounts[written];
        }
      } else {
        modules += step.count;
        runs += startsRun ? 1 : 0;
        values += step.operationCount;
      }
      value += stateCounts[label];
    };

    for (size_t i = begin;;) {
      // Without ids, a run of the old word whose modules that can expire all expire at one
      // death (RewriteTable::oneLifetime) continues the run of that death once a module
      // has started it: after that module, the rest goes by a loop of a step a module,
      // its labels copied with one store and its values by its operations.
      if constexpr (kWriting && !kWithIds) {
        if (table.oneLifetime && table.steps.size() <= 64 && birth + table.runLifetime <= horizon) {
          const size_t runEnd = nextRunStart(starts, i, end);
          const double death = birth + table.runLifetime;
          const uint64_t runDeathBits = std::bit_cast<uint64_t>(death);
          while (i < runEnd && tailBits != runDeathBits) visit(i++);
          // The first block that starts after what is written; one starting just there has
          // not been started yet (put starts a block before its first module).
          size_t blockEnd = (writer.at + CompactWord::kBlock - 1) / CompactWord::kBlock * CompactWord::kBlock;
          StepsWithValues loop{labels, table.runSteps.data(), steps, bytes, operations, stateCounts, in,
                               writer.labels, writer.values};
          StepsWithValues::State state{i, writer.at, writer.valueAt, value, 0, 0, 0};
          // A step is written while 16 bytes fit in the slice (a slice smaller than that
          // takes the walk module by module).
          const size_t stop = writer.sliceEnd - RewriteTable::kBytesPadding;
          for (; writer.sliceEnd >= RewriteTable::kBytesPadding;) {
            loop.run(state, runEnd, stop, blockEnd);
            writer.at = state.at;
            writer.valueAt = state.valueAt;
            if (!(blockEnd < state.at)) break;
            // The last step crossed into a block, whose values start inside the step's.
            loop.lastStep(state);
            writer.startValueBlocks(blockEnd, state.stepModule, state.stepValue, stateCounts);
          }
          i = state.i;
          value = state.value;
          counts.events += state.events;
          counts.born += state.born;
          for (uint64_t seen = state.seen; seen != 0; seen &= seen - 1) {
            const size_t taken = static_cast<size_t>(std::countr_zero(seen));
            counts.soonest = std::min(counts.soonest, death + steps[taken].soonAfter);
          }
          while (i < runEnd) visit(i++);
          if (i == end) break;
          ++run;  // i starts a run
          loadRun();
          continue;
        }
      }
      visit(i);
      if (++i == end) break;
      if ((starts[i / CompactWord::kBlock] >> (i % CompactWord::kBlock)) & 1u) {
        ++run;
        j = 0;
        loadRun();
      } else {
        ++j;
      }
    }
    if constexpr (kWriting) {
      writer.store();
    } else {
      out.modules_ += modules;
      out.countedRuns_ += runs;
      out.values_ += values;
    }
    return counts;
  }

  template <bool kWriting, class Lineage>
  static TableRewriteCounts walk(CompactWord::Slice& out, const CompactWord& from, size_t begin, size_t end,
                                 const RewriteTable& table, double horizon, Lineage& lineage) {
    TableRewriteCounts counts;
    end = std::min(end, from.size());
    if (begin >= end) return counts;
    const uint8_t* labels = from.labels8_.data();
    const uint64_t* starts = from.runStarts_.data();
    const RewriteTable::Entry* entries = table.entries.data();
    const uint32_t* successors = table.labels.data();
    const uint8_t* padded = table.bytes.data();  // the successors' labels as bytes, padded

    // The run of the module under way.
    const CompactWord::Place place = from.locate(begin);
    size_t run = place.run;
    uint32_t j = place.j;
    uint64_t key = 0, keyFirst = 0;
    uint32_t firstK = 0, birthIndex = 0;
    double birth = 0;
    bool keyFirstKnown = false;
    auto loadRun = [&] {
      key = from.keys_[run];
      firstK = from.firstKOf(run);
      birthIndex = from.birthIndex_[run];
      birth = from.births_[birthIndex];
      keyFirstKnown = false;
    };
    loadRun();

    Writer<true> writer(out);
    size_t modules = 0, runs = 0;  // counted
    // The last module written, for RunTail's rule: its key, k and birth bits; none after
    // new successors, which nothing continues. The rule is written out here rather than
    // asked of a RunTail, which also keeps whether the last module was new and which
    // event made it: that made Koch and Thue-Morse 5 % slower.
    bool tail = false;
    uint64_t tailKey = 0, tailBirth = 0;
    uint32_t tailK = 0;
    auto keep = [&](uint32_t label, uint32_t k, double bornAt, uint32_t index) {
      const uint64_t bits = std::bit_cast<uint64_t>(bornAt);
      const bool continues = tail && key == tailKey && k != IdKey::kWhole && tailK != IdKey::kWhole && k == tailK + 1 &&
                             (k & 0xFFFFu) != 0 && bits == tailBirth;
      tail = true;
      tailKey = key;
      tailK = k;
      tailBirth = bits;
      if constexpr (kWriting) {
        writer.put(label, IdKey{key, k}, continues, index);
      } else {
        ++modules;
        runs += continues ? 0 : 1;
      }
    };
    // The last death of new successors, and its index in the slice's births.
    bool deathKnown = false;
    uint64_t lastDeath = 0;
    uint32_t deathIndex = 0;
    auto deathIndexOf = [&](double death) {
      const uint64_t bits = std::bit_cast<uint64_t>(death);
      if (!deathKnown || bits != lastDeath) {
        deathKnown = true;
        lastDeath = bits;
        deathIndex = out.birthIndexOf(death);
      }
      return deathIndex;
    };

    for (size_t i = begin;;) {
      const uint32_t label = labels[i];
      const RewriteTable::Entry& entry = entries[label];
      const double death = birth + entry.lifetime;
      const uint32_t k = firstK == IdKey::kWhole ? IdKey::kWhole : firstK + j;
      if (death > horizon) {
        keep(label, k, birth, birthIndex);
        counts.soonest = std::min(counts.soonest, death);
      } else {
        ++counts.events;
        counts.soonest = std::min(counts.soonest, death + entry.lifeAfter);
        if (entry.renews) {
          keep(label, k, death, kWriting ? deathIndexOf(death) : 0);
        } else {
          counts.born += entry.count;
          tail = false;
          if constexpr (kWriting) {
            writer.putFresh(successors + entry.first, entry.packed, padded + entry.first, entry.count,
                            lineage(parentFirstOf(key, k, keyFirst, keyFirstKnown), death), deathIndexOf(death), death);
          } else {
            modules += entry.count;
            ++runs;
          }
        }
      }
      if (++i == end) break;
      if ((starts[i / CompactWord::kBlock] >> (i % CompactWord::kBlock)) & 1u) {
        ++run;
        j = 0;
        loadRun();
      } else {
        ++j;
      }
    }
    if constexpr (kWriting) {
      writer.store();
    } else {
      out.modules_ += modules;
      out.countedRuns_ += runs;
    }
    return counts;
  }
};

}  // namespace ontogen
