#include <iostream>
#include <optional>

#include "apps/cli_values.h"
#include "apps/commands.h"
#include "apps/program_loader.h"
#include "apps/sweep_terminal.h"
#include "batch/evolution.h"

namespace ontogen::app {

namespace {

// `NAME=LOW:HIGH`; prints why not.
std::optional<GeneRange> parseRange(const std::string& text) {
  const size_t equals = text.find('='), colon = text.rfind(':');
  std::optional<double> low, high;
  if (equals != std::string::npos && equals > 0 && colon != std::string::npos && colon > equals) {
    low = parseReal(std::string_view(text).substr(equals + 1, colon - equals - 1));
    high = parseReal(std::string_view(text).substr(colon + 1));
  }
  if (!low || !high || !(*low < *high)) {
    std::cerr << "ontogen: error: --range takes NAME=LOW:HIGH, numbers with LOW < HIGH, as in --range SEGMENTS=2:12, "
                 "not '"
              << text << "'\n";
    return std::nullopt;
  }
  return GeneRange{text.substr(0, equals), *low, *high};
}

}  // namespace

int runEvolve(const EvolveOptions& options) {
  const std::unique_ptr<Cluster> cluster = joinCluster();
  if (!cluster) return kExitUsage;
  QuietFollowers quiet(cluster->leader());

  EvolutionDef def;
  def.settings.measures = options.sweep.measures;
  def.generations = options.generations;
  def.population = options.population;
  def.elite = options.elite;
  if (std::string why = evolutionDefProblem(def); !why.empty()) {
    std::cerr << "ontogen: error: " << why << "\n";
    return kExitUsage;
  }
  VariationOptions variation;
  variation.constants = options.varyConstants;
  variation.rate = options.mutationRate;
  variation.strength = options.mutationStrength;
  for (const std::string& text : options.ranges) {
    std::optional<GeneRange> range = parseRange(text);
    if (!range) return kExitUsage;
    variation.ranges.push_back(std::move(*range));
  }
  if (int code = readSweepSettings(options.sweep, def.settings); code != kExitOk) return code;
  def.settings.variation = variation;
  def.crossover = options.crossover;
  def.evolveSeed = options.evolveSeed;
  def.seed = options.sweep.common.seed;
  def.rangeTexts = options.ranges;
  def.out = options.sweep.out;
  def.resume = options.sweep.resume;
  def.sizeText = options.sweep.size;
  def.stop = &BatchInterrupt::requested;

  // A bar a generation, and Ctrl-C asks the batch to stop only while a generation runs.
  std::optional<BatchProgressBar> bar;
  std::optional<BatchInterrupt> interrupt;
  int batchCode = kExitOk;
  def.generationStarts = [&](int generation) {
    bar.emplace("evolving " + def.settings.stem + ", generation " + std::to_string(generation + 1) + "/" +
                    std::to_string(options.generations),
                options.sweep.progress, cluster->leader());
    interrupt.emplace();
  };
  def.progress = [&](const BatchProgress& progress) { bar->callback()(progress); };
  def.generationEnds = [&](int, const BatchResult& result) {
    interrupt.reset();
    batchCode = bar->finish(result);
  };
  const EvolutionResult result = runEvolution(def, *cluster);
  if (result.batchEnded) {
    if (batchCode == kExitInterrupted && cluster->leader())
      std::cerr << "ontogen: stopped in generation " << result.generation << "; --resume continues the evolution\n";
    return batchCode;
  }
  if (result.status != BatchStatus::Done) {
    std::cerr << "ontogen: error: " << result.message << "\n";
    return result.status == BatchStatus::OutputError ? kExitOutputError : kExitUsage;
  }
  if (!cluster->leader()) return kExitOk;
  std::cerr << "evolved " << options.generations << " generation" << (options.generations == 1 ? "" : "s") << " of "
            << options.population << ": best " << result.fitnessName << " " << formatValue(result.bestFitness) << " ("
            << result.best.string() << ")\n";
  return kExitOk;
}

}  // namespace ontogen::app
