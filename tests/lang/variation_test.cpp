// The variation operators: which numbers of a text are genes, that a variant's text is
// the original but for its genes, and that mutate and crossover are deterministic and
// stay in their ranges.

#include "lang/variation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace ontogen {
namespace {

// Defines of every shape, a define that is an expression, directive settings, a zero, a
// value pattern (the 4 of `A(4)`) and numbers in a comment: only some are genes.
const std::string kText =
    "#define N 3\n"
    "#define RATE 0.25  // 7 in a comment\n"
    "#define X -2\n"
    "#define Z 0\n"
    "#define B N / 2\n"
    "#seed 7\n"
    "#until 10\n"
    "cell A(x = 1.5) {\n"
    "  lifetime 2;\n"
    "  rules { A(4) me : x > 0 : x = x * 2.5 + 1e1; }\n"
    "}\n"
    "system s { pool linear; axiom A(N) A(7); }\n";

struct Compiled {
  DiagnosticSink sink;
  std::unique_ptr<Program> program;
};

std::unique_ptr<Compiled> compileText(const std::string& name, const std::string& text,
                                      std::vector<DefineOverride> defines = {}) {
  auto result = std::make_unique<Compiled>();
  CompileOptions options;
  options.defines = std::move(defines);
  result->program = compileSource(name, text, result->sink, options);
  return result;
}

double defineValue(const Program& program, const std::string& name) {
  for (const ProgramDefine& define : program.defines)
    if (define.name == name) return define.value;
  ADD_FAILURE() << "no #define " << name;
  return NAN;
}

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string spelling(const VariationSpace& space, const Gene& gene) {
  return space.text().substr(gene.offset, gene.length);
}

void expectGene(const VariationSpace& space, size_t index, Gene::Kind kind, const std::string& name,
                const std::string& text, uint32_t line, uint32_t column, double value, double low, double high,
                bool integer) {
  SCOPED_TRACE("gene " + std::to_string(index) + " " + name);
  ASSERT_LT(index, space.genes().size());
  const Gene& gene = space.genes()[index];
  EXPECT_EQ(gene.kind, kind);
  EXPECT_EQ(gene.name, name);
  EXPECT_EQ(spelling(space, gene), text);
  EXPECT_EQ(gene.line, line);
  EXPECT_EQ(gene.column, column);
  EXPECT_EQ(gene.value, value);
  EXPECT_EQ(gene.low, low);
  EXPECT_EQ(gene.high, high);
  EXPECT_EQ(gene.integer, integer);
}

TEST(VariationGenes, DefinesOfANumberInTextOrder) {
  VariationSpace space(kText);
  using K = Gene::Kind;
  ASSERT_EQ(space.genes().size(), 4u);
  expectGene(space, 0, K::Define, "N", "3", 1, 11, 3, 1, 6, true);
  expectGene(space, 1, K::Define, "RATE", "0.25", 2, 14, 0.25, 0, 0.5, false);
  expectGene(space, 2, K::Define, "X", "-2", 3, 11, -2, -4, 0, true);
  expectGene(space, 3, K::Define, "Z", "0", 4, 11, 0, -1, 1, true);
  EXPECT_EQ(space.genes()[0].offset, 10u);
  EXPECT_EQ(space.genes()[0].length, 1u);
  EXPECT_EQ(space.genes()[2].offset, kText.find("-2"));
  EXPECT_EQ(space.genes()[2].length, 2u);
  EXPECT_EQ(space.original(), (Genome{{3, 0.25, -2, 0}}));
}

TEST(VariationGenes, ConstantsOfExpressionsWhenAsked) {
  VariationSpace space(kText, {.constants = true});
  using K = Gene::Kind;
  ASSERT_EQ(space.genes().size(), 9u);
  expectGene(space, 0, K::Define, "N", "3", 1, 11, 3, 1, 6, true);
  expectGene(space, 3, K::Define, "Z", "0", 4, 11, 0, -1, 1, true);
  expectGene(space, 4, K::Constant, "8:12", "1.5", 8, 12, 1.5, 0, 3, false);
  expectGene(space, 5, K::Constant, "9:12", "2", 9, 12, 2, 1, 4, true);
  expectGene(space, 6, K::Constant, "10:37", "2.5", 10, 37, 2.5, 0, 5, false);
  expectGene(space, 7, K::Constant, "10:43", "1e1", 10, 43, 10, 0, 20, false);
  expectGene(space, 8, K::Constant, "12:38", "7", 12, 38, 7, 1, 14, true);
  for (const Gene& gene : space.genes()) EXPECT_EQ(gene.offset, kText.find(spelling(space, gene), gene.offset));
}

TEST(VariationGenes, DirectiveSettingsZerosPatternsAndDefineExpressionsAreNoGenes) {
  VariationSpace space(kText, {.constants = true});
  for (const Gene& gene : space.genes()) {
    SCOPED_TRACE(gene.name);
    EXPECT_NE(gene.line, 5u);  // #define B N / 2
    EXPECT_NE(gene.line, 6u);  // #seed 7
    EXPECT_NE(gene.line, 7u);  // #until 10
    if (gene.kind == Gene::Kind::Constant) {
      EXPECT_NE(gene.value, 0);
    }
    EXPECT_NE(gene.name, "10:13");  // the pattern A(4)
  }
  EXPECT_TRUE(
      VariationSpace("#seed 3\n#until 20\n#dt 0.5\n#angle 30\ncell A {}\n", {.constants = true}).genes().empty());
}

TEST(VariationGenes, DigitsUnderLettersAreModulesNotGenes) {
  const std::string text =
      "lsystem l {\n"
      "  #letters\n"
      "  axiom 0\n"
      "  0 -> 1[0]0\n"
      "  1 -> 11 F(2)\n"
      "}\n";
  ASSERT_NE(compileText("letters.cell", text)->program, nullptr);
  VariationSpace space(text, {.constants = true});
  ASSERT_EQ(space.genes().size(), 1u);
  expectGene(space, 0, Gene::Kind::Constant, "5:13", "2", 5, 13, 2, 1, 4, true);
}

TEST(VariationGenes, ADefineMayEndAtASemicolonButNotBeforeAnExpression) {
  VariationSpace space("#define A 1; #define B 2 * 3\n#define C\n  4\ncell X {}\n");
  ASSERT_EQ(space.genes().size(), 1u);
  EXPECT_EQ(space.genes()[0].name, "A");
}

TEST(VariationText, OriginalTextComesBackByteForByte) {
  for (bool constants : {false, true}) {
    VariationSpace space(kText, {.constants = constants});
    EXPECT_EQ(space.programText(space.original()), kText);
  }
  // Spellings the shortest form would change, and a byte-order mark before the offsets.
  const std::string odd = "\xEF\xBB\xBF#define A 0.50\n#define B 007\ncell C(x = 7., y = .5) {}\n";
  VariationSpace space(odd, {.constants = true});
  ASSERT_EQ(space.genes().size(), 4u);
  EXPECT_EQ(spelling(space, space.genes()[0]), "0.50");
  EXPECT_EQ(spelling(space, space.genes()[2]), "7.");
  EXPECT_FALSE(space.genes()[2].integer);
  EXPECT_EQ(space.programText(space.original()), odd);
}

TEST(VariationText, NewValuesInShortestSpelling) {
  VariationSpace space(kText, {.constants = true});
  Genome genome = space.original();
  genome.values[0] = 5;        // N
  genome.values[1] = 0.1;      // RATE
  genome.values[2] = -3.5;     // X
  genome.values[6] = 1000000;  // 2.5
  genome.values[8] = -0.0;     // 7
  const std::string text = space.programText(genome);
  EXPECT_NE(text.find("#define N 5\n"), std::string::npos) << text;
  EXPECT_NE(text.find("#define RATE 0.1  // 7 in a comment\n"), std::string::npos) << text;
  EXPECT_NE(text.find("#define X -3.5\n"), std::string::npos) << text;
  EXPECT_NE(text.find("x = x * 1000000 + 1e1;"), std::string::npos) << text;
  EXPECT_NE(text.find("axiom A(N) A(0);"), std::string::npos) << text;
}

TEST(VariationText, ANegativeConstantIsParenthesised) {
  const std::string text = "cell A(x = 2^2) {}\nsystem s { pool linear; axiom A; }\n";
  VariationSpace space(text, {.constants = true});
  ASSERT_EQ(space.genes().size(), 2u);
  const std::string variant = space.programText({{-2, 2}});
  EXPECT_EQ(variant, "cell A(x = (-2)^2) {}\nsystem s { pool linear; axiom A; }\n");
  auto c = compileText("negative.cell", variant);
  ASSERT_NE(c->program, nullptr) << formatDiagnostics(c->sink);
}

TEST(VariationText, ANegativeDefineRoundTrips) {
  const std::string text = "#define X -2\ncell A(x = X) {}\nsystem s { pool linear; axiom A; }\n";
  VariationSpace space(text);
  ASSERT_EQ(space.genes().size(), 1u);
  EXPECT_EQ(space.original(), (Genome{{-2}}));
  EXPECT_EQ(space.programText(space.original()), text);
  for (double value : {-3.5, 0.0, -1.0}) {
    SCOPED_TRACE(value);
    const std::string variant = space.programText({{value}});
    auto c = compileText("negative.cell", variant);
    ASSERT_NE(c->program, nullptr) << formatDiagnostics(c->sink);
    EXPECT_EQ(defineValue(*c->program, "X"), value);
    // The variant's own genes read the value back.
    EXPECT_EQ(VariationSpace(variant).original(), (Genome{{value}}));
  }
  EXPECT_EQ(space.programText({{-3.5}}), "#define X -3.5\ncell A(x = X) {}\nsystem s { pool linear; axiom A; }\n");
}

TEST(VariationText, AMutatedTextCompilesWithTheMutatedDefines) {
  VariationSpace space(kText, {.constants = true});
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE(seed);
    const Genome child = space.mutate(space.original(), seed);
    auto c = compileText("variant.cell", space.programText(child));
    ASSERT_NE(c->program, nullptr) << formatDiagnostics(c->sink);
    for (size_t i = 0; i < space.genes().size(); ++i)
      if (space.genes()[i].kind == Gene::Kind::Define) {
        EXPECT_EQ(defineValue(*c->program, space.genes()[i].name), child.values[i]);
      }
    EXPECT_EQ(defineValue(*c->program, "B"), child.values[0] / 2);
  }
}

TEST(VariationText, DefinesMatchTheDefineGenes) {
  VariationSpace space(kText, {.constants = true});
  const Genome child = space.mutate(space.original(), 5);
  const std::vector<DefineOverride> defines = space.defines(child);
  ASSERT_EQ(defines.size(), 4u);
  const char* const names[] = {"N", "RATE", "X", "Z"};
  for (size_t i = 0; i < defines.size(); ++i) {
    EXPECT_EQ(defines[i].name, names[i]);
    EXPECT_EQ(defines[i].value, child.values[i]);
  }
  // The original text with the overrides compiles to the same defines as the variant's text.
  auto overridden = compileText("test.cell", kText, defines);
  ASSERT_NE(overridden->program, nullptr) << formatDiagnostics(overridden->sink);
  for (const DefineOverride& define : defines) EXPECT_EQ(defineValue(*overridden->program, define.name), define.value);
}

TEST(VariationMutate, IsDeterministicPerSeedAndDiffersBetweenSeeds) {
  VariationSpace space(kText, {.constants = true});
  const Genome parent = space.original();
  EXPECT_EQ(space.mutate(parent, 42), space.mutate(parent, 42));
  EXPECT_NE(space.mutate(parent, 42), space.mutate(parent, 43));
  // The parent is part of the key: another parent with the same seed varies otherwise.
  const Genome other = space.mutate(parent, 1);
  const Genome a = space.mutate(parent, 7), b = space.mutate(other, 7);
  bool sameChanges = true;
  for (size_t i = 0; i < parent.values.size(); ++i)
    sameChanges = sameChanges && (a.values[i] - parent.values[i] == b.values[i] - other.values[i]);
  EXPECT_FALSE(sameChanges);
}

TEST(VariationMutate, StaysInRangeKeepsIntegersAndChangesAGene) {
  for (double rate : {0.0, 0.3, 1.0}) {
    VariationSpace space(kText, {.constants = true, .rate = rate});
    Genome parent = space.original();
    for (uint64_t seed = 0; seed < 300; ++seed) {
      SCOPED_TRACE(testing::Message() << "rate " << rate << " seed " << seed);
      const Genome child = space.mutate(parent, seed);
      ASSERT_EQ(child.values.size(), parent.values.size());
      size_t changed = 0;
      for (size_t i = 0; i < child.values.size(); ++i) {
        const Gene& gene = space.genes()[i];
        EXPECT_GE(child.values[i], gene.low);
        EXPECT_LE(child.values[i], gene.high);
        if (gene.integer) {
          EXPECT_EQ(child.values[i], std::round(child.values[i]));
        }
        changed += child.values[i] != parent.values[i];
      }
      if (rate == 0) {
        EXPECT_EQ(changed, 1u);
      }
      if (rate == 1) {
        EXPECT_EQ(changed, child.values.size());
      }
      EXPECT_GE(changed, 1u);
      parent = child;  // a lineage: values drift and meet the bounds
    }
  }
}

TEST(VariationMutate, AnIntegerAtItsBoundStillMoves) {
  VariationSpace space("#define N 1\n", {.rate = 1, .strength = 0.01});
  for (uint64_t seed = 0; seed < 50; ++seed) EXPECT_EQ(space.mutate({{1}}, seed), (Genome{{2}}));
}

// A program's `#range` and a caller's range replace the default [0, 2v]; an integer
// gene keeps to the whole numbers inside; a fixed define is no gene.
TEST(VariationRanges, DeclaredGivenAndFixed) {
  const std::string text = "#define N 3\n#range N 1.5 9.5\n#define R 0.25\n#range R -1 1\n#define S 4\n";
  VariationSpace declared(text);
  ASSERT_EQ(declared.genes().size(), 3u);
  EXPECT_EQ(declared.genes()[0].low, 2);  // whole numbers of [1.5, 9.5]
  EXPECT_EQ(declared.genes()[0].high, 9);
  EXPECT_EQ(declared.genes()[1].low, -1);
  EXPECT_EQ(declared.genes()[1].high, 1);
  EXPECT_EQ(declared.genes()[2].low, 1);  // the default for a whole number 4: [1, 8]
  EXPECT_EQ(declared.genes()[2].high, 8);
  for (uint64_t seed = 0; seed < 200; ++seed) {
    const Genome child = declared.mutate(declared.original(), seed);
    EXPECT_GE(child.values[1], -1);  // a declared range may cross zero
    EXPECT_LE(child.values[0], 9);
  }

  VariationSpace given(text, {.ranges = {{"R", 0.1, 0.2}}, .fixed = {"S"}});
  ASSERT_EQ(given.genes().size(), 2u);
  EXPECT_EQ(given.genes()[1].name, "R");
  EXPECT_EQ(given.genes()[1].low, 0.1);
  EXPECT_EQ(given.genes()[1].high, 0.2);

  EXPECT_THROW(VariationSpace(text, {.ranges = {{"Q", 0, 1}}}), std::invalid_argument);
  EXPECT_THROW(VariationSpace(text, {.ranges = {{"N", 2, 1}}}), std::invalid_argument);
  EXPECT_THROW(VariationSpace(text, {.ranges = {{"N", 2.2, 2.8}}}), std::invalid_argument);
}

TEST(VariationCrossover, TakesEachGeneFromAParentDeterministically) {
  std::string text;
  for (int i = 0; i < 32; ++i) text += "#define G" + std::to_string(i) + " " + std::to_string(i + 1) + "\n";
  VariationSpace space(text);
  ASSERT_EQ(space.genes().size(), 32u);
  Genome a = space.original(), b = a;
  for (double& value : b.values) value = -value;
  const Genome child = space.crossover(a, b, 9);
  EXPECT_EQ(child, space.crossover(a, b, 9));
  EXPECT_NE(child, space.crossover(a, b, 10));
  size_t fromA = 0, fromB = 0;
  for (size_t i = 0; i < child.values.size(); ++i) {
    EXPECT_TRUE(child.values[i] == a.values[i] || child.values[i] == b.values[i]) << i;
    fromA += child.values[i] == a.values[i];
    fromB += child.values[i] == b.values[i];
  }
  EXPECT_GT(fromA, 0u);
  EXPECT_GT(fromB, 0u);
  EXPECT_EQ(space.crossover(a, a, 3), a);
}

TEST(VariationErrors, ATextThatDoesNotLexThrowsWithItsLocation) {
  try {
    VariationSpace("#define A 1\ncell B { ` }\n");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_STREQ(error.what(), "cannot find the numbers of a text that does not lex: 2:10: unexpected character '`'");
  }
  EXPECT_THROW(VariationSpace("/* never closed"), std::invalid_argument);
  // Defines are read from the tokens alone; constants need the parse as well.
  EXPECT_EQ(VariationSpace("#define A 1\ncell {\n").genes().size(), 1u);
  EXPECT_THROW(VariationSpace("#define A 1\ncell {\n", {.constants = true}), std::invalid_argument);
}

TEST(VariationErrors, WrongGenomesAndOptionsThrow) {
  VariationSpace space(kText);
  EXPECT_THROW(space.programText({{1, 2}}), std::invalid_argument);
  EXPECT_THROW(space.mutate({{3, 0.25, -2, NAN}}, 1), std::invalid_argument);
  EXPECT_THROW(space.crossover(space.original(), {{3, INFINITY, -2, 0}}, 1), std::invalid_argument);
  EXPECT_THROW(space.defines({}), std::invalid_argument);
  EXPECT_THROW(VariationSpace(kText, {.rate = 1.5}), std::invalid_argument);
  EXPECT_THROW(VariationSpace(kText, {.strength = 0}), std::invalid_argument);
  EXPECT_THROW(VariationSpace(kText, {.strength = NAN}), std::invalid_argument);
}

// The defines a model writes as `#define NAME NUMBER`, read by a pattern independent of the lexer.
std::vector<std::string> numberDefines(const std::string& text) {
  static const std::regex kDefine(R"(^\s*#define\s+(\S+)\s+-?[0-9.]+([eE][-+]?[0-9]+)?\s*(//.*)?;?\s*$)");
  std::vector<std::string> names;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::smatch match;
    if (std::regex_match(line, match, kDefine)) names.push_back(match[1]);
  }
  return names;
}

TEST(VariationModels, CreatureHasItsDefinesAsGenes) {
  const std::filesystem::path path = std::filesystem::path(ONTOGEN_SOURCE_DIR) / "models/creature.cell";
  const std::string text = readFile(path);
  VariationSpace space(text);
  std::vector<std::string> names;
  for (const Gene& gene : space.genes()) names.push_back(gene.name);
  EXPECT_EQ(names, numberDefines(text));
  ASSERT_FALSE(names.empty());
  EXPECT_EQ(names.front(), "SEGMENTS");
  expectGene(space, 0, Gene::Kind::Define, "SEGMENTS", "3", 30, 18, 3, 1, 6, true);
  for (const Gene& gene : space.genes()) EXPECT_TRUE(text.substr(gene.offset - 9 - gene.name.size(), 8) == "#define ");

  const Genome child = space.mutate(space.original(), 2024);
  auto c = compileText(path.string(), space.programText(child));
  ASSERT_NE(c->program, nullptr) << formatDiagnostics(c->sink);
  for (size_t i = 0; i < space.genes().size(); ++i)
    EXPECT_EQ(defineValue(*c->program, space.genes()[i].name), child.values[i]);
}

TEST(VariationModels, EveryModelRoundTripsAndItsVariantsCompile) {
  size_t models = 0, compiled = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(ONTOGEN_SOURCE_DIR) / "models")) {
    if (entry.path().extension() != ".cell") continue;
    ++models;
    SCOPED_TRACE(entry.path().filename().string());
    const std::string text = readFile(entry.path());
    VariationSpace defines(text);
    std::vector<std::string> names;
    for (const Gene& gene : defines.genes()) names.push_back(gene.name);
    EXPECT_EQ(names, numberDefines(text));
    VariationSpace space(text, {.constants = true});
    EXPECT_EQ(space.programText(space.original()), text);
    // Models that name a set's constants (`scale(minor)`) need the interpreters' sets.
    if (!compileText(entry.path().string(), text)->program) continue;
    ++compiled;
    // flower.cell's `#define kBud 0` names a surface id: the range of a zero, [-1, 1],
    // reaches -1, which #surface rejects. Its constants are varied all the same.
    const bool definesMayFail = entry.path().filename() == "flower.cell";
    for (uint64_t seed = 1; seed <= 5; ++seed) {
      const Genome child = space.mutate(space.original(), seed);
      Genome constantsOnly = child;
      for (size_t i = 0; i < space.genes().size(); ++i)
        if (space.genes()[i].kind == Gene::Kind::Define) constantsOnly.values[i] = space.genes()[i].value;
      auto expectCompiles = [&](const Genome& variant, const char* what) {
        auto c = compileText(entry.path().string(), space.programText(variant));
        EXPECT_NE(c->program, nullptr) << what << ", seed " << seed << "\n" << formatDiagnostics(c->sink);
      };
      if (!definesMayFail) expectCompiles(child, "every gene");
      expectCompiles(constantsOnly, "constants");
    }
  }
  EXPECT_GT(models, 10u);
  EXPECT_GT(compiled, models / 2);
}

}  // namespace
}  // namespace ontogen
