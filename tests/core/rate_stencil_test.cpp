// Rates of full grids integrated as stencils (core/rate_stencil.h): the bits of the
// general path (WorldDef::rateStencils = false) on every boundary, neighbourhood and
// dimension, with several variables and every aggregate, on any number of threads; RK4's
// amplification of a Fourier mode; and the general path wherever the stencil must not apply.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/grid_development.h"
#include "core/rate_stencil.h"
#include "core/world.h"
#include "test_support.h"

namespace ontogen {
namespace {

using testing_support::compileOrFail;

struct Grown {
  std::vector<uint64_t> bits;  ///< every state value, as bits
  WorldStats stats;
};

Grown grow(const std::shared_ptr<const Program>& program, bool stencils, unsigned threads, int steps, double dt) {
  WorldDef def;
  def.seed = 3;
  def.threads = threads;
  def.rateStencils = stencils;
  World world(program, def);
  world.advanceTo(steps * dt, dt);
  Grown grown{{}, world.stats()};
  for (double value : world.rootPool().stateArena()) grown.bits.push_back(std::bit_cast<uint64_t>(value));
  return grown;
}

struct Case {
  const char* name;
  const char* text;
};

const Case kCases[] = {
    // Large enough (9,100 cells) that the passes split over threads.
    {"2-D wrap von Neumann diffusion", R"(
#define D 0.2
cell U(u = 0) { rules { rate(u) = D * (sum(u) - count() * u); } }
system plate { pool grid(130, 70) wrap vonneumann; fill U(sin(me.x * 0.3) + cos(me.y * 0.2)); }
)"},
    // Two rates and a constant that starts at -0 (odeint's zero coefficients make it +0),
    // labelled and unlabelled aggregates of every kind, a pure built-in.
    {"2-D clamp Moore, two rates, every aggregate", R"(
cell V(a = 0, k = 0, b = 0) {
  rules {
    rate(a) = mean(a) - a + 0.1 * max(b) - 0.05 * min(b) * k + 0.01 * sin(a);
    rate(b) = count(V) * 0.01 * (sum(V.a) - b) - 0.02 * count(W) + sum(W.b);
  }
}
cell W(b = 0) { }
system plate { pool grid(19, 17) clamp moore; fill V(me.x * 0.1, -0, me.y * 0.2); }
)"},
    {"3-D closed von Neumann", R"(
cell C(w = 0) { rules { rate(w) = 0.1 * (sum(w) - count() * w); } }
system block { pool grid(9, 8, 7) closed vonneumann; fill C(me.x + 2 * me.y - me.z); }
)"},
    {"3-D wrap Moore", R"(
cell C(w = 0) { rules { rate(w) = 0.01 * (sum(w) - count() * w) - 0.1 * max(w); } }
system block { pool grid(5, 4, 6) wrap moore; fill C(me.x * me.y - me.z); }
)"},
    // A later rule's rate replaces an earlier one for the same variable.
    {"1-D wrap, a rate replaced", R"(
cell L(v = 1) { rules { rate(v) = -v; rate(v) = 0.3 * (sum(v) - 2 * v); } }
system ring { pool grid(50) wrap vonneumann; fill L(me.x % 7); }
)"},
    // Sums and counts only, several variables: the stencil holds them a variable at a
    // time; rows of 70 take a full batch and a partial one; a labelled sum and count.
    {"2-D clamp, Gray-Scott's kind, a variable at a time", R"(
cell G(u = 1, c = 0.5, v = 0) {
  rules {
    rate(u) = 0.2 * (sum(u) - count() * u) - u * v * v + 0.0367 * (1 - u) + c * 0.001;
    rate(v) = 0.1 * (sum(G.v) - count(G) * v) + u * v * v - (0.0367 + 0.0649) * v;
  }
}
system dish { pool grid(70, 9) clamp vonneumann; fill G(1 - 0.01 * me.x, -0, 0.02 * me.y + 0.001 * me.x); }
)"},
    // No cell has all its neighbours inside: every one asks the grid.
    {"2 x 2, all at the edge", R"(
cell C(w = 0) { rules { rate(w) = sum(w) - count() * w; } }
system tiny { pool grid(2, 2) wrap moore; fill C(me.x + 3 * me.y); }
)"},
};

TEST(RateStencil, TheBitsOfTheGeneralPathOnAnyThreads) {
  constexpr int kSteps = 5;
  for (const Case& test : kCases) {
    auto program = compileOrFail(test.text, test.name);
    ASSERT_NE(program, nullptr) << test.name;
    const Grown general = grow(program, false, 1, kSteps, 0.25);
    EXPECT_EQ(general.stats.stencilSteps, 0u) << test.name;
    ASSERT_GT(general.stats.rateEquations, 0u) << test.name;
    for (unsigned threads : {1u, 2u, 3u}) {
      const Grown stencil = grow(program, true, threads, kSteps, 0.25);
      EXPECT_EQ(stencil.stats.stencilSteps, static_cast<uint64_t>(kSteps)) << test.name << ": not taken";
      EXPECT_EQ(stencil.stats.rateEquations, general.stats.rateEquations) << test.name;
      ASSERT_EQ(stencil.bits.size(), general.bits.size()) << test.name;
      size_t differing = 0;
      for (size_t i = 0; i < general.bits.size(); ++i) differing += stencil.bits[i] != general.bits[i];
      EXPECT_EQ(differing, 0u) << test.name << " on " << threads << " threads";
    }
  }
}

// The tables of the cells at an edge that prepare() makes are what edgeTableBytes
// counts for the grid's shape (a closed boundary leaves some neighbours out).
TEST(RateStencil, TheEdgeTablesAreTheirCountedBytes) {
  for (const Case& test : kCases) {
    auto program = compileOrFail(test.text, test.name);
    ASSERT_NE(program, nullptr) << test.name;
    World world(program, WorldDef{});
    const auto* grid = dynamic_cast<const GridPool*>(&world.rootPool());
    ASSERT_NE(grid, nullptr) << test.name;
    RateStencil stencil;
    ASSERT_TRUE(stencil.prepare(*program, *grid)) << test.name;
    const uint64_t counted = RateStencil::edgeTableBytes(grid->shape());
    if (grid->shape().boundary == GridBoundary::Closed)
      EXPECT_LT(stencil.edgeTableBytes(), counted) << test.name;
    else
      EXPECT_EQ(stencil.edgeTableBytes(), counted) << test.name;
  }
}

// The memory limit's bytes of a site count the edge tables, shared out over the sites:
// an 8 x 8 wrapped von Neumann grid has 28 edge cells (the 2 ends of the 6 rows inside
// and the 16 cells of the first and last rows), 4 + 4 bytes each, one more start, and 4
// neighbours of 8 bytes each: 1124 bytes, 18 a site (rounded up).
TEST(RateStencil, TheMemoryLimitCountsTheEdgeTables) {
  auto program = compileOrFail(R"(
cell U(u = 0) { rules { rate(u) = sum(u) - count() * u; } }
system s { pool grid(8, 8) wrap vonneumann; fill U(me.x); }
)");
  ASSERT_NE(program, nullptr);
  const SystemDefinition& system = program->systems[program->root];
  ASSERT_TRUE(system.rates);
  EXPECT_EQ(RateStencil::edgeTableBytes(system.grid), 1124u);
  uint64_t values = 0;
  for (const MasterCell& master : program->masters) values = std::max<uint64_t>(values, master.stateCount());
  // The index, the seeding's source, three copies of a cell, eight arrays of stages.
  const uint64_t before = 4 + 8 + 3 * (sizeof(CellRecord) + 4 + 8 * values) + 8 * 8 * values;
  EXPECT_EQ(gridBytesPerSite(*program, system), before + 18);
}

TEST(RateStencil, ANegativeZeroConstantBecomesPositiveAsInOdeint) {
  auto program = compileOrFail(kCases[1].text, kCases[1].name);
  ASSERT_NE(program, nullptr);
  const Grown grown = grow(program, true, 1, 1, 0.25);
  // V(a, k, b): k starts at -0, and 1.0 * -0 + 0.5 dt * 0 is +0.
  EXPECT_EQ(grown.bits[1], std::bit_cast<uint64_t>(0.0));
}

// u_j = cos(2 pi m j / N) on a ring is an eigenvector of sum(u) - 2u with eigenvalue
// lambda = 2 cos(2 pi m / N) - 2; one RK4 step multiplies it by R(z) = 1 + z + z^2/2 +
// z^3/6 + z^4/24, z = D dt lambda.
TEST(RateStencil, AFourierModeDecaysByRk4sAmplification) {
  constexpr int kN = 64, kMode = 6, kSteps = 10;
  constexpr double kD = 0.2, kDt = 0.5;
  auto program = compileOrFail(R"(
cell U(u = 0) { rules { rate(u) = 0.2 * (sum(u) - count() * u); } }
system ring { pool grid(64) wrap vonneumann; fill U(cos(2 * pi * 6 * me.x / 64)); }
)");
  ASSERT_NE(program, nullptr);
  WorldDef def;
  World world(program, def);
  world.advanceTo(kSteps * kDt, kDt);
  EXPECT_EQ(world.stats().stencilSteps, static_cast<uint64_t>(kSteps));
  const double angle = 2 * std::numbers::pi * kMode / kN;
  const double z = kD * kDt * (2 * std::cos(angle) - 2);
  const double factor = std::pow(1 + z + z * z / 2 + z * z * z / 6 + z * z * z * z / 24, kSteps);
  ASSERT_LT(factor, 0.9);  // it did decay noticeably
  const auto cells = world.rootPool().cells();
  for (int j = 0; j < kN; ++j)
    EXPECT_NEAR(*world.rootPool().stateOf(cells[static_cast<size_t>(j)]), factor * std::cos(angle * j), 1e-12)
        << "cell " << j;
}

TEST(RateStencil, TheGeneralPathWhereItDoesNotApply) {
  const char* kNot[] = {
      // An empty site.
      "cell U(u = 0) { rules { rate(u) = sum(u) - count() * u; } }\n"
      "system s { pool grid(8, 8) wrap vonneumann; at(1, 1) U(1); at(2, 1) U(2); }",
      // Two masters.
      "cell U(u = 0) { rules { rate(u) = sum(u) - count() * u; } }\ncell V(u = 0) { }\n"
      "system s { pool grid(8, 8) wrap vonneumann; fill U(me.x); at(3, 3) V(1); }",
      // A rate with a condition.
      "cell U(u = 0) { rules { u < 5 : rate(u) = sum(u) - count() * u; } }\n"
      "system s { pool grid(8, 8) wrap vonneumann; fill U(me.x); }",
      // A rate that reads the cell's age.
      "cell U(u = 0) { rules { rate(u) = sum(u) - count() * u + age; } }\n"
      "system s { pool grid(8, 8) wrap vonneumann; fill U(me.x); }",
      // A rate that draws.
      "cell U(u = 0) { rules { rate(u) = sum(u) - count() * u + uniform(0, 1); } }\n"
      "system s { pool grid(8, 8) wrap vonneumann; fill U(me.x); }",
      // The adaptive stepper.
      "#tolerance 1e-6\ncell U(u = 0) { rules { rate(u) = sum(u) - count() * u; } }\n"
      "system s { pool grid(8, 8) wrap vonneumann; fill U(me.x); }",
  };
  for (const char* text : kNot) {
    auto program = compileOrFail(text);
    ASSERT_NE(program, nullptr) << text;
    const Grown general = grow(program, false, 1, 3, 0.25);
    const Grown asked = grow(program, true, 1, 3, 0.25);
    EXPECT_EQ(asked.stats.stencilSteps, 0u) << text;
    EXPECT_GT(asked.stats.rateEquations, 0u) << text;
    EXPECT_EQ(asked.bits, general.bits) << text;
  }
}

}  // namespace
}  // namespace ontogen
