// The cursor (pools/cell_cursor.h) gives each cell as it was appended, in pool order, and
// agrees with Pool::cellAt; and no reader outside pools/ and core/ sees the record type,
// so the linear pool can change how it stores its words (docs/COMPACT_WORDS.md).

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "pools/linear_pool.h"
#include "pools/spatial_pool.h"

namespace ontogen {
namespace {

struct Appended {
  uint32_t master;
  double birth;
  uint64_t id;
  std::vector<double> state;
};

// Cells with no, one and three values, births that are not whole seconds and ids that
// use all 64 bits.
const std::vector<Appended> kCells = {
    {2, 0.0, 0x8000000000000001ull, {}},
    {0, 0.04, 42, {1.5}},
    {1, -0.25, 0xfedcba9876543210ull, {-0.0, 3e-300, 7}},
    {2, 4.04, 7, {}},
    {0, 1e9, 0, {0.1}},
};

void fill(Pool& pool) {
  for (const Appended& cell : kCells)
    pool.append({.master = cell.master, .birth = cell.birth, .id = cell.id}, cell.state.data(),
                static_cast<uint32_t>(cell.state.size()));
}

void expectCell(const CellView& view, const Appended& cell, size_t index) {
  EXPECT_EQ(view.index, index);
  EXPECT_EQ(view.master, cell.master) << "cell " << index;
  EXPECT_EQ(std::bit_cast<uint64_t>(view.birth), std::bit_cast<uint64_t>(cell.birth)) << "cell " << index;
  EXPECT_EQ(view.id, cell.id) << "cell " << index;
  for (size_t k = 0; k < cell.state.size(); ++k)
    EXPECT_EQ(std::bit_cast<uint64_t>(view.state[k]), std::bit_cast<uint64_t>(cell.state[k]))
        << "cell " << index << ", value " << k;
}

void expectWalk(const Pool& pool) {
  ASSERT_EQ(pool.size(), kCells.size());
  size_t index = 0;
  CellCursor cursor = pool.cursor();
  EXPECT_EQ(cursor.size(), kCells.size());
  for (; !cursor.done(); cursor.next(), ++index) {
    ASSERT_LT(index, kCells.size());
    EXPECT_EQ(cursor.index(), index);
    EXPECT_EQ(cursor.master(), kCells[index].master);
    EXPECT_EQ(cursor.id(), kCells[index].id);
    EXPECT_EQ(std::bit_cast<uint64_t>(cursor.birth()), std::bit_cast<uint64_t>(kCells[index].birth));
    expectCell(cursor.view(), kCells[index], index);
    expectCell(pool.cellAt(index), kCells[index], index);
    // The offset reads the cell's values out of the state array, as integrators do.
    EXPECT_EQ(cursor.stateOffset(), pool.stateOffset(index));
    EXPECT_EQ(pool.stateArena().data() + pool.stateOffset(index), cursor.state());
  }
  EXPECT_EQ(index, kCells.size());
  // Offsets are those of the values appended before: 0, 0, 1, 4, 4.
  const std::vector<size_t> offsets = {0, 0, 1, 4, 4};
  for (size_t i = 0; i < offsets.size(); ++i) EXPECT_EQ(pool.stateOffset(i), offsets[i]) << "cell " << i;
  // A cursor for a chunk starts at its first cell and walks to the end.
  for (size_t first = 0; first <= kCells.size(); ++first) {
    CellCursor chunk = pool.cursor(first);
    for (size_t i = first; i < kCells.size(); ++i, chunk.next()) {
      ASSERT_FALSE(chunk.done()) << "from " << first;
      expectCell(chunk.view(), kCells[i], i);
    }
    EXPECT_TRUE(chunk.done()) << "from " << first;
  }
}

TEST(CellCursor, WalksALinearPoolInOrder) {
  LinearPool pool;
  fill(pool);
  expectWalk(pool);
}

TEST(CellCursor, WalksASpatialPoolInOrder) {
  SpatialPool pool;
  fill(pool);
  expectWalk(pool);
}

TEST(CellCursor, AnEmptyPoolIsDoneAtOnce) {
  LinearPool pool;
  EXPECT_TRUE(pool.cursor().done());
  EXPECT_EQ(pool.cursor().size(), 0u);
}

// A pool that counts its values (Pool::countValues, the linear pool's words) finds them by
// the masters' value counts: a running sum in cursors, a per-block offset for random
// access. The records' offsets are overwritten here, so a reader that still used them
// would read other values.
TEST(CellCursor, APoolThatCountsItsValuesNeverReadsTheRecordsOffsets) {
  // kCells' masters have 1, 3 and 0 values: 60 copies make 300 cells over five blocks
  // of 64, appended one by one (as an axiom is) or swapped in (as a new word is).
  const std::vector<uint32_t> counts = {1, 3, 0};
  std::vector<Appended> cells;
  std::vector<size_t> offsets;
  size_t total = 0;
  for (int copy = 0; copy < 60; ++copy)
    for (Appended cell : kCells) {
      for (double& value : cell.state) value += copy;
      offsets.push_back(total);
      total += cell.state.size();
      cells.push_back(cell);
    }
  LinearPool appended;
  appended.countValues(counts);
  for (const Appended& cell : cells)
    appended.append({.master = cell.master, .birth = cell.birth, .id = cell.id}, cell.state.data(),
                    static_cast<uint32_t>(cell.state.size()));
  LinearPool swapped;
  swapped.countValues(counts);
  CellArray records;
  StateArray values;
  for (const Appended& cell : cells) {
    records.push_back({.master = cell.master, .state = 0, .birth = cell.birth, .id = cell.id});
    values.insert(values.end(), cell.state.begin(), cell.state.end());
  }
  swapped.swapContents(records, values);

  for (LinearPool* pool : {&appended, &swapped}) {
    for (CellRecord& record : pool->cells()) record.state = 0x7fffffff;
    size_t index = 0;
    for (CellCursor cursor = pool->cursor(); !cursor.done(); cursor.next(), ++index) {
      ASSERT_LT(index, cells.size());
      EXPECT_EQ(cursor.stateOffset(), offsets[index]) << "cell " << index;
      expectCell(cursor.view(), cells[index], index);
      expectCell(pool->cellAt(index), cells[index], index);
      EXPECT_EQ(pool->stateOffset(index), offsets[index]) << "cell " << index;
    }
    EXPECT_EQ(index, cells.size());
    for (size_t first : {0, 1, 63, 64, 65, 127, 128, 200, 299}) {
      CellCursor chunk = pool->cursor(first);
      for (size_t i = first; i < cells.size(); ++i, chunk.next()) expectCell(chunk.view(), cells[i], i);
      EXPECT_TRUE(chunk.done());
    }
    EXPECT_TRUE(pool->cursor(cells.size()).done());
    // From a neighbour whose offset is known, on either side, near and far.
    for (auto [i, from] : std::vector<std::pair<size_t, size_t>>{
             {10, 9}, {9, 10}, {64, 63}, {63, 64}, {130, 128}, {128, 131}, {70, 5}, {5, 200}, {299, 0}})
      EXPECT_EQ(pool->stateOffsetNear(i, from, offsets[from]), offsets[i]) << i << " from " << from;
  }
}

TEST(CellCursor, APoolWithoutValuesHasThemAllAtZero) {
  LinearPool pool;
  pool.countValues({0, 0, 0});
  for (int k = 0; k < 100; ++k) pool.append({.master = static_cast<uint32_t>(k % 3), .id = 1}, nullptr, 0);
  for (CellRecord& record : pool.cells()) record.state = 0x7fffffff;
  for (CellCursor cursor = pool.cursor(); !cursor.done(); cursor.next())
    EXPECT_EQ(cursor.stateOffset(), 0u) << "cell " << cursor.index();
  EXPECT_EQ(pool.stateOffset(99), 0u);
  EXPECT_EQ(pool.cursor(50).stateOffset(), 0u);
}

// interpreters/, apps/ and bench/ read cells through the cursor and cellAt only: none
// of their sources names the record, the record array or a record's state offset.
TEST(CellCursor, NoReaderOutsidePoolsAndCoreSeesTheRecord) {
  namespace fs = std::filesystem;
  const fs::path root = ONTOGEN_SOURCE_DIR;
  size_t files = 0;
  for (const char* folder : {"interpreters", "apps", "bench"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
      const std::string extension = entry.path().extension().string();
      if (!entry.is_regular_file() || (extension != ".h" && extension != ".cpp")) continue;
      ++files;
      std::ifstream in(entry.path(), std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      for (const char* name : {"CellRecord", ".cells()", "stateOf("})
        EXPECT_EQ(text.str().find(name), std::string::npos)
            << fs::relative(entry.path(), root).string() << " uses " << name << "; read cells with Pool::cursor()";
    }
  }
  EXPECT_GT(files, 100u) << "the sources were not found under " << root;
}

}  // namespace
}  // namespace ontogen
