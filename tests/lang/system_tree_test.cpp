// The system tree's limits: how many systems a program has, and how deep they nest.

#include "lang/system_tree.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "lang/compiler.h"

namespace ontogen {
namespace {

struct Compiled {
  DiagnosticSink sink;
  std::unique_ptr<Program> program;
};

std::unique_ptr<Compiled> compileText(const std::string& text) {
  auto result = std::make_unique<Compiled>();
  result->program = compileSource("test.cell", text, result->sink);
  return result;
}

// s0 contains s1 contains ... s(n-1), whose pool holds a cell.
std::string nestedSystems(int n) {
  std::string text;
  for (int i = 0; i < n; ++i)
    text += "system s" + std::to_string(i) + " { pool linear; axiom " +
            (i + 1 < n ? "s" + std::to_string(i + 1) : std::string("Leaf")) + "; }\n";
  return text + "cell Leaf { }\n";
}

TEST(SystemTree, DepthsFollowTheLongestChainOfContainment) {
  auto c = compileText(nestedSystems(5));
  ASSERT_NE(c->program, nullptr) << formatDiagnostics(c->sink);
  const SystemTree::Depths depths = SystemTree(*c->program).depths();
  EXPECT_EQ(depths.depth, (std::vector<int>{1, 2, 3, 4, 5}));
  EXPECT_EQ(depths.above, (std::vector<int>{-1, 0, 1, 2, 3}));
}

TEST(SystemTree, SystemsNestUpToTheLimitAndOneMoreIsALocatedError) {
  auto deepest = compileText(nestedSystems(kMaxSystemDepth));
  EXPECT_NE(deepest->program, nullptr) << formatDiagnostics(deepest->sink);
  auto tooDeep = compileText(nestedSystems(kMaxSystemDepth + 1));
  EXPECT_EQ(tooDeep->program, nullptr);
  ASSERT_EQ(tooDeep->sink.errorCount(), 1) << formatDiagnostics(tooDeep->sink);
  const Diagnostic& error = tooDeep->sink.diagnostics().front();
  EXPECT_EQ(error.message, "system 's64' is nested 65 deep (under 's0'), past the limit of 64 nested systems");
  EXPECT_EQ(error.span.line(), 65);
  EXPECT_EQ(error.span.column(), 8);
}

TEST(SystemTree, ThirtyThousandSystemsAreOneErrorNotMinutesAndGigabytes) {
  const auto start = std::chrono::steady_clock::now();
  auto many = compileText(nestedSystems(30000));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(many->program, nullptr);
  ASSERT_EQ(many->sink.errorCount(), 1) << formatDiagnostics(many->sink).substr(0, 500);
  EXPECT_EQ(many->sink.diagnostics().front().message,
            "system 's1024' is one too many: a program has at most 1024 systems");
  EXPECT_EQ(many->sink.diagnostics().front().span.line(), 1025);
  EXPECT_LT(seconds, 20.0);  // it took over a minute before the limit; well under a second with it
}

}  // namespace
}  // namespace ontogen
