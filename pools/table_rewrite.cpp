// The parts of pools/table_rewrite.h that are not templates used across files: the
// table's making, the bounds of a slice, the walk of a word of labels without ids (its
// four forms instantiated here), and the loop of steps with values.

#include "pools/table_rewrite.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>

#include "pools/label_counts.h"

namespace ontogen {

void RewriteTable::setSuccessors(Entry& entry, const std::vector<uint32_t>& successors) {
  entry.renews = false;
  entry.first = static_cast<uint32_t>(labels.size());
  entry.count = static_cast<uint32_t>(successors.size());
  labels.insert(labels.end(), successors.begin(), successors.end());
  entry.packed = 0;
  for (size_t s = 0; s < successors.size() && s < 8; ++s) entry.packed |= uint64_t{successors[s] & 0xFFu} << (8 * s);
}

void RewriteTable::setOperations(Entry& entry, const std::vector<ValueOperation>& computed) {
  entry.firstOperation = static_cast<uint32_t>(operations.size());
  entry.operationCount = static_cast<uint32_t>(computed.size());
  operations.insert(operations.end(), computed.begin(), computed.end());
}

void RewriteTable::finish(std::vector<uint32_t> values) {
  stateCounts = std::move(values);
  stateCounts.resize(entries.size(), 0);
  withValues = std::any_of(stateCounts.begin(), stateCounts.end(), [](uint32_t n) { return n > 0; });
  // A kept or renewed module takes its own values: one copy a value, after the entries'.
  std::vector<uint32_t> copies(entries.size());
  for (size_t label = 0; label < entries.size(); ++label) {
    copies[label] = static_cast<uint32_t>(operations.size());
    for (uint32_t v = 0; v < stateCounts[label]; ++v) operations.push_back(ValueOperation::copy(v));
  }
  boundValues.assign(entries.size(), 0);
  bytes.assign(labels.begin(), labels.end());  // one byte each (at most 256 labels)
  const uint32_t self = static_cast<uint32_t>(bytes.size());
  for (size_t label = 0; label < entries.size(); ++label) bytes.push_back(static_cast<uint8_t>(label));
  bytes.resize(bytes.size() + kBytesPadding, 0);
  lifetimes.clear();
  steps.clear();
  runSteps.clear();
  runLifetime = kForever;
  oneLifetime = true;
  for (const Entry& entry : entries) {
    if (entry.lifetime == kForever) continue;  // timeless: never expires
    if (runLifetime == kForever) runLifetime = entry.lifetime;
    oneLifetime = oneLifetime && entry.lifetime == runLifetime && entry.count <= kBytesPadding;
  }
  oneLifetime = oneLifetime && runLifetime < kForever;
  anyTimeless = false;
  for (size_t label = 0; label < entries.size(); ++label) {
    const Entry& entry = entries[label];
    lifetimes.push_back(entry.lifetime);
    const uint32_t itself = self + static_cast<uint32_t>(label);
    const bool timeless = entry.lifetime == kForever;
    anyTimeless = anyTimeless || timeless;
    // Kept: adds nothing to its death, which is forever for a timeless module.
    steps.push_back({itself, 1, 0, 0, timeless ? kForever : 0.0, timeless, copies[label], stateCounts[label]});
    if (entry.renews)
      steps.push_back({itself, 1, 0, 1, entry.lifeAfter, false, copies[label], stateCounts[label]});
    else
      steps.push_back({entry.first, entry.count, entry.count, 1, entry.lifeAfter, false, entry.firstOperation,
                       entry.operationCount});
    boundValues[label] = std::max(steps[2 * label].operationCount, steps[2 * label + 1].operationCount);
    for (size_t taken = 2 * label; taken < 2 * label + 2; ++taken) {
      Step& step = steps[taken];
      step.affine = step.count > 0 && std::all_of(operations.begin() + step.firstOperation,
                                                  operations.begin() + step.firstOperation + step.operationCount,
                                                  [](const ValueOperation& operation) { return operation.affine; });
    }
    runSteps.push_back(static_cast<uint32_t>(2 * label + (timeless ? 0 : 1)));
  }
}

TableBound TableRewrite::bound(const CompactWord& from, size_t begin, size_t end, const RewriteTable& table) {
  uint64_t counts[256];
  countLabels(from.labels8_.data() + begin, end - begin, table.entries.size(), counts);
  TableBound result;
  for (size_t label = 0; label < table.entries.size(); ++label) {
    const RewriteTable::Entry& entry = table.entries[label];
    const uint64_t count = counts[label];
    if (entry.lifetime < RewriteTable::kForever) result.events += count;
    result.modules += count * (entry.renews ? 1 : entry.count);
    result.born += count * (entry.renews ? 0 : entry.count);
    result.values += count * (table.withValues ? table.boundValues[label] : 0);
  }
  return result;
}

template <bool kWriting, bool kFewSteps>
TableRewriteCounts TableRewrite::walkWithoutIds(CompactWord::Slice& out, const CompactWord& from, size_t begin,
                                                size_t end, const RewriteTable& table, double horizon) {
  TableRewriteCounts counts;
  end = std::min(end, from.size());
  if (begin >= end) return counts;
  const uint8_t* labels = from.labels8_.data();
  const uint64_t* starts = from.runStarts_.data();
  const RewriteTable::Step* steps = table.steps.data();
  const double* lifetimes = table.lifetimes.data();
  const uint8_t* bytes = table.bytes.data();

  size_t run = from.locate(begin).run;
  Writer<false> writer(out);
  constexpr uint64_t kNone = ~uint64_t{0};  // the bits of no birth (a NaN)
  uint64_t tailBits = kNone;                // the birth of the last module written
  uint64_t deathBits = kNone;               // the last death, and its index
  uint32_t deathIndex = 0;
  uint64_t events = 0, born = 0, modules = 0, runs = 0;
  double soonest = std::numeric_limits<double>::infinity();

  // One module of a run born at `birth`: its step, its labels written or counted.
  auto visit = [&](size_t i, double birth, uint64_t birthBits, uint32_t birthIndex, uint64_t& seen) {
    const uint32_t label = labels[i];
    const double death = birth + lifetimes[label];
    uint32_t taken = 2 * label;  // the step, kept; expiring is the next
    uint64_t bits;
    uint32_t index = birthIndex;
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
    } else {
      bits = steps[taken].joins && tailBits != kNone ? tailBits : birthBits;
    }
    const RewriteTable::Step* step = steps + taken;
    events += step->event;
    born += step->born;
    if constexpr (kFewSteps)
      seen |= uint64_t{1} << taken;
    else
      soonest = std::min(soonest, death + step->soonAfter);
    const bool startsRun = bits != tailBits;
    tailBits = bits;
    if constexpr (kWriting) {
      writer.putWithoutIds(bytes + step->source, step->count, startsRun, index);
    } else {
      modules += step->count;
      runs += startsRun ? 1 : 0;
    }
  };

  for (size_t i = begin; i < end;) {
    // The modules of one run of `from` up to the next run start, or the end.
    const uint32_t birthIndex = from.birthIndex_[run];
    const double birth = from.births_[birthIndex];
    const uint64_t birthBits = std::bit_cast<uint64_t>(birth);
    const size_t runEnd = nextRunStart(starts, i, end);
    uint64_t seen = 0;  // kFewSteps: bit s, step s taken in this run
    // A run whose modules that can expire all expire at one death (one lifetime, at most
    // 16 successors, the other labels timeless: Thue-Morse, Koch) continues the run of
    // that death once a module has started it: after that module, the rest goes by a
    // loop of a copy a module, blocks started as they pass, timeless modules joining.
    if constexpr (kWriting) {
      if (table.oneLifetime && i + 1 < runEnd && birth + table.runLifetime <= horizon) {
        const double death = birth + table.runLifetime;
        const uint64_t runDeathBits = std::bit_cast<uint64_t>(death);
        while (i < runEnd && tailBits != runDeathBits) visit(i++, birth, birthBits, birthIndex, seen);
        const uint32_t* runSteps = table.runSteps.data();
        // The first block that starts after what is written; one starting just there has
        // not been started yet (a put starts a block before its first module).
        size_t blockEnd = (writer.at + CompactWord::kBlock - 1) / CompactWord::kBlock * CompactWord::kBlock;
        // Without timeless labels every module is an event, and its step follows from its
        // label: a load less a module (Thue-Morse 6 % faster).
        auto copies = [&]<bool kTimeless>() {
          for (; i < runEnd && writer.at + 16 <= writer.sliceEnd; ++i) {
            const uint32_t taken = kTimeless ? runSteps[labels[i]] : 2 * uint32_t{labels[i]} + 1;
            const RewriteTable::Step& step = steps[taken];
            std::memcpy(writer.labels + writer.at, bytes + step.source, 16);  // bytes past count written over next
            writer.at += step.count;
            if constexpr (kTimeless)
              events += step.event;
            else
              ++events;
            born += step.born;
            if constexpr (kFewSteps)
              seen |= uint64_t{1} << taken;
            else
              soonest = std::min(soonest, death + step.soonAfter);
            writer.startBlocksBefore(blockEnd);
          }
        };
        if (table.anyTimeless)
          copies.template operator()<true>();
        else
          copies.template operator()<false>();
      }
    }
    for (; i < runEnd; ++i) visit(i, birth, birthBits, birthIndex, seen);
    if constexpr (kFewSteps) {
      for (; seen != 0; seen &= seen - 1) {
        const size_t taken = static_cast<size_t>(std::countr_zero(seen));
        soonest = std::min(soonest, (birth + lifetimes[taken / 2]) + steps[taken].soonAfter);
      }
    }
    ++run;
  }
  if constexpr (kWriting) {
    writer.store();
  } else {
    out.modules_ += modules;
    out.countedRuns_ += runs;
  }
  counts.events = events;
  counts.born = born;
  counts.soonest = soonest;
  return counts;
}

template TableRewriteCounts TableRewrite::walkWithoutIds<true, true>(CompactWord::Slice&, const CompactWord&, size_t,
                                                                     size_t, const RewriteTable&, double);
template TableRewriteCounts TableRewrite::walkWithoutIds<true, false>(CompactWord::Slice&, const CompactWord&, size_t,
                                                                      size_t, const RewriteTable&, double);
template TableRewriteCounts TableRewrite::walkWithoutIds<false, true>(CompactWord::Slice&, const CompactWord&, size_t,
                                                                      size_t, const RewriteTable&, double);
template TableRewriteCounts TableRewrite::walkWithoutIds<false, false>(CompactWord::Slice&, const CompactWord&, size_t,
                                                                       size_t, const RewriteTable&, double);

template <uint32_t kWritten>
size_t TableRewrite::StepsWithValues::stretchOfOne(const uint8_t* from, size_t room, uint32_t label,
                                                   const uint8_t* writes, uint32_t count,
                                                   const ValueOperation* operation, const double* own,
                                                   uint8_t* labelsOut, double* valuesOut) {
  double multiplier[kWritten], addend[kWritten];
  for (uint32_t w = 0; w < kWritten; ++w) {
    multiplier[w] = operation[w].multiplier;
    addend[w] = operation[w].addend;
  }
  size_t k = 0;
  for (; k < room && from[k] == label; ++k) {
    std::memcpy(labelsOut, writes, 16);  // bytes past count written over next
    labelsOut += count;
    const double x = own[k];
    for (uint32_t w = 0; w < kWritten; ++w) valuesOut[w] = x * multiplier[w] + addend[w];
    valuesOut += kWritten;
  }
  return k;
}

void TableRewrite::StepsWithValues::run(State& state, size_t end, size_t stop, size_t blockEnd) const {
  size_t i = state.i, at = state.at, valueAt = state.valueAt, value = state.value;
  uint64_t events = state.events, born = state.born, seen = state.seen;
  // In locals: a label stored through a byte pointer may alias the members.
  const uint8_t* const from = labels;
  const uint32_t* const stepOf = runSteps;
  const RewriteTable::Step* const stepAt = steps;
  const uint8_t* const source = bytes;
  const ValueOperation* const computed = operations;
  const uint32_t* const counts = stateCounts;
  const double* const values = in;
  uint8_t* const labelsOut = outLabels;
  double* const valuesOut = outValues;
  while (i < end && at <= stop) {
    const uint32_t label = from[i];
    const uint32_t taken = stepOf[label];
    const RewriteTable::Step& step = stepAt[taken];
    if (step.affine) {
      // Modules of this label one after another, each writing the same labels and its
      // values by multiply-adds, up to the step that writes past blockEnd.
      const uint32_t count = step.count, written = step.operationCount, read = counts[label];
      const size_t room = std::min({end - i, (stop - at) / count + 1, (blockEnd - at) / count + 1});
      const uint8_t* writes = source + step.source;
      const ValueOperation* operation = computed + step.firstOperation;
      size_t k = 0;
      // One value a module, a few written (the parametric word's A and B: two): the
      // multipliers and addends held in registers.
      if (read == 1 && written >= 1 && written <= 4) {
        const auto stretch = [&]<uint32_t kWritten>() {
          return stretchOfOne<kWritten>(from + i, room, label, writes, count, operation, values + value, labelsOut + at,
                                        valuesOut + valueAt);
        };
        k = written == 1   ? stretch.template operator()<1>()
            : written == 2 ? stretch.template operator()<2>()
            : written == 3 ? stretch.template operator()<3>()
                           : stretch.template operator()<4>();
        at += k * count;
        valueAt += k * written;
        value += k;
      } else {
        for (; k < room && from[i + k] == label; ++k) {
          std::memcpy(labelsOut + at, writes, 16);  // bytes past count written over next
          const double* own = values + value;
          double* to = valuesOut + valueAt;
          for (uint32_t v = 0; v < written; ++v)
            to[v] = own[operation[v].slot] * operation[v].multiplier + operation[v].addend;
          at += count;
          valueAt += written;
          value += read;
        }
      }
      i += k;
      events += step.event * k;
      born += step.born * k;
      seen |= uint64_t{1} << taken;
      if (blockEnd < at) break;
      continue;
    }
    ++i;
    std::memcpy(labelsOut + at, source + step.source, 16);  // bytes past count written over next
    const double* own = values + value;
    double* to = valuesOut + valueAt;
    const ValueOperation* operation = computed + step.firstOperation;
    for (uint32_t v = 0; v < step.operationCount; ++v) to[v] = operation[v].applyQuickly(own);
    value += counts[label];
    at += step.count;
    valueAt += step.operationCount;
    events += step.event;
    born += step.born;
    seen |= uint64_t{1} << taken;
    if (blockEnd < at) [[unlikely]]
      break;
  }
  state.i = i;
  state.at = at;
  state.valueAt = valueAt;
  state.value = value;
  state.events = events;
  state.born = born;
  state.seen = seen;
}

}  // namespace ontogen
