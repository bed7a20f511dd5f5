#pragma once
// A linear word in a few bytes a module (docs/COMPACT_WORDS.md, section 4). Instead of a
// 24-byte record per module, the word keeps:
//  - a label stream: one byte per module, two when there are more than 256 labels;
//  - runs: stretches of consecutive modules born in one event. A run holds its lineage
//    key, its birth (an index into a table of distinct birth times) and the successor
//    number k of its first module, in two bytes (a k from 65534 on in a table of wide k
//    beside the runs); the j-th module of the run has the id mixKey(key, firstK + j),
//    exactly the id core/successors.h gives it;
//  - a run-start bitmap, one bit a module, and a block index (runs and state values
//    before each block of 64 modules, and the place in its run of the block's first
//    module), so module i is found in constant time;
//  - the state values in word order, without a per-module offset.
// Koch's word takes 4.02 bytes a module this way, Thue-Morse's 8.22.
//
// A writer appends modules in word order; it extends the last run when the module has
// the same key and birth and the next k, unless that k is a multiple of 65536, and starts
// a run otherwise, so the encoding of a word written serially is canonical, and a run
// holds at most 65536 modules (its place j fits in two bytes). An id that cannot be
// written as (key, k) is kept whole in a run of its own.
//
// What runs once a module stays inline here (an append, a slice's put, a cursor's step,
// the run tail): a call there cost a fifth of a rewrite. The rest is in compact_word.cpp.

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <utility>
#include <vector>

#include "pools/cell_view.h"
#include "pools/large_page_allocator.h"
#include "pools/mix_key.h"

namespace ontogen {

/// Where a module's id comes from: mixKey(key, k), or `key` itself when k is kWhole.
struct IdKey {
  static constexpr uint32_t kWhole = UINT32_MAX;
  uint64_t key = 0;
  uint32_t k = kWhole;

  /// An id kept as it is (a module whose id is not the k-th of a lineage key).
  static constexpr IdKey whole(uint64_t id) { return {id, kWhole}; }
  constexpr uint64_t id() const { return k == kWhole ? key : mixKey(key, k); }
};

class CompactWordCursor;
class LabelCursor;
class TableRewrite;

/// The canonical rule every writer and counter of a compact word applies: a module
/// continues the run of the module before it when both have (key, k) ids with the same
/// key and the next k, that k is not a multiple of 65536, and the births have the same
/// bits.
///
/// A writer by slices names the new successors of an event by the event instead of by
/// their lineage key (continuesFresh), so that it can count its runs before it computes
/// any key: an event's successors continue each other, and never a module of another
/// event or a kept key. The words read the same; the encoding differs from the canonical
/// one only where a new lineage key equals the key of the module before it, one chance in
/// 2^64 a module.
class RunTail {
 public:
  /// Whether the module continues the last module's run; it becomes the last module.
  bool continues(IdKey key, double birth) { return continuesAs(key.key, false, key.k, birth); }
  /// The same for the k-th new successor (k below kWhole) of the event named `event`.
  bool continuesFresh(uint64_t event, uint32_t k, double birth) { return continuesAs(event, true, k, birth); }
  /// The tail after the successors 1 .. n of the event named `event` went by one by one
  /// with continuesFresh: the first started a run (no module before has k = 0 and the
  /// event's name), the others continued it.
  void endFresh(uint64_t event, uint32_t n, double birth) {
    any_ = true;
    last_ = event;
    lastFresh_ = true;
    lastK_ = n;
    lastBirth_ = std::bit_cast<uint64_t>(birth);
  }

 private:
  bool continuesAs(uint64_t identity, bool fresh, uint32_t k, double birth) {
    const uint64_t bits = std::bit_cast<uint64_t>(birth);
    const bool continues = any_ && k != IdKey::kWhole && lastK_ != IdKey::kWhole && identity == last_ &&
                           fresh == lastFresh_ && k == lastK_ + 1 && (k & 0xFFFFu) != 0 && bits == lastBirth_;
    any_ = true;
    last_ = identity;
    lastFresh_ = fresh;
    lastK_ = k;
    lastBirth_ = bits;
    return continues;
  }

  bool any_ = false;
  bool lastFresh_ = false;
  uint64_t last_ = 0;
  uint32_t lastK_ = IdKey::kWhole;
  uint64_t lastBirth_ = 0;
};

class CompactWord {
 public:
  /// The most modules appendRun and appendFreshRun write at once. A run's first k takes
  /// two bytes up to 65533 (65534 marks a k in the table of wide k, 65535 a run whose one
  /// id is kept whole). Two bytes rather than one keep the ids of an axiom (its module i
  /// has k = i) in runs of 65536 with few entries in the wide table, and so its renewed
  /// modules: a signal along 100,000 modules takes 2 runs. Koch pays 1 byte a run, 0.2 a
  /// module.
  static constexpr uint32_t kLargestRunK = 65534;
  /// Modules per block of the index: one 64-bit word of the run-start bitmap.
  static constexpr size_t kBlock = 64;

  /// A word whose labels are 0 .. stateCounts.size() - 1; module with label m has
  /// stateCounts[m] state values. More than 256 labels take two bytes a module.
  explicit CompactWord(std::vector<uint32_t> stateCounts = {});

  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  size_t runCount() const { return birthIndex_.size(); }
  size_t birthCount() const { return births_.size(); }
  size_t valueCount() const { return values_.size(); }
  bool wideLabels() const { return wide_; }
  /// Whether the runs hold the modules' ids. A word rewritten by a table may be written
  /// without them (docs/COMPACT_WORDS.md, "Words without ids"): its runs then split only
  /// where the birth changes, their keys and first k mean nothing, and reading an id
  /// (cursor, cellAt, keyOf) is an internal error; labels, births and locate's run stay
  /// exact. The word's owner makes the ids again when they are read (pools/id_replay.h).
  bool holdsIds() const { return !withoutIds_; }
  /// Says the word is written without ids (until the next clear): after beginSlices or
  /// beginWholeSlice, before the slices end. Its runs then keep no key or first k.
  void markWithoutIds() { withoutIds_ = true; }
  /// Bytes the word's arrays take (their sizes, not their capacities: pages never
  /// written are never mapped).
  size_t bytes() const;
  /// Bytes the word's arrays have written and keep: bytes(), or more where the word was
  /// cleared after a larger one, whose pages it keeps (the memory limit counts them:
  /// LinearDevelopment::heldBytes). Room reserved and never written is not counted.
  size_t heldBytes() const { return std::max(bytes(), largestBytes_); }

  // --- Writing, in word order ---

  /// Empties the word; keeps the arrays' storage and the birth table.
  void clear();
  /// Empties the word and gives it `other`'s birth table, so a module copied from `other`
  /// keeps its birth index (the writer of the next word from this one).
  void clearWithBirthsOf(const CompactWord& other);
  /// Room for this many modules, runs and values without reallocation.
  void reserve(size_t modules, size_t runs, size_t values);
  /// The index of `birth` in the table: one of the last few entries when its bits match,
  /// else a new entry.
  uint32_t birthIndexOf(double birth) {
    if (!births_.empty() && std::bit_cast<uint64_t>(births_.back()) == std::bit_cast<uint64_t>(birth)) [[likely]]
      return static_cast<uint32_t>(births_.size() - 1);
    return addBirth(birth);
  }
  /// Appends a module with label `label` (below the label count), id `key`, birth
  /// births()[birthIndex], and the label's state count of values from `values` (null:
  /// the caller writes them later, at values()[valueCount() before the append]).
  /// Inline: a single-pass rewrite calls it for every module.
  void append(uint32_t label, IdKey key, uint32_t birthIndex, const double* values) {
    const uint32_t count = stateless_ ? 0 : stateCounts_[label];
    const size_t i = size_;
    if (i % kBlock == 0) [[unlikely]]
      startBlock();
    if (!tail_.continues(key, births_[birthIndex])) {
      runStarts_.back() |= uint64_t{1} << (i % kBlock);
      keys_.push_back(key.key);
      birthIndex_.push_back(birthIndex);
      firstK_.push_back(storedK(key.k));
      if (key.k != IdKey::kWhole && key.k >= kWideMark) [[unlikely]]
        addWideK(keys_.size() - 1, key.k);
      runJ_ = 0;
    } else {
      ++runJ_;
    }
    if (wide_)
      labels16_.push_back(static_cast<uint16_t>(label));
    else
      labels8_.push_back(static_cast<uint8_t>(label));
    if (count > 0) appendValues(count, values);
    ++size_;
  }
  void append(uint32_t label, IdKey key, double birth, const double* values) {
    append(label, key, birthIndexOf(birth), values);
  }
  /// Modules with ids (lineage, 1) .. (lineage, n), labels `labels`, n from 1 to
  /// kLargestRunK, born at births()[birthIndex]: as n appends with null values (written
  /// later, from valueCount() before the call on), the later n - 1 continuing the first's
  /// run by the canonical rule without asking it.
  void appendRun(const uint32_t* labels, uint32_t n, uint64_t lineage, uint32_t birthIndex) {
    append(labels[0], IdKey{lineage, 1}, birthIndex, nullptr);
    size_t values = 0;  // of the modules appended since the values last grew
    for (uint32_t k = 2; k <= n; ++k) {
      if (size_ % kBlock == 0) [[unlikely]] {
        growValues(values);  // the block index counts the values before the block
        values = 0;
        startBlock();
      }
      ++runJ_;
      if (wide_)
        labels16_.push_back(static_cast<uint16_t>(labels[k - 1]));
      else
        labels8_.push_back(static_cast<uint8_t>(labels[k - 1]));
      if (!stateless_) values += stateCounts_[labels[k - 1]];
      ++size_;
    }
    growValues(values);
    tail_.continues(IdKey{lineage, n}, births_[birthIndex]);  // the last module becomes the tail
  }
  /// Modules first .. first + n - 1 of `from`, which lie in one run there, with their
  /// labels and ids (key.key, key.k + j), born at births()[birthIndex]: as n appends, the
  /// later n - 1 continuing the first's run without asking, which they do (kept or renewed
  /// together, their k follow one another and none is a multiple of 65,536). For words
  /// without state values: a stretch of a word of labels alone.
  void appendStretch(const CompactWord& from, size_t first, uint32_t n, IdKey key, uint32_t birthIndex);
  /// After the last append: renumbers the birth table in order of first use, dropping
  /// entries no run uses and duplicates, once it holds more than max(64, 2 x runs).
  void finish();

  /// Appends the modules of `part`, a word without state values written serially from
  /// a clearWithBirthsOf of a word whose first `sharedBirths` births this word shares
  /// (the word both copy from): labels and runs copied, the bitmap shifted into place,
  /// the block index made for the blocks it starts, the part's own births added to the
  /// table. The part's first module starts a run, as at a seam between slices. Not
  /// finished: call finish() after the last part.
  void appendWord(const CompactWord& part, size_t sharedBirths);
  /// appendWord for several parts at once, each copied on a thread of its own:
  /// placeParts (one thread) sizes the word for all of them and says where each goes,
  /// copyPart (any thread, each part once) copies one, endParts (one thread) joins the
  /// bitmap words parts share and takes the last part's tail. A part copied by the thread
  /// that wrote it, and that will read it at the next rewrite, stays in that core's cache.
  struct PartPlace {
    const CompactWord* part = nullptr;
    size_t firstModule = 0, firstRun = 0;
    std::vector<uint32_t> births;                          // the part's own births here
    std::vector<std::pair<size_t, uint64_t>> sharedWords;  // bitmap words it shares
  };
  void placeParts(std::span<PartPlace> places, size_t sharedBirths);
  void copyPart(PartPlace& place, size_t sharedBirths);
  void endParts(std::span<PartPlace> places);

  // --- Writing by slices (each thread a slice of the word, as core/parallel_rewrite.h
  // writes the next word): every slice counts, then beginSlices sizes the word and places
  // the slices by prefix sums, each slice writes in place, and endSlices joins the seams.

  class Slice;
  /// Sizes the word's labels, runs and values for `slices`, which have counted, and places
  /// them one after the other. The word was cleared with the births of the word the slices
  /// copy from (clearWithBirthsOf).
  void beginSlices(std::span<Slice> slices);
  /// After every slice has written: appends the slices' new births to the table in slice
  /// order, renumbers the runs that refer to them, and joins the run-start bits of the
  /// bitmap words two slices share. Then finish() as after serial appends.
  void endSlices(std::span<Slice> slices);
  /// endSlices in two parts, for a caller that renumbers on several threads: joinSlices
  /// (one thread), then Slice::place for every slice (any thread each).
  void joinSlices(std::span<Slice> slices);
  /// Before joinSlices, for slices placed by bounds that wrote their modules but fewer
  /// runs than they were given (a word written without ids, whose runs split only where
  /// the birth changes; a word whose modules each write one, given a run a module): moves
  /// each slice's runs after the last one's, corrects the block index, and cuts the runs
  /// to those written. One thread; it moves runs, not modules.
  void closeRunGaps(std::span<Slice> slices);
  /// One slice that writes the whole word without counting it first: beginWholeSlice
  /// sizes the word for at most `modules` modules, `runs` runs and `values` state values,
  /// the slice writes, and endWholeSlice cuts the word to what the slice wrote and ends it
  /// as endSlices does. Pages past what is written are never touched.
  void beginWholeSlice(Slice& slice, size_t modules, size_t runs, size_t values = 0);
  void endWholeSlice(Slice& slice);

  // --- Reading ---

  uint32_t label(size_t i) const { return wide_ ? labels16_[i] : labels8_[i]; }
  /// The label stream itself: one of the two is empty, as wideLabels() says.
  std::span<const uint8_t> labels8() const { return labels8_; }
  std::span<const uint16_t> labels16() const { return labels16_; }
  std::span<const double> births() const { return births_; }
  std::span<const double> values() const { return values_; }
  std::span<double> values() { return values_; }
  uint32_t stateCount(uint32_t label) const { return stateCounts_[label]; }
  const std::vector<uint32_t>& stateCounts() const { return stateCounts_; }

  /// Where module i sits: its run, its place j in the run and its first state value.
  struct Place {
    size_t run = 0;
    uint32_t j = 0;
    size_t value = 0;
  };
  /// Module i (below size()) in constant time: a popcount, the block's place in its run
  /// when no run starts in the block up to i, at most 63 state counts for the value offset.
  Place locate(size_t i) const;

  IdKey keyOf(size_t run, uint32_t j) const {
    if (withoutIds_) [[unlikely]]
      noIds();
    const uint32_t first = firstKOf(run);
    return first == IdKey::kWhole ? IdKey::whole(keys_[run]) : IdKey{keys_[run], first + j};
  }
  /// The k of the run's first module, or IdKey::kWhole for a run whose one id is whole.
  uint32_t firstKOf(size_t run) const {
    const uint16_t first = firstK_[run];
    if (first < kWideMark) [[likely]]
      return first;
    return first == kWholeMark ? IdKey::kWhole : wideK(run);
  }
  /// Runs whose first k is in the table of wide k.
  size_t wideKCount() const { return wideK_.size(); }
  uint32_t birthIndex(size_t run) const { return birthIndex_[run]; }
  double birthOf(size_t run) const { return births_[birthIndex_[run]]; }

  /// Whether the block index agrees with the run-start bitmap and the labels: each
  /// block's count of runs and values before it, and the runs and values held. For tests:
  /// it reads the whole word.
  bool indexAgrees() const;
  /// Module i as readers see it (pools/cell_cursor.h).
  CellView cellAt(size_t i) const;
  /// A cursor at the first module.
  CompactWordCursor cursor() const;

 private:
  friend class CompactWordCursor;
  friend class LabelCursor;
  friend class TableRewrite;
  static constexpr uint16_t kWholeMark = 0xFFFF;
  static constexpr uint16_t kWideMark = 0xFFFE;
  // A run whose first k takes more than two bytes (from kWideMark on), in run order.
  struct WideK {
    uint32_t run;
    uint32_t k;
  };
  static constexpr uint16_t storedK(uint32_t k) {
    return k == IdKey::kWhole ? kWholeMark : k >= kWideMark ? kWideMark : static_cast<uint16_t>(k);
  }
  void addWideK(size_t run, uint32_t k);
  /// The first k of a run marked kWideMark: a binary search of the table.
  uint32_t wideK(size_t run) const;

  bool startsRun(size_t i) const { return (runStarts_[i / kBlock] >> (i % kBlock)) & 1u; }
  /// Where the next new birth of a writer goes: one of the last few of `births` whose bits
  /// match, or a new entry.
  static size_t birthIndexIn(std::vector<double>& births, double birth);
  uint32_t addBirth(double birth);
  /// Sizes the arrays for `modules`, `runs` and `values`, what is already there kept and
  /// the rest left unwritten, for writers that fill them in place (slices, parts).
  void resizeForWriters(size_t modules, size_t runs, size_t values);
  /// A new block of the index at the next module; checks the 32-bit limits of the block
  /// index, once a block.
  void startBlock();
  [[noreturn]] static void tooManyValues();
  /// `count` values from `values`, or left to be written later (null). Out of line: words
  /// of labels alone never call it, and their appends stay small.
  void appendValues(uint32_t count, const double* values);
  /// `count` more values, written later.
  void growValues(size_t count) {
    if (count == 0) return;
    if (values_.size() + count > UINT32_MAX) [[unlikely]]
      tooManyValues();
    resizeForOverwrite(values_, values_.size() + count);
  }

  std::vector<uint32_t> stateCounts_;
  bool wide_ = false;
  bool stateless_ = true;  // no label has state: the block index keeps no value offsets
  size_t size_ = 0;
  LargeVector<uint8_t> labels8_;
  LargeVector<uint16_t> labels16_;
  LargeVector<uint64_t> runStarts_;    // bit i % 64 of word i / 64: module i starts a run
  LargeVector<uint32_t> blockRuns_;    // runs started before each block
  LargeVector<uint32_t> blockValues_;  // state values before each block (empty if stateless_)
  LargeVector<uint16_t> blockJ_;       // the place in its run of each block's first module
  LargeVector<uint64_t> keys_;         // per run: lineage key, or the whole id
  LargeVector<uint32_t> birthIndex_;   // per run: index into births_
  LargeVector<uint16_t> firstK_;       // per run: k of its first module, kWideMark or kWholeMark
  std::vector<WideK> wideK_;           // the first k of the runs marked kWideMark
  std::vector<double> births_;         // distinct birth times, exact
  LargeVector<double> values_;
  RunTail tail_;              // the last module appended serially
  uint32_t runJ_ = 0;         // its place in its run
  size_t writtenBlocks_ = 0;  // bitmap words written before placeParts
  bool withoutIds_ = false;   // markWithoutIds: the runs' keys and first k mean nothing
  size_t largestBytes_ = 0;   // the largest bytes() the word had when cleared
  [[noreturn]] static void noIds();
};

/// One slice of a word written by slices. Before CompactWord::beginSlices the slice
/// counts: append, appendCopy and appendBorn count modules, runs and values and write
/// nothing, and appendBorn needs no lineage key, so counting hashes nothing. After it the
/// same calls write labels, run starts, runs and values in place in the word, and new
/// births into the slice's own table, which CompactWord::endSlices appends to the word's
/// once every slice has written. The slice's first module always starts a run: a word
/// written by slices may have one run more a seam than the same word written serially,
/// and reads the same, module for module.
// On cache lines of its own: slices side by side in an array are written module by module
// by different threads (without it, two threads took longer on the signal than one).
class alignas(64) CompactWord::Slice {
 public:
  /// A slice of the word that starts with the birth table of `from`, the word it copies
  /// modules from (their birth indices stay valid).
  explicit Slice(const CompactWord& from);
  /// Starts the slice again, counting, for a word copying from `from`.
  void restart(const CompactWord& from);
  /// Whether the slice writes (after beginSlices) rather than counts.
  bool writing() const { return word_ != nullptr; }
  /// A module with id `key`, born at `birth` (a birth the slice may have to add to the table).
  [[gnu::always_inline]] void append(uint32_t label, IdKey key, double birth, const double* values) {
    const bool continues = tail_.continues(key, birth);
    if (!word_) return count(label, continues);
    put(label, key, continues, newBirth(birth), values);
  }
  /// A module copied from `from` with its birth index there.
  [[gnu::always_inline]] void appendCopy(uint32_t label, IdKey key, uint32_t birthIndex, const double* values) {
    const bool continues = tail_.continues(key, from_->births_[birthIndex]);
    if (!word_) return count(label, continues);
    put(label, key, continues, birthIndex, values);
  }
  /// The k-th new successor (k from 1) of an event, whose id is mixKey(lineage, k).
  /// `event` names the event among the slice's (a counter will do), so that the slice
  /// counts without the lineage key: pass any while counting.
  [[gnu::always_inline]] void appendBorn(uint32_t label, uint64_t event, uint64_t lineage, uint32_t k, double birth,
                                         const double* values) {
    const bool continues = tail_.continuesFresh(event, k, birth);
    if (!word_) return count(label, continues);
    put(label, IdKey{lineage, k}, continues, newBirth(birth), values);
  }
  /// The new successors 1 .. n of an event, none keeping an id, n at most kLargestRunK:
  /// as n calls of appendBorn with null values (written later, from nextValue() before
  /// the call on), in one run written at once.
  [[gnu::always_inline]] void appendFreshRun(const uint32_t* labels, uint32_t n, uint64_t event, uint64_t lineage,
                                             double birth) {
    tail_.endFresh(event, n, birth);
    if (!word_) {
      modules_ += n;
      ++countedRuns_;
      if (!stateless_) [[unlikely]]
        for (uint32_t j = 0; j < n; ++j) values_ += stateCounts_[labels[j]];
      return;
    }
    const size_t i = firstModule_ + written_;
    if (i % kBlock == 0 || bitsWord_ == SIZE_MAX) [[unlikely]]
      startBlock(i);
    bits_ |= uint64_t{1} << (i % kBlock);
    out_.keys[runs_] = lineage;
    out_.birthIndex[runs_] = birthIndexOf(birth);
    out_.firstK[runs_] = 1;
    ++runs_;
    if (i % kBlock + n <= kBlock && out_.labels8) [[likely]] {
      uint8_t* to = out_.labels8 + i;
      for (uint32_t j = 0; j < n; ++j) to[j] = static_cast<uint8_t>(labels[j]);
      if (!stateless_) [[unlikely]]
        for (uint32_t j = 0; j < n; ++j) writtenValues_ += stateCounts_[labels[j]];
    } else {
      for (uint32_t j = 0; j < n; ++j) {
        if (j > 0 && (i + j) % kBlock == 0) {
          runJ_ = j - 1;  // the module before: startBlock gives the block's j as one more
          startBlock(i + j);
        }
        if (out_.labels8)
          out_.labels8[i + j] = static_cast<uint8_t>(labels[j]);
        else
          out_.labels16[i + j] = static_cast<uint16_t>(labels[j]);
        if (!stateless_) writtenValues_ += stateCounts_[labels[j]];  // before the next block starts
      }
    }
    written_ += n;
    runJ_ = n - 1;
  }
  /// Modules first .. first + n - 1 of the word the slice copies from, which lie in one
  /// run there, kept with their ids (the first's is `key`) and birth index: as n calls of
  /// appendCopy (CompactWord::appendStretch says why the later ones continue the first).
  void appendKept(size_t first, uint32_t n, IdKey key, uint32_t birthIndex);
  /// The same modules renewed, born again at `birth`: as n calls of append.
  void appendRenewed(size_t first, uint32_t n, IdKey key, double birth);
  /// After the slice's last append of a pass.
  void finish();
  size_t modules() const { return modules_; }
  /// Modules written so far (while writing).
  size_t written() const { return written_; }
  /// Takes these figures as counted, without counting (no state values): a writer that
  /// knows them, or bounds them and checks wroteAsAssumed() before finish().
  void assume(size_t modules, size_t runs, size_t values = 0) {
    modules_ = modules;
    countedRuns_ = runs;
    values_ = values;
  }
  /// After writing: whether the slice wrote just the modules, runs and values it was given.
  bool wroteAsAssumed() const {
    return written_ == modules_ && runs_ == countedRuns_ && writtenValues_ == values_;
  }
  /// The same for a slice of a word written without ids, whose bound on its runs need not
  /// be met: CompactWord::closeRunGaps closes the gaps. Then keepRunsWritten before finish.
  bool wroteModulesAsAssumed() const {
    return written_ == modules_ && runs_ <= countedRuns_ && writtenValues_ == values_;
  }
  void keepRunsWritten() { countedRuns_ = runs_; }
  /// Once writing: `birth` is already births()[index] of the word written, so a writer
  /// that asks birthIndexOf (TableRewrite) takes that index instead of adding it to the
  /// slice's own births, which place() would then renumber.
  void knowBirth(double birth, uint32_t index) {
    knowsBirth_ = true;
    knownBirth_ = std::bit_cast<uint64_t>(birth);
    knownIndex_ = index;
  }
  /// The index a module born at `birth` takes: a known birth's, or a new birth's.
  uint32_t birthIndexOf(double birth) {
    if (knowsBirth_ && std::bit_cast<uint64_t>(birth) == knownBirth_) return knownIndex_;
    return newBirth(birth);
  }
  size_t values() const { return values_; }
  /// While writing: where the next module's first value goes in the word's values, and
  /// those values, for a writer that appends a module without its values (null) and
  /// writes them later.
  size_t nextValue() const { return firstValue_ + writtenValues_; }
  double* wordValues() const { return out_.values; }
  /// Runs written (after the writing pass).
  size_t runs() const { return runs_; }
  /// After CompactWord::joinSlices: gives the slice's runs born at its new births their
  /// index in the word's table. Slices place in any order, on any threads.
  void place();
  /// Bytes the slice keeps from one pass to the next, by capacity: its own births, wide k
  /// and shared bitmap words.
  size_t heldBytes() const;

 private:
  friend class CompactWord;
  friend class TableRewrite;
  // Marks a birth index as one of the slice's new births, renumbered by place.
  static constexpr uint32_t kNewBirth = uint32_t{1} << 31;
  void count(uint32_t label, bool continues) {
    ++modules_;
    if (!stateless_) values_ += stateCounts_[label];
    countedRuns_ += continues ? 0 : 1;
  }
  uint32_t newBirth(double birth) {
    if (births_.empty() || std::bit_cast<uint64_t>(births_.back()) != std::bit_cast<uint64_t>(birth)) [[unlikely]]
      lastBorn_ = static_cast<uint32_t>(birthIndexIn(births_, birth));
    return kNewBirth | lastBorn_;
  }
  // Inlined into every append: a call per module costs a fifth of a rewrite.
  [[gnu::always_inline]] void put(uint32_t label, IdKey key, bool continues, uint32_t birthIndex,
                                  const double* values) {
    const size_t i = firstModule_ + written_;
    if (i % kBlock == 0 || bitsWord_ == SIZE_MAX) [[unlikely]]
      startBlock(i);
    if (!continues) {
      bits_ |= uint64_t{1} << (i % kBlock);
      // The word holds the runs the slice counted (beginSlices): no capacity to check.
      out_.keys[runs_] = key.key;
      out_.birthIndex[runs_] = birthIndex;
      out_.firstK[runs_] = storedK(key.k);
      if (key.k != IdKey::kWhole && key.k >= kWideMark) [[unlikely]]
        wideK_.push_back({static_cast<uint32_t>(runs_), key.k});
      ++runs_;
      runJ_ = 0;
    } else {
      ++runJ_;
    }
    if (out_.labels8)
      out_.labels8[i] = static_cast<uint8_t>(label);
    else
      out_.labels16[i] = static_cast<uint16_t>(label);
    ++written_;
    if (stateless_) return;
    const uint32_t count = stateCounts_[label];
    double* to = out_.values + firstValue_ + writtenValues_;
    if (values)  // null: written later, at nextValue() before the append
      for (uint32_t v = 0; v < count; ++v) to[v] = values[v];
    writtenValues_ += count;
  }
  // appendKept and appendRenewed once the first module's run is known. Words without
  // state values only.
  void stretch(size_t first, uint32_t n, IdKey key, bool continues, uint32_t birthIndex);
  /// At module i: the block index entry of a block starting there, and a new bitmap word.
  void startBlock(size_t i);
  void flushBits();

  const CompactWord* from_;
  const uint32_t* stateCounts_;  // from_'s, and whether none has values
  bool stateless_;
  CompactWord* word_ = nullptr;                        // null while counting
  size_t modules_ = 0, values_ = 0, countedRuns_ = 0;  // counted
  size_t written_ = 0, writtenValues_ = 0, runs_ = 0;  // written
  uint32_t runJ_ = 0;                                  // the last module's place in its run
  RunTail tail_;
  std::vector<double> births_;  // new births, in order of first use
  std::vector<WideK> wideK_;    // the slice's runs of wide k, numbered from its first run
  uint32_t lastBorn_ = 0;       // index in births_ of the last new birth appended
  bool knowsBirth_ = false;     // knowBirth: a birth already in the word's table
  uint64_t knownBirth_ = 0;
  uint32_t knownIndex_ = 0;
  struct {
    uint8_t* labels8 = nullptr;
    uint16_t* labels16 = nullptr;
    double* values = nullptr;
    uint64_t* keys = nullptr;  // the slice's first run in the word
    uint32_t* birthIndex = nullptr;
    uint16_t* firstK = nullptr;
  } out_;  // where the slice writes
  // Where the slice writes: its first module, run, value and new birth in the word.
  size_t firstModule_ = 0, firstRun_ = 0, firstValue_ = 0;
  uint32_t firstBirth_ = 0;
  // The bitmap word being filled, and the words shared with the neighbouring slices.
  size_t bitsWord_ = SIZE_MAX;
  uint64_t bits_ = 0;
  std::vector<std::pair<size_t, uint64_t>> sharedWords_;
};

/// Walks a compact word in order with the accessors of CellCursor (pools/cell_cursor.h),
/// so a reader templated on its cursor reads either kind of word. The id is computed
/// only when asked. Invalid once the word changes.
class CompactWordCursor {
 public:
  /// A cursor over no word, done() at once.
  CompactWordCursor() = default;
  explicit CompactWordCursor(const CompactWord& word, size_t first = 0);

  bool done() const { return index_ >= size_; }
  void next() {
    if (!stateless_) value_ += stateCounts_[master()];
    if (++index_ >= size_) return;
    if ((runStarts_[index_ / CompactWord::kBlock] >> (index_ % CompactWord::kBlock)) & 1u) {
      ++run_;
      j_ = 0;
      loadRun();
    } else {
      ++j_;
    }
  }
  size_t size() const { return size_; }

  // The module under the cursor (not done()).
  size_t index() const { return index_; }
  uint32_t master() const { return labels8_ ? labels8_[index_] : labels16_[index_]; }
  const double* state() const { return word_->values_.data() + value_; }
  double birth() const { return runBirth_; }
  uint32_t birthIndex() const { return runBirthIndex_; }
  /// Whether the module continues the run of the module before it.
  bool continuesRun() const { return j_ > 0; }
  IdKey key() const { return runFirstK_ == IdKey::kWhole ? IdKey::whole(runKey_) : IdKey{runKey_, runFirstK_ + j_}; }
  uint64_t id() const { return key().id(); }
  /// Where the module's values start in the word's values.
  size_t stateOffset() const { return value_; }
  CellView view() const { return {master(), state(), birth(), id(), index_}; }

 private:
  const CompactWord* word_ = nullptr;
  const uint8_t* labels8_ = nullptr;  // null for a word of two-byte labels
  const uint16_t* labels16_ = nullptr;
  // What a module's run says, read once a run: most runs are read module after module.
  void loadRun() {
    runKey_ = keys_[run_];
    runFirstK_ = firstK_[run_];
    if (runFirstK_ >= CompactWord::kWideMark) [[unlikely]]
      runFirstK_ = word_->firstKOf(run_);
    runBirthIndex_ = birthIndex_[run_];
    runBirth_ = births_[runBirthIndex_];
  }

  const uint64_t* runStarts_ = nullptr;
  const uint32_t* stateCounts_ = nullptr;
  const uint64_t* keys_ = nullptr;
  const uint16_t* firstK_ = nullptr;
  const uint32_t* birthIndex_ = nullptr;
  const double* births_ = nullptr;
  size_t size_ = 0;
  bool stateless_ = true;
  uint64_t runKey_ = 0;
  uint32_t runFirstK_ = 0, runBirthIndex_ = 0;
  double runBirth_ = 0;
  size_t index_ = 0, run_ = 0, value_ = 0;
  uint32_t j_ = 0;
};

}  // namespace ontogen
