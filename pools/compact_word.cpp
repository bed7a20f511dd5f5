#include "pools/compact_word.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <unordered_map>

namespace ontogen {

namespace {
// How far back birthIndexOf looks for an equal birth before it appends one. A step's
// events are born at few instants, and a writer copying an old word meets its births in
// the order they were appended, so a short look finds them.
constexpr size_t kBirthLookBack = 8;
}  // namespace

CompactWord::CompactWord(std::vector<uint32_t> stateCounts) : stateCounts_(std::move(stateCounts)) {
  wide_ = stateCounts_.size() > 256;
  stateless_ = std::all_of(stateCounts_.begin(), stateCounts_.end(), [](uint32_t n) { return n == 0; });
}

size_t CompactWord::bytes() const {
  return labels8_.size() + labels16_.size() * sizeof(uint16_t) + runStarts_.size() * sizeof(uint64_t) +
         (blockRuns_.size() + blockValues_.size()) * sizeof(uint32_t) + blockJ_.size() * sizeof(uint16_t) +
         keys_.size() * (sizeof(uint64_t) + sizeof(uint16_t)) + birthIndex_.size() * sizeof(uint32_t) +
         wideK_.size() * sizeof(WideK) + births_.size() * sizeof(double) + values_.size() * sizeof(double);
}

size_t CompactWord::Slice::heldBytes() const {
  return births_.capacity() * sizeof(double) + wideK_.capacity() * sizeof(WideK) +
         sharedWords_.capacity() * sizeof(std::pair<size_t, uint64_t>);
}

void CompactWord::clear() {
  largestBytes_ = std::max(largestBytes_, bytes());
  size_ = 0;
  labels8_.clear();
  labels16_.clear();
  runStarts_.clear();
  blockRuns_.clear();
  blockValues_.clear();
  blockJ_.clear();
  keys_.clear();
  birthIndex_.clear();
  firstK_.clear();
  wideK_.clear();
  values_.clear();
  tail_ = RunTail{};
  runJ_ = 0;
  withoutIds_ = false;
}

void CompactWord::noIds() {
  throw std::logic_error("ontogen: internal error: an id read from a compact word held without ids");
}

void CompactWord::clearWithBirthsOf(const CompactWord& other) {
  clear();
  births_ = other.births_;
}

void CompactWord::reserve(size_t modules, size_t runs, size_t values) {
  (wide_ ? labels16_.reserve(modules) : labels8_.reserve(modules));
  const size_t blocks = (modules + kBlock - 1) / kBlock;
  runStarts_.reserve(blocks);
  blockRuns_.reserve(blocks);
  blockJ_.reserve(blocks);
  if (!stateless_) blockValues_.reserve(blocks);
  keys_.reserve(runs);
  birthIndex_.reserve(runs);
  firstK_.reserve(runs);
  values_.reserve(values);
}

size_t CompactWord::birthIndexIn(std::vector<double>& births, double birth) {
  const uint64_t bits = std::bit_cast<uint64_t>(birth);
  const size_t lookBack = std::min(births.size(), kBirthLookBack);
  for (size_t back = 1; back <= lookBack; ++back)
    if (std::bit_cast<uint64_t>(births[births.size() - back]) == bits) return births.size() - back;
  births.push_back(birth);
  return births.size() - 1;
}

uint32_t CompactWord::addBirth(double birth) {
  const size_t index = birthIndexIn(births_, birth);
  if (index >= UINT32_MAX) throw std::length_error("ontogen: a linear word with 2^32 distinct birth times");
  return static_cast<uint32_t>(index);
}

void CompactWord::tooManyValues() {
  throw std::length_error("ontogen: a linear word with 2^32 state values");
}

void CompactWord::appendValues(uint32_t count, const double* values) {
  if (values_.size() + count > UINT32_MAX) [[unlikely]]
    tooManyValues();
  const size_t at = values_.size();
  if (!values) {
    resizeForOverwrite(values_, at + count);  // written later, from `at` on
    return;
  }
  values_.resize(at + count);
  std::copy(values, values + count, values_.begin() + static_cast<std::ptrdiff_t>(at));
}

void CompactWord::startBlock() {
  // The block index counts runs and values in 32 bits, as a record's state offset did.
  if (keys_.size() >= UINT32_MAX || values_.size() >= UINT32_MAX)
    throw std::length_error("ontogen: a linear word with 2^32 runs or state values");
  runStarts_.push_back(0);
  blockRuns_.push_back(static_cast<uint32_t>(keys_.size()));
  // The place of the block's first module if it continues the last run (if it starts one,
  // its bit says so and this is not read).
  blockJ_.push_back(static_cast<uint16_t>(size_ == 0 ? 0 : runJ_ + 1));
  if (!stateless_) blockValues_.push_back(static_cast<uint32_t>(values_.size()));
}

void CompactWord::appendStretch(const CompactWord& from, size_t first, uint32_t n, IdKey key, uint32_t birthIndex) {
  if (!stateless_) throw std::logic_error("ontogen: internal error: a stretch appended to a word with state values");
  append(from.label(first), key, birthIndex, nullptr);
  for (uint32_t j = 1; j < n;) {
    if (size_ % kBlock == 0) startBlock();  // before runJ_ moves: the block's j is one more
    const uint32_t room = std::min<uint32_t>(n - j, static_cast<uint32_t>(kBlock - size_ % kBlock));
    if (wide_)
      labels16_.insert(labels16_.end(), from.labels16_.begin() + static_cast<std::ptrdiff_t>(first + j),
                       from.labels16_.begin() + static_cast<std::ptrdiff_t>(first + j + room));
    else
      labels8_.insert(labels8_.end(), from.labels8_.begin() + static_cast<std::ptrdiff_t>(first + j),
                      from.labels8_.begin() + static_cast<std::ptrdiff_t>(first + j + room));
    runJ_ += room;
    size_ += room;
    j += room;
  }
  if (n > 1) tail_.continues(IdKey{key.key, key.k + n - 1}, births_[birthIndex]);
}

void CompactWord::finish() {
  if (births_.size() <= std::max<size_t>(64, 2 * birthIndex_.size())) return;
  std::vector<double> renumbered;
  std::unordered_map<uint64_t, uint32_t> indexOf;
  for (uint32_t& index : birthIndex_) {
    const double birth = births_[index];
    const auto [at, added] = indexOf.try_emplace(std::bit_cast<uint64_t>(birth), renumbered.size());
    if (added) renumbered.push_back(birth);
    index = at->second;
  }
  births_ = std::move(renumbered);
}

void CompactWord::resizeForWriters(size_t modules, size_t runs, size_t values) {
  size_ = modules;
  (wide_ ? resizeForOverwrite(labels16_, modules) : resizeForOverwrite(labels8_, modules));
  const size_t blocks = (modules + kBlock - 1) / kBlock;
  resizeForOverwrite(runStarts_, blocks);
  resizeForOverwrite(blockRuns_, blocks);
  resizeForOverwrite(blockJ_, blocks);
  if (!stateless_) resizeForOverwrite(blockValues_, blocks);
  resizeForOverwrite(keys_, runs);
  resizeForOverwrite(birthIndex_, runs);
  resizeForOverwrite(firstK_, runs);
  resizeForOverwrite(values_, values);
}

void CompactWord::appendWord(const CompactWord& part, size_t sharedBirths) {
  PartPlace place;
  place.part = &part;
  placeParts({&place, 1}, sharedBirths);
  copyPart(place, sharedBirths);
  endParts({&place, 1});
}

void CompactWord::placeParts(std::span<PartPlace> places, size_t sharedBirths) {
  size_t modules = size_, runs = keys_.size();
  for (PartPlace& place : places) {
    const CompactWord& part = *place.part;
    if (!values_.empty() || !part.values_.empty())
      throw std::logic_error("ontogen: internal error: a part of a compact word with state values");
    if (part.stateCounts_ != stateCounts_)
      throw std::logic_error("ontogen: internal error: a part of a compact word of other labels");
    if (sharedBirths > part.births_.size() || sharedBirths > births_.size())
      throw std::logic_error("ontogen: internal error: a part of a compact word that does not share the births");
    place.firstModule = modules;
    place.firstRun = runs;
    modules += part.size_;
    runs += part.keys_.size();
    // The part's own births, where this word's table has them or added to it.
    place.births.clear();
    for (size_t b = sharedBirths; b < part.births_.size(); ++b) place.births.push_back(addBirth(part.births_[b]));
    place.sharedWords.clear();
  }
  if (runs >= UINT32_MAX) throw std::length_error("ontogen: a linear word with 2^32 runs");
  writtenBlocks_ = runStarts_.size();
  resizeForWriters(modules, runs, 0);
}

void CompactWord::copyPart(PartPlace& place, size_t sharedBirths) {
  const CompactWord& part = *place.part;
  const size_t base = place.firstModule, n = part.size_, runsBefore = place.firstRun;
  if (n == 0) return;
  std::copy(part.keys_.begin(), part.keys_.end(), keys_.begin() + static_cast<ptrdiff_t>(runsBefore));
  std::copy(part.firstK_.begin(), part.firstK_.end(), firstK_.begin() + static_cast<ptrdiff_t>(runsBefore));
  uint32_t* birthIndex = birthIndex_.data() + runsBefore;
  for (const uint32_t index : part.birthIndex_)
    *birthIndex++ = index < sharedBirths ? index : place.births[index - sharedBirths];
  if (wide_)
    std::copy(part.labels16_.begin(), part.labels16_.end(), labels16_.begin() + static_cast<ptrdiff_t>(base));
  else
    std::copy(part.labels8_.begin(), part.labels8_.end(), labels8_.begin() + static_cast<ptrdiff_t>(base));
  // The part's run-start bits from its module `from` on, 64 of them (none past its end).
  auto bitsFrom = [&](size_t from) {
    const size_t word = from / kBlock;
    const unsigned shift = from % kBlock;
    uint64_t bits = part.runStarts_[word] >> shift;
    if (shift != 0 && word + 1 < part.runStarts_.size()) bits |= part.runStarts_[word + 1] << (kBlock - shift);
    const size_t left = n - from;
    return left >= kBlock ? bits : bits & ((uint64_t{1} << left) - 1);
  };
  // The modules up to the end of the block the part starts in, then a block at a time.
  // Bitmap words the part shares with a neighbour are joined by endParts.
  size_t at = 0, starts = 0, lastStart = base;  // the part's module 0 starts a run
  if (base % kBlock != 0) {
    const uint64_t bits = bitsFrom(0) & (~uint64_t{0} >> (base % kBlock));
    place.sharedWords.emplace_back(base / kBlock, bits << (base % kBlock));
    starts = static_cast<size_t>(std::popcount(bits));
    lastStart = base + (kBlock - 1 - static_cast<size_t>(std::countl_zero(bits)));
    at = kBlock - base % kBlock;
  }
  for (; at < n; at += kBlock) {
    const uint64_t bits = bitsFrom(at);
    const size_t first = base + at, block = first / kBlock;
    if (at + kBlock <= n)
      runStarts_[block] = bits;
    else
      place.sharedWords.emplace_back(block, bits);
    blockRuns_[block] = static_cast<uint32_t>(runsBefore + starts);
    blockJ_[block] = static_cast<uint16_t>(bits & 1u ? 0 : first - lastStart);
    if (!stateless_) blockValues_[block] = 0;  // neither word has values
    starts += static_cast<size_t>(std::popcount(bits));
    if (bits != 0) lastStart = first + (kBlock - 1 - static_cast<size_t>(std::countl_zero(bits)));
  }
}

void CompactWord::endParts(std::span<PartPlace> places) {
  // A shared word this word held before the parts keeps its bits; the others are
  // cleared, then joined.
  for (const PartPlace& place : places)
    for (const auto& [word, bits] : place.sharedWords)
      if (word >= writtenBlocks_) runStarts_[word] = 0;
  for (const PartPlace& place : places)
    for (const auto& [word, bits] : place.sharedWords) runStarts_[word] |= bits;
  for (const PartPlace& place : places) {
    for (const WideK& wide : place.part->wideK_) addWideK(place.firstRun + wide.run, wide.k);
    if (!place.part->empty()) {
      tail_ = place.part->tail_;
      runJ_ = place.part->runJ_;
    }
  }
}

void CompactWord::beginSlices(std::span<Slice> slices) {
  size_t modules = 0, values = 0, runs = 0;
  for (const Slice& slice : slices) {
    if (slice.from_->stateCounts_ != stateCounts_)
      throw std::logic_error("ontogen: internal error: a slice copies from a word of other labels");
    modules += slice.modules_;
    values += slice.values_;
    runs += slice.countedRuns_;
  }
  // Birth indices carry kNewBirth while a slice writes.
  if (values > UINT32_MAX || runs > UINT32_MAX || births_.size() >= Slice::kNewBirth)
    throw std::length_error("ontogen: a linear word with 2^32 runs or state values, or 2^31 birth times");
  std::vector<double> births = std::move(births_);
  clear();
  births_ = std::move(births);
  resizeForWriters(modules, runs, values);
  size_t module = 0, value = 0, run = 0;
  for (Slice& slice : slices) {
    slice.word_ = this;
    slice.firstModule_ = module;
    slice.firstValue_ = value;
    slice.firstRun_ = run;
    module += slice.modules_;
    value += slice.values_;
    run += slice.countedRuns_;
    slice.written_ = slice.writtenValues_ = slice.runs_ = 0;
    slice.runJ_ = 0;
    slice.tail_ = RunTail{};
    slice.births_.clear();
    slice.wideK_.clear();
    slice.sharedWords_.clear();
    slice.bitsWord_ = SIZE_MAX;
    slice.out_ = {
        wide_ ? nullptr : labels8_.data(), wide_ ? labels16_.data() : nullptr,   values_.data(),
        keys_.data() + slice.firstRun_,    birthIndex_.data() + slice.firstRun_, firstK_.data() + slice.firstRun_};
  }
}

void CompactWord::endSlices(std::span<Slice> slices) {
  joinSlices(slices);
  for (Slice& slice : slices) slice.place();
}

void CompactWord::joinSlices(std::span<Slice> slices) {
  for (Slice& slice : slices) {
    slice.firstBirth_ = static_cast<uint32_t>(births_.size());
    births_.insert(births_.end(), slice.births_.begin(), slice.births_.end());
  }
  if (births_.size() >= Slice::kNewBirth) throw std::length_error("ontogen: a linear word with 2^31 birth times");
  for (const Slice& slice : slices)
    for (const WideK& wide : slice.wideK_) addWideK(slice.firstRun_ + wide.run, wide.k);
  // A word two slices share holds the run starts of both: cleared, then joined.
  for (const Slice& slice : slices)
    for (const auto& [word, bits] : slice.sharedWords_) runStarts_[word] = 0;
  for (const Slice& slice : slices)
    for (const auto& [word, bits] : slice.sharedWords_) runStarts_[word] |= bits;
}

void CompactWord::closeRunGaps(std::span<Slice> slices) {
  size_t run = 0;
  for (Slice& slice : slices) {
    if (slice.firstRun_ != run) {
      const size_t from = slice.firstRun_, n = slice.runs_, gap = from - run;
      std::memmove(birthIndex_.data() + run, birthIndex_.data() + from, n * sizeof(uint32_t));
      if (!withoutIds_) {
        std::memmove(keys_.data() + run, keys_.data() + from, n * sizeof(uint64_t));
        std::memmove(firstK_.data() + run, firstK_.data() + from, n * sizeof(uint16_t));
      }
      // The blocks the slice started (Slice::startBlock) counted the runs before them from
      // its first run as placed.
      const size_t firstBlock = (slice.firstModule_ + kBlock - 1) / kBlock;
      const size_t endBlock = (slice.firstModule_ + slice.written_ + kBlock - 1) / kBlock;
      for (size_t block = firstBlock; block < endBlock; ++block) blockRuns_[block] -= static_cast<uint32_t>(gap);
      slice.firstRun_ = run;
      slice.out_.keys = keys_.data() + run;
      slice.out_.birthIndex = birthIndex_.data() + run;
      slice.out_.firstK = firstK_.data() + run;
    }
    slice.keepRunsWritten();
    run += slice.runs_;
  }
  // A word without ids keeps no key or first k (its writers wrote none). The slices' runs
  // of wide k are numbered from their first run, which joinSlices reads as moved here.
  keys_.resize(withoutIds_ ? 0 : run);
  birthIndex_.resize(run);
  firstK_.resize(withoutIds_ ? 0 : run);
}

void CompactWord::beginWholeSlice(Slice& slice, size_t modules, size_t runs, size_t values) {
  if (stateless_ && values > 0)
    throw std::logic_error("ontogen: internal error: state values in a whole slice of a word without them");
  slice.modules_ = modules;
  slice.countedRuns_ = runs;
  slice.values_ = values;
  beginSlices({&slice, 1});
}

void CompactWord::endWholeSlice(Slice& slice) {
  // What was written is what the slice counts: its last bitmap word is flushed as the
  // word's own when whole, and the arrays are cut to it.
  slice.modules_ = slice.written_;
  slice.countedRuns_ = slice.runs_;
  slice.values_ = slice.writtenValues_;
  slice.finish();
  size_ = slice.written_;
  (wide_ ? labels16_.resize(size_) : labels8_.resize(size_));
  const size_t blocks = (size_ + kBlock - 1) / kBlock;
  runStarts_.resize(blocks);
  blockRuns_.resize(blocks);
  blockJ_.resize(blocks);
  if (!stateless_) blockValues_.resize(blocks);
  values_.resize(slice.writtenValues_);
  keys_.resize(withoutIds_ ? 0 : slice.runs_);  // a word without ids keeps no key or first k
  birthIndex_.resize(slice.runs_);
  firstK_.resize(withoutIds_ ? 0 : slice.runs_);
  endSlices({&slice, 1});
}

void CompactWord::Slice::place() {
  if (births_.empty()) return;
  uint32_t* birthIndex = out_.birthIndex;
  for (size_t r = 0; r < runs_; ++r) {
    const uint32_t index = birthIndex[r];
    if (index & kNewBirth) birthIndex[r] = firstBirth_ + (index & ~kNewBirth);
  }
}

void CompactWord::Slice::startBlock(size_t i) {
  if (i % kBlock == 0) {
    word_->blockRuns_[i / kBlock] = static_cast<uint32_t>(firstRun_ + runs_);
    word_->blockJ_[i / kBlock] = static_cast<uint16_t>(runJ_ + 1);  // read only if it continues a run
    if (!word_->stateless_) word_->blockValues_[i / kBlock] = static_cast<uint32_t>(firstValue_ + writtenValues_);
  }
  flushBits();
  bitsWord_ = i / kBlock;
  bits_ = 0;
}

void CompactWord::Slice::flushBits() {
  if (bitsWord_ == SIZE_MAX) return;
  const size_t first = bitsWord_ * kBlock;
  if (first >= firstModule_ && first + kBlock <= firstModule_ + modules_)
    word_->runStarts_[bitsWord_] = bits_;
  else
    sharedWords_.emplace_back(bitsWord_, bits_);
}

void CompactWord::Slice::finish() {
  if (!word_) return;
  flushBits();
  bitsWord_ = SIZE_MAX;
  // Counting and writing agree by contract; a slice that wrote other than it counted
  // would leave unwritten memory in the word, so it stops here.
  if (written_ != modules_ || writtenValues_ != values_ || runs_ != countedRuns_)
    throw std::logic_error("ontogen: internal error: a slice of a compact word wrote other than it counted");
}

bool CompactWord::indexAgrees() const {
  size_t runs = 0, values = 0;
  for (size_t i = 0; i < size_; ++i) {
    const size_t block = i / kBlock;
    if (i % kBlock == 0) {
      const bool startsHere = startsRun(i);
      // A block's count of runs before it, and its place in its run when its first module
      // continues one (read only for words with ids).
      if (blockRuns_[block] != runs || (!stateless_ && blockValues_[block] != values)) return false;
      if (!startsHere && runs == 0) return false;
    }
    if (startsRun(i)) ++runs;
    values += stateless_ ? 0 : stateCounts_[label(i)];
  }
  // No run starts past the end, and every run is held.
  const size_t blocks = (size_ + kBlock - 1) / kBlock;
  if (size_ % kBlock != 0 && (runStarts_[blocks - 1] >> (size_ % kBlock)) != 0) return false;
  return runs == birthIndex_.size() && values == values_.size();
}

CompactWord::Place CompactWord::locate(size_t i) const {
  const size_t block = i / kBlock;
  const unsigned bit = i % kBlock;
  const uint64_t upTo = runStarts_[block] & (bit == kBlock - 1 ? ~uint64_t{0} : (uint64_t{2} << bit) - 1);
  Place place;
  // Module 0 starts a run, so a block with no start up to i has runs before it.
  place.run = blockRuns_[block] + static_cast<size_t>(std::popcount(upTo)) - 1;
  if (upTo != 0)
    place.j = static_cast<uint32_t>(i - (block * kBlock + (kBlock - 1 - static_cast<size_t>(std::countl_zero(upTo)))));
  else
    place.j = blockJ_[block] + static_cast<uint32_t>(bit);
  if (!stateless_) {
    size_t value = blockValues_[block];
    for (size_t p = block * kBlock; p < i; ++p) value += stateCounts_[label(p)];
    place.value = value;
  }
  return place;
}

void CompactWord::addWideK(size_t run, uint32_t k) {
  if (run >= UINT32_MAX) throw std::length_error("ontogen: a linear word with 2^32 runs");
  wideK_.push_back({static_cast<uint32_t>(run), k});
}

uint32_t CompactWord::wideK(size_t run) const {
  const auto at =
      std::lower_bound(wideK_.begin(), wideK_.end(), run, [](const WideK& wide, size_t r) { return wide.run < r; });
  if (at == wideK_.end() || at->run != run)
    throw std::logic_error("ontogen: internal error: a run of a compact word marked for a wide k it does not have");
  return at->k;
}

CellView CompactWord::cellAt(size_t i) const {
  const Place place = locate(i);
  return {label(i), values_.data() + place.value, birthOf(place.run), keyOf(place.run, place.j).id(), i};
}

CompactWord::Slice::Slice(const CompactWord& from)
    : from_(&from), stateCounts_(from.stateCounts_.data()), stateless_(from.stateless_) {}

void CompactWord::Slice::restart(const CompactWord& from) {
  from_ = &from;
  stateCounts_ = from.stateCounts_.data();
  stateless_ = from.stateless_;
  word_ = nullptr;
  knowsBirth_ = false;
  modules_ = values_ = countedRuns_ = 0;
  tail_ = RunTail{};
}

void CompactWord::Slice::appendKept(size_t first, uint32_t n, IdKey key, uint32_t birthIndex) {
  const double birth = from_->births_[birthIndex];
  const bool continues = tail_.continues(key, birth);
  stretch(first, n, key, continues, birthIndex);
  if (n > 1) tail_.continues(IdKey{key.key, key.k + n - 1}, birth);
}

void CompactWord::Slice::appendRenewed(size_t first, uint32_t n, IdKey key, double birth) {
  const bool continues = tail_.continues(key, birth);
  stretch(first, n, key, continues, word_ ? birthIndexOf(birth) : 0);
  if (n > 1) tail_.continues(IdKey{key.key, key.k + n - 1}, birth);
}

void CompactWord::Slice::stretch(size_t first, uint32_t n, IdKey key, bool continues, uint32_t birthIndex) {
  if (!word_) {
    modules_ += n;
    countedRuns_ += continues ? 0 : 1;
    return;
  }
  put(from_->label(first), key, continues, birthIndex, nullptr);
  for (uint32_t j = 1; j < n;) {
    const size_t i = firstModule_ + written_;
    if (i % kBlock == 0) startBlock(i);  // before runJ_ moves: the block's j is one more
    const uint32_t room = std::min<uint32_t>(n - j, static_cast<uint32_t>(kBlock - i % kBlock));
    if (out_.labels8)
      std::memcpy(out_.labels8 + i, from_->labels8_.data() + first + j, room);
    else
      std::memcpy(out_.labels16 + i, from_->labels16_.data() + first + j, room * sizeof(uint16_t));
    runJ_ += room;
    written_ += room;
    j += room;
  }
}

CompactWordCursor::CompactWordCursor(const CompactWord& word, size_t first)
    : word_(&word),
      labels8_(word.wide_ ? nullptr : word.labels8_.data()),
      labels16_(word.wide_ ? word.labels16_.data() : nullptr),
      runStarts_(word.runStarts_.data()),
      stateCounts_(word.stateCounts_.data()),
      keys_(word.keys_.data()),
      firstK_(word.firstK_.data()),
      birthIndex_(word.birthIndex_.data()),
      births_(word.births_.data()),
      size_(word.size_),
      stateless_(word.stateless_),
      index_(first) {
  if (word.withoutIds_) [[unlikely]]
    CompactWord::noIds();
  if (first >= size_) return;
  if (first > 0) {
    const CompactWord::Place place = word.locate(first);
    run_ = place.run;
    j_ = place.j;
    value_ = place.value;
  }
  loadRun();
}

CompactWordCursor CompactWord::cursor() const {
  return CompactWordCursor(*this);
}

}  // namespace ontogen
