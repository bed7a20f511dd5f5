#include "pools/compact_word.h"

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace ontogen {
namespace {

// A module as a 24-byte record would hold it, to compare the compact word against.
struct Expected {
  uint32_t label;
  IdKey key;
  double birth;
  std::vector<double> values;
};

void expectSameModule(const CellView& cell, const Expected& expected, size_t i) {
  ASSERT_EQ(cell.index, i);
  ASSERT_EQ(cell.master, expected.label) << "module " << i;
  ASSERT_EQ(cell.id, expected.key.id()) << "module " << i;
  ASSERT_EQ(std::bit_cast<uint64_t>(cell.birth), std::bit_cast<uint64_t>(expected.birth)) << "module " << i;
  for (size_t v = 0; v < expected.values.size(); ++v) ASSERT_EQ(cell.state[v], expected.values[v]) << "module " << i;
}

// Every module read three ways: the cursor, cellAt(i) (locate), and what was appended.
void expectWordReadsAs(const CompactWord& word, const std::vector<Expected>& expected) {
  ASSERT_EQ(word.size(), expected.size());
  size_t i = 0;
  for (CompactWordCursor cell = word.cursor(); !cell.done(); cell.next(), ++i) {
    expectSameModule(cell.view(), expected[i], i);
    expectSameModule(word.cellAt(i), expected[i], i);
  }
  EXPECT_EQ(i, expected.size());
  // A cursor may also start anywhere, as a thread starts its slice.
  for (size_t first = 0; first < expected.size(); first += 1 + first / 3) {
    CompactWordCursor cell(word, first);
    for (size_t k = 0; k < 70 && !cell.done(); ++k, cell.next())
      expectSameModule(cell.view(), expected[first + k], first + k);
  }
}

TEST(CompactWord, ASuccessorsEventIsOneRunAndTheIdsAreTheLineages) {
  CompactWord word({0, 0});
  const uint64_t lineage = mixKey(17, keyOf(2.0));
  std::vector<Expected> expected;
  auto add = [&](uint32_t label, IdKey key, double birth) {
    word.append(label, key, birth, nullptr);
    expected.push_back({label, key, birth, {}});
  };
  for (uint32_t k = 1; k <= 9; ++k) add(k % 2, {lineage, k}, 2.0);  // F+F-F-F+F: one run
  add(0, {lineage, 11}, 2.0);                                       // k skips: a new run
  add(0, {lineage, 12}, 3.0);                                       // another birth: a new run
  add(0, {lineage + 1, 13}, 3.0);                                   // another key: a new run
  add(1, {lineage + 1, 14}, 3.0);                                   // extends it
  word.finish();
  EXPECT_EQ(word.runCount(), 4u);
  EXPECT_EQ(word.birthCount(), 2u);
  expectWordReadsAs(word, expected);
  EXPECT_EQ(word.cellAt(3).id, mixKey(lineage, 4));
}

TEST(CompactWord, IdsPastTwoBytesOfKTakeTheWideTableAndStillEqualTheLineages) {
  // A production of 65,580 successors: k 1 to 65,535 make one run (1,024 blocks of the
  // index, so module i far into it is found by its block's place in the run), 65,536 to
  // 65,580 another, whose first k is in the table of wide k.
  static_assert(CompactWord::kLargestRunK == 65534);
  constexpr uint32_t kSuccessors = CompactWord::kLargestRunK + 46;
  CompactWord word({0, 0});
  const uint64_t lineage = mixKey(99, keyOf(1.0));
  std::vector<Expected> expected;
  for (uint32_t k = 1; k <= kSuccessors; ++k) {
    word.append(k % 2, {lineage, k}, 1.0, nullptr);
    expected.push_back({k % 2, {lineage, k}, 1.0, {}});
  }
  // A module that keeps a whole id (`me` of a module whose id was kept whole).
  word.append(0, IdKey::whole(mixKey(lineage, kSuccessors)), 1.0, nullptr);
  expected.push_back({0, IdKey::whole(mixKey(lineage, kSuccessors)), 1.0, {}});
  EXPECT_EQ(word.runCount(), 3u);
  EXPECT_EQ(word.wideKCount(), 1u);
  expectWordReadsAs(word, expected);
  EXPECT_EQ(word.cellAt(kSuccessors - 1).id, mixKey(lineage, kSuccessors));
  EXPECT_EQ(word.cellAt(kSuccessors).id, mixKey(lineage, kSuccessors));
  EXPECT_EQ(word.cellAt(65000).id, mixKey(lineage, 65001));
  EXPECT_EQ(word.cellAt(65535).id, mixKey(lineage, 65536));

  // An axiom's ids (k = i) past 2^16 and 2^17: a run for each 65,536, one wide entry for
  // each run after the first.
  CompactWord axiom({0});
  std::vector<Expected> axiomExpected;
  for (uint32_t k = 0; k < 150'000; ++k) {
    axiom.append(0, {17, k}, 0.0, nullptr);
    axiomExpected.push_back({0, {17, k}, 0.0, {}});
  }
  EXPECT_EQ(axiom.runCount(), 3u);
  EXPECT_EQ(axiom.wideKCount(), 2u);
  expectWordReadsAs(axiom, axiomExpected);
}

TEST(CompactWord, LocateAgreesWithTheCursorOnARandomWordWithState) {
  // Runs of every length up to 300 (so they cross several blocks), some starting near the
  // largest k two bytes hold or near 2^20 and 2^32 (in the table of wide k), whole ids,
  // labels with 0 to 3 values, births that differ only in sign (0.0 and -0.0 are distinct).
  const std::vector<uint32_t> stateCounts{0, 1, 3, 0, 2};
  CompactWord word(stateCounts);
  std::mt19937_64 random(20261202);
  const double births[] = {0.0, -0.0, 0.25, 1.0 / 3.0, 7.5};
  std::vector<Expected> expected;
  size_t runs = 0;
  double value = 0.5;
  while (expected.size() < 60000) {
    const uint64_t key = random();
    const bool whole = random() % 16 == 0;
    const uint32_t near[] = {CompactWord::kLargestRunK, uint32_t{1} << 20, uint32_t{0xFFFF0000}};
    const uint32_t firstK = static_cast<uint32_t>(random() % 4 ? random() % 255 : near[random() % 3] - random() % 300);
    const size_t length = whole ? 1 : 1 + random() % 300;
    const double birth = births[random() % 5];
    // The canonical rule: a run ends before a k that is a multiple of 65536, and a run of
    // whole ids holds one module.
    runs += whole ? 1 : 1 + ((firstK + length - 1) >> 16) - (firstK >> 16);
    for (size_t j = 0; j < length; ++j) {
      const uint32_t label = static_cast<uint32_t>(random() % stateCounts.size());
      Expected module{label, whole ? IdKey::whole(key) : IdKey{key, firstK + static_cast<uint32_t>(j)}, birth, {}};
      for (uint32_t v = 0; v < stateCounts[label]; ++v) module.values.push_back(value += 1.0);
      word.append(label, module.key, birth, module.values.data());
      expected.push_back(std::move(module));
    }
  }
  word.finish();
  EXPECT_EQ(word.runCount(), runs);
  EXPECT_EQ(word.birthCount(), 5u);  // each found among the last 8 once all five are in
  expectWordReadsAs(word, expected);
}

TEST(CompactWord, MoreThan256LabelsTakeTwoBytes) {
  std::vector<uint32_t> stateCounts(300, 0);
  stateCounts[299] = 1;
  CompactWord word(stateCounts);
  EXPECT_TRUE(word.wideLabels());
  std::vector<Expected> expected;
  for (uint32_t label = 0; label < 300; ++label) {
    const double values[] = {42.0};
    word.append(label, IdKey::whole(label), 0.0, values);
    expected.push_back(
        {label, IdKey::whole(label), 0.0, label == 299 ? std::vector<double>{42.0} : std::vector<double>{}});
  }
  expectWordReadsAs(word, expected);
  EXPECT_EQ(word.labels16().size(), 300u);
  EXPECT_TRUE(word.labels8().empty());
}

TEST(CompactWord, TheBirthTableIsRenumberedOnceItOutgrowsTheRuns) {
  CompactWord old({0});
  for (uint32_t i = 0; i < 200; ++i) old.append(0, IdKey::whole(i), 0.5 * i, nullptr);
  old.finish();
  ASSERT_EQ(old.birthCount(), 200u);  // 200 runs: the table may keep them all

  // The next word copies three modules with their birth indices and adds two more, one
  // of them born at a time already in the table but too far back to be looked up.
  CompactWord next({0});
  next.clearWithBirthsOf(old);
  next.append(0, IdKey::whole(1000), old.birthIndex(5), nullptr);
  next.append(0, IdKey::whole(1001), old.birthIndex(199), nullptr);
  next.append(0, IdKey::whole(1002), old.birthIndex(5), nullptr);
  next.append(0, IdKey::whole(1003), 1.5, nullptr);  // = 0.5 * 3: appended again
  next.append(0, IdKey::whole(1004), 1234.0, nullptr);
  EXPECT_EQ(next.birthCount(), 202u);
  next.finish();
  // In order of first use, each value once.
  ASSERT_EQ(next.birthCount(), 4u);
  EXPECT_EQ(next.births()[0], 2.5);
  EXPECT_EQ(next.births()[1], 99.5);
  EXPECT_EQ(next.births()[2], 1.5);
  EXPECT_EQ(next.births()[3], 1234.0);
  expectWordReadsAs(next, {{0, IdKey::whole(1000), 2.5, {}},
                           {0, IdKey::whole(1001), 99.5, {}},
                           {0, IdKey::whole(1002), 2.5, {}},
                           {0, IdKey::whole(1003), 1.5, {}},
                           {0, IdKey::whole(1004), 1234.0, {}}});
}

// Koch's curve (F -> F+F-F-F+F) grown as the engine grows it: an F expiring at time t
// makes a run of 9 with the lineage mixKey(its id, keyOf(t)) and k = 1 .. 9; a sign never
// expires and keeps its id and birth. Labels: 0 F, 1 +, 2 -.
TEST(CompactWord, KochTakesAboutFourBytesAModule) {
  const uint32_t production[] = {0, 1, 0, 2, 0, 2, 0, 1, 0};
  CompactWord word({0, 0, 0}), next({0, 0, 0});
  std::vector<Expected> expected{{0, {mixKey(7, 0), 0}, 0.0, {}}}, expectedNext;
  word.append(0, expected[0].key, 0.0, nullptr);
  const int generations = 7;
  for (int n = 1; n <= generations; ++n) {
    const double when = n;
    next.clearWithBirthsOf(word);
    expectedNext.clear();
    for (CompactWordCursor cell = word.cursor(); !cell.done(); cell.next()) {
      if (cell.master() != 0) {
        next.append(cell.master(), cell.key(), cell.birthIndex(), nullptr);
        expectedNext.push_back({cell.master(), cell.key(), cell.birth(), {}});
        continue;
      }
      const uint64_t lineage = mixKey(cell.id(), keyOf(when));
      for (uint32_t k = 1; k <= 9; ++k) {
        next.append(production[k - 1], {lineage, k}, when, nullptr);
        expectedNext.push_back({production[k - 1], {lineage, k}, when, {}});
      }
    }
    next.finish();
    std::swap(word, next);
    std::swap(expected, expectedNext);
  }
  size_t fives = 1;
  for (int n = 1; n < generations; ++n) fives *= 5;
  ASSERT_EQ(word.size(), 2 * 5 * fives - 1);  // 2 * 5^n - 1 modules
  EXPECT_EQ(word.runCount(), 2 * fives - 1);  // a run per F of n - 1, and one per sign
  EXPECT_EQ(word.birthCount(), static_cast<size_t>(generations + 1));
  expectWordReadsAs(word, expected);
  // 1 label byte + 1/8 bitmap + 6/64 block index + 14 bytes per run of about 5 modules.
  const double perModule = static_cast<double>(word.bytes()) / static_cast<double>(word.size());
  EXPECT_LT(perModule, 4.03);
  EXPECT_GT(perModule, 4.0);
}

// A word written by slices reads as the word written serially, module for module,
// wherever the cuts fall: inside runs, inside one bitmap word, at its edges, and with
// slices shorter than a bitmap word or empty. Modules copied from the old word keep
// their birth indices; new ones add births.
TEST(CompactWord, AWordWrittenBySlicesReadsAsTheSerialOne) {
  const std::vector<uint32_t> stateCounts{0, 2, 1};
  CompactWord old(stateCounts);
  std::mt19937_64 random(7);
  double value = 0.0;
  // The old word: runs of 1 to 20, births 0 to 3, one in eight with ids past two bytes
  // of k (in the table of wide k, some crossing a multiple of 65536).
  while (old.size() < 5000) {
    const uint64_t key = random();
    const size_t length = 1 + random() % 20;
    const double birth = static_cast<double>(random() % 4);
    const uint32_t firstK = random() % 8 ? 0 : random() % 2 ? 65530 : (uint32_t{1} << 20) - 10;
    for (uint32_t k = 0; k < length; ++k) {
      const uint32_t label = static_cast<uint32_t>(random() % 3);
      const double values[] = {value += 1, value += 1};
      old.append(label, {key, firstK + k}, birth, values);
    }
  }
  EXPECT_GT(old.wideKCount(), 50u);
  old.finish();
  // The next word: label 1 expands into a run of 3 born at 4.0, or of 300 (ids past 254)
  // for one module in 500; the others are copied. Each module i of the old word makes
  // its successors through `emit`, so the serial writer and the slices see one sequence.
  auto emit = [&](size_t i, auto&& born, auto&& copied) {
    const CellView cell = old.cellAt(i);
    if (cell.master != 1) {
      const CompactWord::Place place = old.locate(i);
      copied(cell.master, old.keyOf(place.run, place.j), old.birthIndex(place.run), cell.state);
      return;
    }
    const uint64_t lineage = mixKey(cell.id, keyOf(4.0));
    const uint32_t successors = i % 500 == 7 ? 300 : 3;
    for (uint32_t k = 1; k <= successors; ++k) {
      const double values[] = {cell.state[0] + k, cell.state[1]};
      born(k == 2 ? 2u : 1u, IdKey{lineage, k}, 4.0, values);
    }
  };
  CompactWord serial(stateCounts);
  std::vector<Expected> expected;
  serial.clearWithBirthsOf(old);
  for (size_t i = 0; i < old.size(); ++i)
    emit(
        i,
        [&](uint32_t label, IdKey key, double birth, const double* values) {
          serial.append(label, key, birth, values);
          expected.push_back({label, key, birth, std::vector<double>(values, values + stateCounts[label])});
        },
        [&](uint32_t label, IdKey key, uint32_t birthIndex, const double* values) {
          serial.append(label, key, birthIndex, values);
          expected.push_back(
              {label, key, old.births()[birthIndex], std::vector<double>(values, values + stateCounts[label])});
        });
  serial.finish();
  expectWordReadsAs(serial, expected);

  const std::vector<std::vector<size_t>> cutsOfEachTry{
      {0, old.size()}, {0, 2500, old.size()}, {0, 1, 2, 63, 64, 65, 128, 129, 4000, 4000, old.size()}};
  // New successors appended with their key, or named by their event (the old module's
  // index) and given their lineage only when the slice writes, as the engine's pass does.
  for (const bool byEvent : {false, true})
    for (const std::vector<size_t>& cuts : cutsOfEachTry) {
      std::vector<CompactWord::Slice> slices(cuts.size() - 1, CompactWord::Slice(old));
      auto pass = [&](size_t s) {
        CompactWord::Slice& slice = slices[s];
        for (size_t i = cuts[s]; i < cuts[s + 1]; ++i)
          emit(
              i,
              [&](uint32_t label, IdKey key, double birth, const double* values) {
                if (byEvent)
                  slice.appendBorn(label, i, slice.writing() ? key.key : 0, key.k, birth, values);
                else
                  slice.append(label, key, birth, values);
              },
              [&](uint32_t label, IdKey key, uint32_t birthIndex, const double* values) {
                slice.appendCopy(label, key, birthIndex, values);
              });
        slice.finish();
      };
      CompactWord bySlices(stateCounts);
      bySlices.clearWithBirthsOf(old);
      for (size_t s = 0; s < slices.size(); ++s) pass(s);  // count
      bySlices.beginSlices(slices);
      for (size_t s = slices.size(); s-- > 0;) pass(s);  // write, in another order than counted
      bySlices.endSlices(slices);
      bySlices.finish();
      SCOPED_TRACE(std::to_string(cuts.size() - 1) + (byEvent ? " slices, new modules by event" : " slices"));
      expectWordReadsAs(bySlices, expected);
      EXPECT_LE(bySlices.runCount(), serial.runCount() + slices.size() - 1);
      EXPECT_GE(bySlices.runCount(), serial.runCount());
    }
}

// An event's new successors written as one run at once (CompactWord::appendRun serially,
// Slice::appendFreshRun by slices) read as the same successors written one by one, and
// encode alike: runs of 1 to 65,534 modules crossing bitmap words, with one-byte and
// two-byte labels, new runs beside copied ones.
TEST(CompactWord, AnEventsRunWrittenAtOnceReadsAsItsModulesOneByOne) {
  for (const size_t labelCount : {size_t{3}, size_t{300}}) {
    SCOPED_TRACE(std::to_string(labelCount) + " labels");
    const std::vector<uint32_t> stateCounts(labelCount, 0);
    CompactWord old(stateCounts);
    std::mt19937_64 random(11);
    while (old.size() < 6000) {
      const uint64_t key = random();
      const size_t length = 1 + random() % 20;
      const double birth = static_cast<double>(random() % 4);
      for (uint32_t k = 0; k < length; ++k) old.append(random() % labelCount, {key, k}, birth, nullptr);
    }
    old.finish();
    // Module i of the old word with a label of 1 modulo 3 fires: n(i) successors, labels
    // from its index; the others are copied.
    // Runs of 1 to 300, and a few as long as a run goes.
    auto successorsOf = [&](size_t i) {
      std::vector<uint32_t> labels(i % 1500 == 4 ? CompactWord::kLargestRunK : 1 + (i * 37) % 300);
      for (size_t k = 0; k < labels.size(); ++k) labels[k] = static_cast<uint32_t>((i + 5 * k) % labelCount);
      return labels;
    };
    auto fires = [&](size_t i) { return old.label(i) % 3 == 1; };
    auto lineageOf = [&](size_t i) { return mixKey(old.cellAt(i).id, keyOf(4.0)); };
    auto copy = [&](size_t i, auto& out) {
      const CompactWord::Place place = old.locate(i);
      out.appendCopy(old.label(i), old.keyOf(place.run, place.j), old.birthIndex(place.run), nullptr);
    };
    struct SerialCopy {
      CompactWord& word;
      void appendCopy(uint32_t label, IdKey key, uint32_t birthIndex, const double*) {
        word.append(label, key, birthIndex, nullptr);
      }
    };

    CompactWord oneByOne(stateCounts), atOnce(stateCounts);
    oneByOne.clearWithBirthsOf(old);
    atOnce.clearWithBirthsOf(old);
    std::vector<Expected> expected;
    SerialCopy toOneByOne{oneByOne}, toAtOnce{atOnce};
    for (size_t i = 0; i < old.size(); ++i) {
      if (!fires(i)) {
        copy(i, toOneByOne);
        copy(i, toAtOnce);
        const CellView cell = old.cellAt(i);
        expected.push_back({cell.master, IdKey::whole(cell.id), cell.birth, {}});
        continue;
      }
      const std::vector<uint32_t> labels = successorsOf(i);
      const uint64_t lineage = lineageOf(i);
      for (uint32_t k = 1; k <= labels.size(); ++k) {
        oneByOne.append(labels[k - 1], IdKey{lineage, k}, 4.0, nullptr);
        expected.push_back({labels[k - 1], IdKey{lineage, k}, 4.0, {}});
      }
      atOnce.appendRun(labels.data(), static_cast<uint32_t>(labels.size()), lineage, atOnce.birthIndexOf(4.0));
    }
    oneByOne.finish();
    atOnce.finish();
    expectWordReadsAs(oneByOne, expected);
    expectWordReadsAs(atOnce, expected);
    EXPECT_EQ(atOnce.runCount(), oneByOne.runCount());
    EXPECT_GT(atOnce.size(), 100 * CompactWord::kBlock);

    const std::vector<size_t> cuts{0, 1, 63, 64, 65, 130, 3001, old.size()};
    std::vector<size_t> runs;
    for (const bool byRun : {false, true}) {
      SCOPED_TRACE(byRun ? "slices, runs at once" : "slices, one by one");
      std::vector<CompactWord::Slice> slices(cuts.size() - 1, CompactWord::Slice(old));
      auto pass = [&](size_t s) {
        CompactWord::Slice& slice = slices[s];
        for (size_t i = cuts[s]; i < cuts[s + 1]; ++i) {
          if (!fires(i)) {
            copy(i, slice);
            continue;
          }
          const std::vector<uint32_t> labels = successorsOf(i);
          const uint64_t lineage = slice.writing() ? lineageOf(i) : 0;
          if (byRun)
            slice.appendFreshRun(labels.data(), static_cast<uint32_t>(labels.size()), i, lineage, 4.0);
          else
            for (uint32_t k = 1; k <= labels.size(); ++k) slice.appendBorn(labels[k - 1], i, lineage, k, 4.0, nullptr);
        }
        slice.finish();
      };
      CompactWord bySlices(stateCounts);
      bySlices.clearWithBirthsOf(old);
      for (size_t s = 0; s < slices.size(); ++s) pass(s);
      bySlices.beginSlices(slices);
      for (size_t s = slices.size(); s-- > 0;) pass(s);
      bySlices.endSlices(slices);
      bySlices.finish();
      expectWordReadsAs(bySlices, expected);
      runs.push_back(bySlices.runCount());
    }
    EXPECT_EQ(runs[0], runs[1]);
  }
}

// Parts of a word written each on its own (as the slices of a rewrite whose choices vary)
// and joined with appendWord read as the word written in one piece: cuts anywhere in a
// bitmap word, on its edges, parts shorter than a block or empty, runs as long as a run
// goes crossing blocks; births the parts add themselves are found in the table.
TEST(CompactWord, PartsJoinedReadAsTheWordWrittenInOnePiece) {
  const std::vector<uint32_t> stateCounts{0, 0, 0};
  CompactWord old(stateCounts);
  std::mt19937_64 random(5);
  while (old.size() < 9000) {
    const uint64_t key = random();
    const size_t length = random() % 50 == 0 ? 3000 : 1 + random() % 20;
    const double birth = static_cast<double>(random() % 4);
    const uint32_t firstK = random() % 4 ? 0 : 65530;  // some in the table of wide k
    for (uint32_t k = 0; k < length; ++k) old.append(random() % 3, {key, firstK + k}, birth, nullptr);
  }
  old.finish();
  // Module i: copied, or renewed at a birth of its own (5 + i % 3), or, for label 2, a run
  // of 1 to 100 new successors born at 4.
  auto emit = [&](size_t i, CompactWord& to, std::vector<Expected>* expected) {
    const CompactWord::Place place = old.locate(i);
    const IdKey key = old.keyOf(place.run, place.j);
    const uint32_t label = old.label(i);
    if (label == 0) {
      to.append(label, key, old.birthIndex(place.run), nullptr);
      if (expected) expected->push_back({label, key, old.birthOf(place.run), {}});
    } else if (label == 1) {
      const double birth = 5.0 + static_cast<double>(i % 3);
      to.append(label, key, birth, nullptr);
      if (expected) expected->push_back({label, key, birth, {}});
    } else {
      const uint64_t lineage = mixKey(key.id(), keyOf(4.0));
      for (uint32_t k = 1; k <= 1 + i % 100; ++k) {
        to.append(static_cast<uint32_t>(k % 3), {lineage, k}, 4.0, nullptr);
        if (expected) expected->push_back({k % 3, {lineage, k}, 4.0, {}});
      }
    }
  };
  std::vector<Expected> expected;
  CompactWord whole(stateCounts);
  whole.clearWithBirthsOf(old);
  for (size_t i = 0; i < old.size(); ++i) emit(i, whole, &expected);
  whole.finish();
  expectWordReadsAs(whole, expected);

  const std::vector<std::vector<size_t>> cutsOfEachTry{
      {0, old.size()}, {0, 4500, old.size()}, {0, 1, 2, 63, 64, 64, 65, 128, 191, 1000, 7000, old.size()}};
  for (const std::vector<size_t>& cuts : cutsOfEachTry) {
    SCOPED_TRACE(std::to_string(cuts.size() - 1) + " parts");
    CompactWord joined(stateCounts);
    joined.clearWithBirthsOf(old);
    size_t runs = 0;
    for (size_t s = 0; s + 1 < cuts.size(); ++s) {
      CompactWord part(stateCounts);
      part.clearWithBirthsOf(old);
      for (size_t i = cuts[s]; i < cuts[s + 1]; ++i) emit(i, part, nullptr);
      runs += part.runCount();
      joined.appendWord(part, old.birthCount());
    }
    joined.finish();
    expectWordReadsAs(joined, expected);
    EXPECT_EQ(joined.runCount(), runs);
    EXPECT_LE(joined.runCount(), whole.runCount() + cuts.size() - 2);
    EXPECT_LE(joined.birthCount(), old.birthCount() + 4);  // 4.0 to 7.0, each added once

    // The same parts placed at once and copied in reverse order, as threads may copy
    // them, after a first part written into the word itself (the engine's first thread).
    CompactWord atOnce(stateCounts);
    atOnce.clearWithBirthsOf(old);
    for (size_t i = cuts[0]; i < cuts[1]; ++i) emit(i, atOnce, nullptr);
    std::vector<CompactWord> parts;
    for (size_t s = 1; s + 1 < cuts.size(); ++s) {
      parts.emplace_back(stateCounts);
      parts.back().clearWithBirthsOf(old);
      for (size_t i = cuts[s]; i < cuts[s + 1]; ++i) emit(i, parts.back(), nullptr);
    }
    std::vector<CompactWord::PartPlace> places(parts.size());
    for (size_t p = 0; p < parts.size(); ++p) places[p].part = &parts[p];
    atOnce.placeParts(places, old.birthCount());
    for (size_t p = places.size(); p-- > 0;) atOnce.copyPart(places[p], old.birthCount());
    atOnce.endParts(places);
    atOnce.finish();
    expectWordReadsAs(atOnce, expected);
    EXPECT_EQ(atOnce.runCount(), runs);
  }
}

}  // namespace
}  // namespace ontogen
