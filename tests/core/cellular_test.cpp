// The cellular model: grid pools with aggregates and actions, `rate` against analytic
// solutions, conservation, and thread-count independence.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "core/world.h"
#include "test_support.h"

namespace ontogen {
namespace {

using testing_support::compileOrFail;
using Cells = std::set<std::pair<int, int>>;

// Live cells of a Life grid: state `alive` == 1, or the label "Live".
Cells liveCells(const World& world) {
  Cells live;
  const GridPool& grid = world.gridPool();
  for (size_t i = 0; i < grid.size(); ++i) {
    const CellRecord& cell = grid.cells()[i];
    const MasterCell& master = world.program().masters[cell.master];
    bool alive = master.label == "Live" || (master.stateCount() == 1 && *grid.stateOf(cell) == 1.0);
    if (!alive) continue;
    GridCoordinates c = grid.coordinates(grid.siteOf(i));
    live.insert({static_cast<int>(c[0]), static_cast<int>(c[1])});
  }
  return live;
}

Cells shifted(const Cells& cells, int dx, int dy, int n) {
  Cells out;
  for (auto [x, y] : cells) out.insert({((x + dx) % n + n) % n, ((y + dy) % n + n) % n});
  return out;
}

const char* kLifeByState = R"(
cell C(alive = 0) {
  rules { alive = if(sum(alive) == 3 || (alive == 1 && sum(alive) == 2), 1, 0); }
}
system life {
  pool grid(8, 8) wrap moore;
  fill C(0);
  at(1, 0) C(1); at(2, 1) C(1); at(0, 2) C(1); at(1, 2) C(1); at(2, 2) C(1);
}
)";

// The same automaton with labels and replace actions instead of a state variable.
const char* kLifeByLabel = R"(
cell Live { rules { count(Live) < 2 || count(Live) > 3 : -> Dead; } }
cell Dead { rules { count(Live) == 3 : -> Live; } }
system life {
  pool grid(8, 8) wrap moore;
  fill Dead;
  at(1, 0) Live; at(2, 1) Live; at(0, 2) Live; at(1, 2) Live; at(2, 2) Live;
}
)";

TEST(Cellular, GliderMovesOneCellDiagonallyEveryFourSteps) {
  for (const char* text : {kLifeByState, kLifeByLabel}) {
    World world(compileOrFail(text));
    const Cells start = liveCells(world);
    ASSERT_EQ(start.size(), 5u);
    for (int step = 1; step <= 3; ++step) {
      world.advanceTo(step, 1);
      EXPECT_EQ(liveCells(world).size(), 5u) << "a glider has five cells in every phase";
      EXPECT_NE(liveCells(world), shifted(start, 1, 1, 8)) << "step " << step;
    }
    world.advanceTo(4, 1);
    EXPECT_EQ(liveCells(world), shifted(start, 1, 1, 8));
    world.advanceTo(32, 1);  // eight periods: once around the torus
    EXPECT_EQ(liveCells(world), start);
    EXPECT_EQ(world.gridPool().size(), 64u) << "every site keeps a cell";
  }
}

TEST(Cellular, AggregatesAtCornersFollowTheBoundary) {
  // Each cell counts its neighbours and sums their `v` (its own site number + 1).
  auto run = [](const std::string& options) {
    std::string text =
        "cell C(v = 0, n = 0, s = 0, lo = 0, hi = 0, m = 0) { rules { "
        "n = count(), s = sum(v), lo = min(v), hi = max(v), m = mean(C.v); } }\n"
        "system g { pool grid(3, 3) " +
        options + "; fill C(1 + me.x + 3 * me.y); }";
    World world(compileOrFail(text));
    world.advanceTo(1, 1);
    const GridPool& grid = world.gridPool();
    const double* corner = grid.stateOf(grid.cells()[0]);  // site (0, 0), v = 1
    const double* centre = grid.stateOf(grid.cells()[4]);  // site (1, 1), v = 5
    return std::make_pair(std::vector<double>(corner + 1, corner + 6), std::vector<double>(centre + 1, centre + 6));
  };
  auto [closedCorner, closedCentre] = run("closed vonneumann");
  EXPECT_EQ(closedCorner, (std::vector<double>{2, 2 + 4, 2, 4, 3}));
  EXPECT_EQ(closedCentre, (std::vector<double>{4, 2 + 4 + 6 + 8, 2, 8, 5}));
  auto [wrapCorner, wrapCentre] = run("wrap vonneumann");
  // (0,0) wraps to (0,2) v=7, (2,0) v=3, (1,0) v=2, (0,1) v=4.
  EXPECT_EQ(wrapCorner, (std::vector<double>{4, 7 + 3 + 2 + 4, 2, 7, 4}));
  auto [clampCorner, clampCentre] = run("clamp vonneumann");
  // Outside neighbours are the corner itself: v=1 twice, plus 2 and 4.
  EXPECT_EQ(clampCorner, (std::vector<double>{4, 1 + 1 + 2 + 4, 1, 4, 2}));
  auto [mooreCorner, mooreCentre] = run("closed moore");
  EXPECT_EQ(mooreCorner, (std::vector<double>{3, 2 + 4 + 5, 2, 5, 11.0 / 3}));
  EXPECT_EQ(mooreCentre, (std::vector<double>{8, 45 - 5, 1, 9, 5}));
}

TEST(Cellular, DeleteEmptiesAndAddFillsNeighbouringSites) {
  // A seed in the middle of a closed 5x5 grid: each step it keeps itself and adds a
  // Spore into the first free von Neumann site (north, west, east, south).
  auto program = compileOrFail(R"(
cell Seed { rules { -> me Spore; } }
cell Spore { rules { age >= 1 : -> ; } }
system g { pool grid(5, 5) closed vonneumann; at(2, 2) Seed; }
)");
  World world(program);
  world.advanceTo(1, 1);
  const GridPool& grid = world.gridPool();
  ASSERT_EQ(grid.size(), 2u);
  EXPECT_NE(grid.cellAt(grid.siteAt({2, 1, 0})), GridPool::kEmpty) << "north first";
  world.advanceTo(2, 1);
  // The first spore (age 1) is deleted; its site frees only at the end of the step,
  // so the new spore goes west.
  EXPECT_EQ(grid.cellAt(grid.siteAt({2, 1, 0})), GridPool::kEmpty);
  EXPECT_NE(grid.cellAt(grid.siteAt({1, 2, 0})), GridPool::kEmpty);
  EXPECT_EQ(grid.size(), 2u);
}

double decayError(double dt) {
  auto program = compileOrFail("cell A(x = 1) { rules { rate(x) = -x; } }\nsystem s { pool linear; axiom A; }");
  World world(program);
  world.advanceTo(2, dt);
  return std::abs(*world.rootPool().stateOf(world.rootPool().cells()[0]) - std::exp(-2.0));
}

TEST(Rate, ExponentialDecayConvergesAtFourthOrder) {
  const double e1 = decayError(0.2), e2 = decayError(0.1), e3 = decayError(0.05);
  EXPECT_LT(e1, 1e-4);
  // Halving the step divides RK4's error by about 2^4 = 16.
  EXPECT_NEAR(e1 / e2, 16.0, 1.5);
  EXPECT_NEAR(e2 / e3, 16.0, 1.5);
}

TEST(Rate, LogisticGrowthMatchesTheClosedForm) {
  auto program = compileOrFail(
      "#define r 1.5\n#define K 10\ncell A(x = 0.5) { rules { rate(x) = r * x * (1 - x / K); } }\n"
      "system s { pool linear; axiom A; }");
  World world(program);
  world.advanceTo(4, 0.05);
  const double exact = 10.0 / (1 + (10.0 / 0.5 - 1) * std::exp(-1.5 * 4));
  EXPECT_NEAR(*world.rootPool().stateOf(world.rootPool().cells()[0]), exact, 1e-6);
}

TEST(Rate, AdaptiveToleranceIsMet) {
  auto program =
      compileOrFail("#tolerance 1e-9\ncell A(x = 1) { rules { rate(x) = -x; } }\nsystem s { pool linear; axiom A; }");
  World world(program);
  world.advanceTo(2, 1);  // two world steps, many integrator steps
  EXPECT_NEAR(*world.rootPool().stateOf(world.rootPool().cells()[0]), std::exp(-2.0), 1e-7);
}

TEST(Rate, PredicateSwitchesTheEquationPerStep) {
  // Grows at rate 1 while x < 1, then stops: with dt = 0.25 it crosses 1 at t = 1.
  auto program = compileOrFail("cell A(x = 0) { rules { x < 1 : rate(x) = 1; } }\nsystem s { pool linear; axiom A; }");
  World world(program);
  world.advanceTo(3, 0.25);
  EXPECT_DOUBLE_EQ(*world.rootPool().stateOf(world.rootPool().cells()[0]), 1.0);
}

const char* kDiffusion = R"(
#define D 0.2
cell U(u = 0) { rules { rate(u) = D * (sum(u) - count() * u); } }
system plate {
  pool grid(20, 20) closed vonneumann;
  fill U(if(me.x == 3 && me.y == 4, 100, 0) + uniform(0, 1));
}
)";

double totalMass(const World& world) {
  double mass = 0;
  for (const CellRecord& cell : world.rootPool().cells()) mass += *world.rootPool().stateOf(cell);
  return mass;
}

TEST(Rate, DiffusionConservesMassOnAClosedGrid) {
  World world(compileOrFail(kDiffusion));
  const double before = totalMass(world);
  world.advanceTo(50, 0.5);
  EXPECT_NEAR(totalMass(world), before, 1e-9 * before);
  // And it diffused: the peak spread out.
  double peak = 0;
  for (const CellRecord& cell : world.rootPool().cells()) peak = std::max(peak, *world.rootPool().stateOf(cell));
  EXPECT_LT(peak, 10);
}

TEST(Threads, OneThreadAndManyGiveTheSameBits) {
  // Big enough that the loops split: 100 x 100 sites.
  std::string text = kDiffusion;
  text.replace(text.find("grid(20, 20)"), 12, "grid(100, 100)");
  text += "cell V(v = 0) { rules { v > 0.5 : -> me V(v / 2); rate(v) = -v + sum(v) * 0.01; } }\n";
  auto program = compileOrFail(text);
  auto run = [&](unsigned threads) {
    WorldDef def;
    def.threads = threads;
    def.seed = 7;
    World world(program, def);
    world.advanceTo(10, 0.5);
    auto state = world.rootPool().stateArena();
    return std::vector<double>(state.begin(), state.end());
  };
  const auto one = run(1);
  EXPECT_EQ(run(2), one);
  EXPECT_EQ(run(3), one);
}

TEST(Cellular, ContextThatDoesNotFitTheGridIsAnError) {
  DiagnosticSink sink;
  auto program = compileSource("t.cell",
                               "cell A(x = 0) { rules { A(y) me A(z) : x = y + z; } }\n"
                               "system g { pool grid(4, 4); fill A; }",
                               sink);
  EXPECT_EQ(program, nullptr);
  EXPECT_NE(formatDiagnostics(sink).find("1 dimension"), std::string::npos) << formatDiagnostics(sink);
}

}  // namespace
}  // namespace ontogen

namespace ontogen {
namespace {

// Heterocysts inhibit differentiation around them through a diffusing, decaying
// inhibitor, so they end up regularly spaced: about 11 vegetative cells apart.
TEST(Models, HeterocystSpacingFallsInRange) {
  auto program = testing_support::compileModel("heterocysts.cell");
  for (uint64_t seed : {1, 2, 3}) {
    WorldDef def;
    def.seed = seed;
    World world(program, def);
    world.advanceTo(60, program->dt);
    const Pool& pool = world.rootPool();
    std::vector<size_t> heterocysts;
    for (size_t i = 0; i < pool.size(); ++i)
      if (world.program().masters[pool.cells()[i].master].label == "H") heterocysts.push_back(i);
    ASSERT_GT(heterocysts.size(), 50u) << "seed " << seed << ": the filament grew to " << pool.size() << " cells";
    std::vector<double> gaps;
    size_t close = 0;
    for (size_t k = 1; k < heterocysts.size(); ++k) {
      gaps.push_back(static_cast<double>(heterocysts[k] - heterocysts[k - 1] - 1));
      close += gaps.back() < 3;
    }
    double mean = 0;
    for (double gap : gaps) mean += gap / gaps.size();
    std::sort(gaps.begin(), gaps.end());
    EXPECT_GE(mean, 8) << "seed " << seed;
    EXPECT_LE(mean, 15) << "seed " << seed;
    EXPECT_GE(gaps[gaps.size() / 2], 9) << "median, seed " << seed;
    EXPECT_LE(gaps[gaps.size() / 2], 15) << "median, seed " << seed;
    EXPECT_LT(close, gaps.size() * 15 / 100) << "gaps under 3 cells, seed " << seed;
  }
}

// Paper 002, eq. (2): averaging neighbours settles into a straight ramp between the
// fixed ends (1 at the left, the last cell above kmin at the right).
TEST(Models, FilamentDiffusionSettlesToARamp) {
  auto program = testing_support::compileModel("diffusion.cell");
  World world(program);
  world.advanceTo(400, 1);
  const Pool& pool = world.rootPool();
  ASSERT_EQ(pool.size(), 20u);
  for (size_t i = 0; i <= 18; ++i)
    EXPECT_NEAR(*pool.stateOf(pool.cells()[i]), 1.0 - i * 0.99 / 18, 2e-3) << "cell " << i;
  EXPECT_EQ(*pool.stateOf(pool.cells()[19]), 0.0);
}

}  // namespace
}  // namespace ontogen

namespace ontogen {
namespace {

// Cells divide and push apart in a spatial pool; a crowded cell stops dividing.
TEST(Models, ColonySpreadsAsADiscAndKeepsItsDensity) {
  auto program = testing_support::compileModel("colony.cell");
  auto grow = [&](unsigned threads) {
    WorldDef def;
    def.threads = threads;
    World world(program, def);
    world.advanceTo(40, program->dt);
    return world;
  };
  World world = grow(1);
  const SpatialPool& pool = world.spatialPool();
  ASSERT_GT(pool.size(), 1000u);
  ASSERT_LT(pool.size(), 20000u);
  // Spread: the colony's extent grows like the square root of its cell count.
  double extent = 0, sumX = 0, sumY = 0;
  for (size_t i = 0; i < pool.size(); ++i) {
    auto p = pool.positionOf(i);
    extent = std::max(extent, std::hypot(p[0], p[1]));
    sumX += p[0];
    sumY += p[1];
  }
  const double n = static_cast<double>(pool.size());
  EXPECT_GT(extent, 0.3 * std::sqrt(n)) << "cells spread out";
  EXPECT_LT(std::hypot(sumX / n, sumY / n), 0.2 * extent) << "a disc around the first cell";
  // Density: the mean number of neighbours within R stays near the crowd limit of 5.
  std::vector<uint32_t> around;
  double neighbours = 0;
  for (size_t i = 0; i < pool.size(); ++i) {
    pool.neighbours(i, around);
    neighbours += static_cast<double>(around.size()) / n;
  }
  EXPECT_LT(neighbours, 12);
  // Same result on two threads, bit for bit.
  World other = grow(2);
  auto a = world.rootPool().stateArena(), b = other.rootPool().stateArena();
  EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
}

// A stop between grid instants (a frame, `word --at 2.105263,40`) must not split an
// integration step: the colony at t = 40 is the same whether or not it was looked at on
// the way, and the stop itself shows a step of its own from the grid instant 2.1.
TEST(Models, ColonyIsTheSameWhereverTheRunStops) {
  auto program = testing_support::compileModel("colony.cell");
  World straight(program);
  straight.advanceTo(40, program->dt);
  World stopped(program);
  stopped.advanceTo(2.105263, program->dt);
  EXPECT_DOUBLE_EQ(stopped.time(), 2.105263);
  World onGrid(program);
  onGrid.advanceTo(2.1, program->dt);
  EXPECT_EQ(stopped.rootPool().size(), onGrid.rootPool().size()) << "no per-step rule fires off the grid";
  stopped.advanceTo(40, program->dt);
  EXPECT_EQ(straight.rootPool().size(), 2551u);
  ASSERT_EQ(stopped.rootPool().size(), straight.rootPool().size());
  auto a = straight.rootPool().stateArena(), b = stopped.rootPool().stateArena();
  EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end())) << "the same positions, bit for bit";
  EXPECT_EQ(stopped.stats().steps, straight.stats().steps) << "the shown step is not kept";
}

TEST(Cellular, PositionalContextDoesNotFitASpatialPool) {
  DiagnosticSink sink;
  auto program = compileSource("t.cell", "cell A(x = 0) { rules { A(y) me A(z) : x = y + z; } }\n"
                                         "system g { pool spatial(2); axiom A A; }", sink);
  EXPECT_EQ(program, nullptr);
  EXPECT_NE(formatDiagnostics(sink).find("does not fit the spatial pool"), std::string::npos)
      << formatDiagnostics(sink);
}

}  // namespace
}  // namespace ontogen

namespace ontogen {
namespace {

// Gray-Scott "mitosis": the square of v splits into separate spots, which keep their
// height (v near 0.3 to 0.45 at their centres) instead of dying out or flooding the dish.
TEST(Models, GrayScottSplitsIntoSpots) {
  auto program = testing_support::compileModel("gray_scott.cell");
  World world(program);
  world.advanceTo(1200, program->dt);
  const GridPool& grid = world.gridPool();
  const int side = 64;
  std::vector<double> v(side * side);
  for (size_t i = 0; i < grid.size(); ++i) {
    const auto c = grid.coordinates(grid.siteOf(i));
    v[c[1] * side + c[0]] = grid.stateOf(grid.cells()[i])[1];
  }
  // Spots: 4-connected components of v > 0.2 on the torus.
  std::vector<int> component(v.size(), -1);
  int spots = 0;
  size_t covered = 0;
  for (size_t start = 0; start < v.size(); ++start) {
    if (v[start] <= 0.2 || component[start] >= 0) continue;
    std::vector<size_t> stack{start};
    component[start] = spots;
    while (!stack.empty()) {
      const size_t at = stack.back();
      stack.pop_back();
      ++covered;
      const int x = static_cast<int>(at % side), y = static_cast<int>(at / side);
      const int nx[4] = {(x + 1) % side, (x + side - 1) % side, x, x}, ny[4] = {y, y, (y + 1) % side, (y + side - 1) % side};
      for (int k = 0; k < 4; ++k) {
        const size_t next = static_cast<size_t>(ny[k] * side + nx[k]);
        if (v[next] > 0.2 && component[next] < 0) {
          component[next] = spots;
          stack.push_back(next);
        }
      }
    }
    ++spots;
  }
  EXPECT_GE(spots, 4) << "the square has split";
  EXPECT_LT(covered, v.size() / 3) << "spots, not a flood";
  EXPECT_GT(*std::max_element(v.begin(), v.end()), 0.3);
}

}  // namespace
}  // namespace ontogen
