// The linear pool alone holds a compact word (pools/linear_pool.h): a copy of a pool that
// holds one reads its own copy of the word, whatever becomes of the pool it was copied
// from; grid and spatial pools have no way to hold one.

#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <memory>
#include <vector>

#include "pools/grid_pool.h"
#include "pools/linear_pool.h"
#include "pools/spatial_pool.h"

namespace ontogen {
namespace {

// Only the linear pool takes a compact word in.
template <class P>
constexpr bool takesCompactWords = requires(P& pool, CompactWord& word) { pool.swapCompactWord(word); };
static_assert(takesCompactWords<LinearPool>);
static_assert(!takesCompactWords<Pool>);
static_assert(!takesCompactWords<GridPool>);
static_assert(!takesCompactWords<SpatialPool>);

struct Cell {
  uint32_t master;
  double birth;
  uint64_t id;
  double value;  // master 1 holds one value, master 0 none
};

const std::vector<Cell> kCells = {{0, 0.0, 11, 0}, {1, 0.5, 0x8000000000000003ull, -2.25}, {0, 1.0, 13, 0},
                                  {1, 1.5, 14, 1e300}};

void fill(LinearPool& pool) {
  pool.countValues({0, 1});
  for (const Cell& cell : kCells)
    pool.append({.master = cell.master, .birth = cell.birth, .id = cell.id}, &cell.value, cell.master);
}

void expectTheCells(const Pool& pool, const char* what) {
  SCOPED_TRACE(what);
  ASSERT_TRUE(pool.holdsCompactWord());
  ASSERT_EQ(pool.size(), kCells.size());
  size_t i = 0;
  for (CellCursor cell = pool.cursor(); !cell.done(); cell.next(), ++i) {
    EXPECT_EQ(cell.master(), kCells[i].master) << i;
    EXPECT_EQ(std::bit_cast<uint64_t>(cell.birth()), std::bit_cast<uint64_t>(kCells[i].birth)) << i;
    EXPECT_EQ(cell.id(), kCells[i].id) << i;
    if (kCells[i].master == 1) {
      EXPECT_EQ(cell.state()[0], kCells[i].value) << i;
    }
  }
  EXPECT_EQ(pool.stateArena().size(), 2u);
}

TEST(LinearPool, ACopyOfAPoolHoldingACompactWordReadsItsOwnWord) {
  LinearPool pool;
  fill(pool);
  pool.storeCompactWord(7);
  expectTheCells(pool, "the pool");
  const LinearPool copied(pool);
  const std::unique_ptr<Pool> cloned = pool.clone();
  LinearPool assigned;
  fill(assigned);
  assigned = pool;

  // The pool copied from takes another word, then goes back to records and is emptied:
  // the copies keep theirs.
  CompactWord other = pool.emptyCompactWord();
  const double value = 4;
  other.append(1, IdKey::whole(99), 2.0, &value);
  other.finish();
  pool.swapCompactWord(other);
  ASSERT_EQ(pool.size(), 1u);
  expectTheCells(copied, "copied");
  expectTheCells(*cloned, "cloned");
  expectTheCells(assigned, "assigned");
  pool.storeRecords();
  EXPECT_FALSE(pool.holdsCompactWord());
  ASSERT_EQ(pool.size(), 1u);
  EXPECT_EQ(pool.cells()[0].id, 99u);
  pool.clear();
  expectTheCells(copied, "copied, the pool cleared");
  expectTheCells(assigned, "assigned, the pool cleared");
}

TEST(LinearPool, GoingBackToRecordsKeepsEveryCell) {
  LinearPool pool;
  fill(pool);
  pool.storeCompactWord(7);
  pool.storeRecords();
  EXPECT_FALSE(pool.holdsCompactWord());
  EXPECT_TRUE(pool.holdsIds());
  ASSERT_EQ(pool.cells().size(), kCells.size());
  for (size_t i = 0; i < kCells.size(); ++i) EXPECT_EQ(pool.cells()[i].id, kCells[i].id) << i;
}

}  // namespace
}  // namespace ontogen
