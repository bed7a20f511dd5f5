#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "apps/cli_values.h"
#include "apps/commands.h"
#include "apps/program_loader.h"
#include "apps/sweep_terminal.h"
#include "batch/batch_run.h"
#include "batch/sweep_setup.h"
#include "interpreters/formats/png_writer.h"
#include "interpreters/output_file.h"
#include "lang/random.h"

namespace ontogen::app {

namespace {

// Salts of the evolution's random streams: the first generation's mutations, and the
// choices that breed generation g from g - 1.
constexpr uint64_t kFirstGenerationSalt = 0x6576'6f6c'7665'3030ull;  // "evolve00"
constexpr uint64_t kBreedSalt = 0x6272'6565'6400'0000ull;            // "breed"

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

// The fitness of a row: its first measure, or -infinity when it failed or has none, so
// that a failure is never chosen over a variant that grew.
double fitnessOf(const SweepRow& row, size_t column) {
  if (!row.error.empty() || column >= row.values.size() || row.values[column].empty())
    return -std::numeric_limits<double>::infinity();
  return std::strtod(row.values[column].c_str(), nullptr);
}

std::string generationName(int generation, int digits) {
  std::string number = std::to_string(generation);
  if (static_cast<int>(number.size()) < digits) number.insert(0, digits - number.size(), '0');
  return "generation_" + number;
}

}  // namespace

int runEvolve(const EvolveOptions& options) {
  const std::unique_ptr<Cluster> cluster = joinCluster();
  if (!cluster) return kExitUsage;
  QuietFollowers quiet(cluster->leader());

  if (options.sweep.measures.empty()) {
    std::cerr << "ontogen: error: evolve needs a fitness: --measure NAME=EXPR (the first --measure is maximised)\n";
    return kExitUsage;
  }
  if (options.elite >= options.population) {
    std::cerr << "ontogen: error: --elite " << options.elite << " must be below --population " << options.population
              << " (the elite are kept and the rest bred)\n";
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
  SweepSettings given;
  if (int code = readSweepSettings(options.sweep, given); code != kExitOk) return code;
  given.variation = variation;
  SweepSetup setup;
  if (int code = prepareSweepReporting(given, setup); code != kExitOk) return code;
  const VariationSpace& space = *setup.space;
  if (space.genes().empty()) {
    std::cerr << "ontogen: error: " << setup.path
              << " has nothing to evolve: no #define NAME NUMBER that is not fixed by --define"
              << (options.varyConstants ? " and no numeric constant" : " (--vary-constants also varies its constants)")
              << "\n";
    return kExitUsage;
  }
  const uint64_t seed = options.sweep.common.seed.value_or(setup.programSeed);
  const size_t population = static_cast<size_t>(options.population);
  setup.digits = std::max<int>(4, static_cast<int>(std::to_string(population - 1).size()));
  const int generationDigits = std::max<int>(3, static_cast<int>(std::to_string(options.generations - 1).size()));

  // Columns: a gene each (a define's name; a second #define of one name, or a constant,
  // by its place), the seed, the measures.
  std::vector<std::string> columns;
  for (const Gene& gene : space.genes()) {
    std::string name = gene.kind == Gene::Kind::Define ? gene.name : "constant@" + gene.name;
    if (std::find(columns.begin(), columns.end(), name) != columns.end()) name += "@" + std::to_string(gene.line);
    columns.push_back(name);
  }
  const size_t fitnessColumn = columns.size() + 1;
  columns.push_back("seed");
  for (const Measure& measure : setup.measures) columns.push_back(measure.name());

  nlohmann::json settings;
  settings["ontogen"] = "evolve";
  settings["program"] = setup.path;
  settings["text"] = textDigest(space.text());
  settings["columns"] = columns;
  nlohmann::json measures = nlohmann::json::array();
  for (const Measure& measure : setup.measures) measures.push_back(measure.name() + "=" + measure.text());
  settings["measures"] = measures;
  settings["seed"] = seed;
  settings["evolve"] = {options.population, options.elite, options.crossover, options.mutationRate,
                        options.mutationStrength, options.evolveSeed, options.varyConstants};
  settings["ranges"] = options.ranges;
  settings["run"] = setup.rerunFlags;
  settings["size"] = options.sweep.size;
  settings["view"] = options.sweep.view;
  settings["limits"] = {setup.run.world.limits.maxCells, setup.run.world.limits.maxEventsPerStep,
                        setup.run.world.limits.maxSteps, setup.run.world.limits.maxMemoryBytes};

  const std::filesystem::path out = options.sweep.out;
  std::vector<Genome> genomes;
  {
    RandomStream stream(mixKey(options.evolveSeed, kFirstGenerationSalt));
    genomes.push_back(space.original());
    while (genomes.size() < population) genomes.push_back(space.mutate(space.original(), stream.next()));
  }
  struct GenerationSummary {
    uint64_t best = 0;
    double bestFitness = 0, meanFitness = 0;
    uint64_t failed = 0;
  };
  std::vector<GenerationSummary> summaries;
  std::vector<ContactTile> bestTiles;
  double bestEver = -std::numeric_limits<double>::infinity();
  std::filesystem::path bestEverProgram;
  for (int generation = 0; generation < options.generations; ++generation) {
    const std::filesystem::path dir = out / generationName(generation, generationDigits);
    BatchDef batch;
    batch.dir = dir;
    batch.columns = columns;
    batch.count = population;
    batch.resume = options.sweep.resume;
    batch.workers = setup.workers;
    BatchProgressBar bar("evolving " + setup.stem + ", generation " + std::to_string(generation + 1) + "/" +
                             std::to_string(options.generations),
                         options.sweep.progress, cluster->leader());
    batch.progress = bar.callback();
    batch.stop = &BatchInterrupt::requested;
    nlohmann::json header = settings;
    header["generation"] = generation;
    std::string population_text;
    for (const Genome& genome : genomes)
      for (double value : genome.values) population_text += formatValue(value) + ",";
    header["population"] = textDigest(population_text);
    batch.header = header.dump();
    batch.thumbnail = [&setup, dir](uint64_t i) { return dir / "thumbnails" / (variantStem(setup, i) + ".png"); };
    if (const auto size = parsePictureSize(options.sweep.size)) {
      batch.sheet.tileWidth = size->first;
      batch.sheet.tileHeight = size->second;
    }
    batch.labelColumns = fitnessColumn - 1;  // the genes
    batch.leading = [&](uint64_t index) {
      std::vector<std::string> leading;
      for (double value : genomes[index].values) leading.push_back(formatValue(value));
      leading.push_back(std::to_string(seed));
      return leading;
    };
    batch.run = [&, dir, generation](uint64_t index) {
      const Genome& genome = genomes[index];
      std::vector<std::string> leading;
      std::string note = "// ontogen evolve of " + setup.path + ", generation " + std::to_string(generation) +
                         ", variant " + std::to_string(index) + "\n";
      for (double value : genome.values) leading.push_back(formatValue(value));
      return runSweepVariant(setup, dir, index, space.programText(genome), seed, std::move(leading), {}, note);
    };
    BatchResult result;
    {
      BatchInterrupt interrupt;
      result = runBatch(batch, *cluster);
    }
    const int code = bar.finish(result);
    if (code == kExitInterrupted && cluster->leader())
      std::cerr << "ontogen: stopped in generation " << generation << "; --resume continues the evolution\n";
    if (code != kExitOk) return code;

    // Rank by fitness, best first; ties go to the lower index, so the order is total.
    std::vector<double> fitness(population, -std::numeric_limits<double>::infinity());
    for (const SweepRow& row : result.table.rows)
      if (row.variant < population) fitness[row.variant] = fitnessOf(row, fitnessColumn);
    std::vector<size_t> ranked(population);
    for (size_t i = 0; i < population; ++i) ranked[i] = i;
    std::stable_sort(ranked.begin(), ranked.end(), [&](size_t a, size_t b) { return fitness[a] > fitness[b]; });
    GenerationSummary summary;
    summary.best = ranked[0];
    summary.bestFitness = fitness[ranked[0]];
    double sum = 0;
    size_t finite = 0;
    for (double value : fitness) {
      if (!std::isfinite(value)) continue;
      sum += value;
      ++finite;
    }
    summary.meanFitness = finite ? sum / static_cast<double>(finite) : std::numeric_limits<double>::quiet_NaN();
    summary.failed = result.failed;
    summaries.push_back(summary);
    const std::filesystem::path bestProgram = dir / "programs" / (variantStem(setup, summary.best) + ".cell");
    // The best of each generation, labelled with its generation and genes.
    const auto bestRow = std::find_if(result.table.rows.begin(), result.table.rows.end(),
                                      [&](const SweepRow& row) { return row.variant == summary.best; });
    const std::filesystem::path bestThumbnail = dir / "thumbnails" / (variantStem(setup, summary.best) + ".png");
    ContactTile bestTile = bestRow != result.table.rows.end()
                               ? galleryTile(bestThumbnail, result.table, *bestRow, fitnessColumn - 1)
                               : ContactTile{bestThumbnail, false, {}, 0};
    bestTile.failed = !std::isfinite(summary.bestFitness);
    bestTile.label = "G" + std::to_string(generation) + (bestTile.label.empty() ? "" : " ") + bestTile.label;
    bestTiles.push_back(std::move(bestTile));
    if (summary.bestFitness > bestEver || bestEverProgram.empty()) {
      bestEver = summary.bestFitness;
      bestEverProgram = bestProgram;
    }
    if (cluster->leader()) {
      try {
        std::error_code error;
        std::filesystem::create_directories(out / "best", error);
        const std::string text = [&] {
          std::ifstream in(bestProgram, std::ios::binary);
          std::ostringstream all;
          all << in.rdbuf();
          return all.str();
        }();
        writeFileAtomically(out / "best" / (generationName(generation, generationDigits) + ".cell"),
                            [&](std::ostream& file) { file << text; });
      } catch (const OutputError& error) {
        std::cerr << "ontogen: error: " << error.what() << "\n";
        return kExitOutputError;
      }
    }
    if (generation + 1 == options.generations) break;

    // The next generation: the elite as they are, then children of tournament winners
    // (two drawn at random, the fitter wins), bred by crossover or copied, then mutated.
    RandomStream stream(mixKey(mixKey(options.evolveSeed, kBreedSalt), static_cast<uint64_t>(generation + 1)));
    auto tournament = [&] {
      const size_t a = std::min(population - 1, static_cast<size_t>(stream.uniform() * static_cast<double>(population)));
      const size_t b = std::min(population - 1, static_cast<size_t>(stream.uniform() * static_cast<double>(population)));
      if (fitness[a] != fitness[b]) return fitness[a] > fitness[b] ? a : b;
      return std::min(a, b);
    };
    std::vector<Genome> next;
    for (int i = 0; i < options.elite; ++i) next.push_back(genomes[ranked[static_cast<size_t>(i)]]);
    while (next.size() < population) {
      const size_t a = tournament(), b = tournament();
      const bool cross = stream.uniform() < options.crossover;
      const uint64_t crossSeed = stream.next(), mutateSeed = stream.next();
      Genome child = cross ? space.crossover(genomes[a], genomes[b], crossSeed) : genomes[a];
      next.push_back(space.mutate(child, mutateSeed));
    }
    genomes = std::move(next);
  }

  if (!cluster->leader()) return kExitOk;
  try {
    const std::string fitnessName = setup.measures.front().name();
    writeFileAtomically(out / "evolution.csv", [&](std::ostream& file) {
      file << "generation,best_variant,best_" << fitnessName << ",mean_" << fitnessName << ",failed\n";
      for (size_t g = 0; g < summaries.size(); ++g)
        file << g << ',' << summaries[g].best << ',' << formatValue(summaries[g].bestFitness) << ','
             << formatValue(summaries[g].meanFitness) << ',' << summaries[g].failed << '\n';
    });
    std::ifstream in(bestEverProgram, std::ios::binary);
    std::ostringstream best;
    best << in.rdbuf();
    writeFileAtomically(out / "best.cell", [&](std::ostream& file) { file << best.str(); });
    ContactSheetDef sheet;
    if (const auto size = parsePictureSize(options.sweep.size)) {
      sheet.tileWidth = size->first;
      sheet.tileHeight = size->second;
    }
    const Image gallery = contactSheet(bestTiles, sheet);
    writeFileAtomically(out / "gallery.png", [&](std::ostream& file) { writePng(gallery, file); });
    writeFileAtomically(out / "gallery.json", [&](std::ostream& file) { writeContactSheetJson(bestTiles, sheet, file); });
  } catch (const OutputError& error) {
    std::cerr << "ontogen: error: " << error.what() << "\n";
    return kExitOutputError;
  }
  std::cerr << "evolved " << options.generations << " generation" << (options.generations == 1 ? "" : "s") << " of "
            << population << ": best " << setup.measures.front().name() << " " << formatValue(bestEver) << " ("
            << (out / "best.cell").string() << ")\n";
  return kExitOk;
}

}  // namespace ontogen::app
