// The evolution as a library call (batch/evolution.h): generations bred from the fittest,
// the same draws on every run, a refusal for what cannot evolve.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "batch/evolution.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"
#include "tests/batch/batch_test_support.h"

namespace ontogen::test {
namespace {

namespace fs = std::filesystem;

EvolutionDef chainEvolution(const fs::path& dir, const std::string& text = kChain) {
  EvolutionDef def;
  def.settings.path = (dir / "chain.cell").string();
  def.settings.stem = "chain";
  def.settings.text = text;
  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  def.settings.program = compileSource(def.settings.path, text, sink, options);
  def.settings.measures = {"h=height"};
  def.settings.width = def.settings.height = 16;
  def.settings.workers = 2;
  def.settings.variation.ranges = {{"LEN", 1, 3}, {"S", 0.1, 0.9}};
  def.generations = 4;
  def.population = 6;
  def.elite = 1;
  def.evolveSeed = 3;
  def.out = dir / "out";
  return def;
}

TEST(Evolution, TheEliteKeepsTheBestFitnessFromFallingAndEveryGenerationIsReported) {
  const fs::path dir = scratch("evolution");
  EvolutionDef def = chainEvolution(dir);
  ASSERT_TRUE(def.settings.program);
  std::vector<std::string> calls;
  def.generationStarts = [&](int g) { calls.push_back("start " + std::to_string(g)); };
  def.generationEnds = [&](int g, const BatchResult& batch) {
    calls.push_back("end " + std::to_string(g) + " " + std::to_string(batch.table.rows.size()));
  };
  const EvolutionResult result = runEvolution(def);
  ASSERT_EQ(result.status, BatchStatus::Done) << result.message;
  const std::vector<std::string> expected{"start 0", "end 0 6", "start 1", "end 1 6",
                                          "start 2", "end 2 6", "start 3", "end 3 6"};
  EXPECT_EQ(calls, expected);
  ASSERT_EQ(result.generations.size(), 4u);
  EXPECT_EQ(result.fitnessName, "h");
  for (size_t g = 1; g < result.generations.size(); ++g)
    EXPECT_GE(result.generations[g].bestFitness, result.generations[g - 1].bestFitness) << "generation " << g;
  EXPECT_EQ(result.bestFitness, result.generations.back().bestFitness);
  // The original program is variant 0 of the first generation: LEN 1, S 0.5, three steps.
  EXPECT_GE(result.generations[0].bestFitness, 1 + 0.5 + 0.25);
  EXPECT_EQ(result.best, def.out / "best.cell");
  const std::string best = readWholeFile(result.best);
  EXPECT_NE(best.find("lsystem chain"), std::string::npos);
  EXPECT_EQ(best, readWholeFile(def.out / "best" / "generation_003.cell"));
  const std::string csv = readWholeFile(def.out / "evolution.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "generation,best_variant,best_h,mean_h,failed");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 5);
  EXPECT_TRUE(fs::exists(def.out / "gallery.png"));

  // The same seed breeds the same generations.
  EvolutionDef again = chainEvolution(dir);
  again.out = dir / "again";
  ASSERT_EQ(runEvolution(again).status, BatchStatus::Done);
  EXPECT_EQ(readWholeFile(again.out / "evolution.csv"), csv);
  EXPECT_EQ(readWholeFile(again.out / "best.cell"), best);
}

TEST(Evolution, WhatCannotEvolveIsRefusedWithWhy) {
  const fs::path dir = scratch("evolution_refused");
  EvolutionDef noMeasure = chainEvolution(dir);
  noMeasure.settings.measures.clear();
  EvolutionResult result = runEvolution(noMeasure);
  EXPECT_EQ(result.status, BatchStatus::Refused);
  EXPECT_EQ(result.message, "evolve needs a fitness: --measure NAME=EXPR (the first --measure is maximised)");
  EXPECT_FALSE(result.batchEnded);

  EvolutionDef allElite = chainEvolution(dir);
  allElite.elite = allElite.population;
  result = runEvolution(allElite);
  EXPECT_EQ(result.status, BatchStatus::Refused);
  EXPECT_EQ(result.message, "--elite 6 must be below --population 6 (the elite are kept and the rest bred)");

  EvolutionDef noGenes = chainEvolution(dir, "lsystem still {\n  #until 1\n  axiom F(1)\n}\n");
  noGenes.settings.variation.ranges.clear();
  result = runEvolution(noGenes);
  EXPECT_EQ(result.status, BatchStatus::Refused);
  EXPECT_EQ(result.message, noGenes.settings.path +
                                " has nothing to evolve: no #define NAME NUMBER that is not fixed by --define "
                                "(--vary-constants also varies its constants)");
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace ontogen::test
