#include "batch/evolution.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "interpreters/formats/png_writer.h"
#include "interpreters/output_file.h"
#include "model/random.h"

namespace ontogen {

namespace {

// Salts of the evolution's random streams: the first generation's mutations, and the
// choices that breed generation g from g - 1.
constexpr uint64_t kFirstGenerationSalt = 0x6576'6f6c'7665'3030ull;  // "evolve00"
constexpr uint64_t kBreedSalt = 0x6272'6565'6400'0000ull;            // "breed"

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

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream all;
  all << in.rdbuf();
  return all.str();
}

// Columns: a gene each (a define's name; a second #define of one name, or a constant, by
// its place), the seed, the measures.
std::vector<std::string> columnsOf(const SweepSetup& setup) {
  std::vector<std::string> columns;
  for (const Gene& gene : setup.space->genes()) {
    std::string name = gene.kind == Gene::Kind::Define ? gene.name : "constant@" + gene.name;
    if (std::find(columns.begin(), columns.end(), name) != columns.end()) name += "@" + std::to_string(gene.line);
    columns.push_back(name);
  }
  columns.push_back("seed");
  for (const Measure& measure : setup.measures) columns.push_back(measure.name());
  return columns;
}

// The settings every generation's journal header holds; a resumed journal must match.
nlohmann::json headerOf(const EvolutionDef& def, const SweepSetup& setup, const std::vector<std::string>& columns,
                        uint64_t seed) {
  nlohmann::json settings;
  settings["ontogen"] = "evolve";
  settings["program"] = setup.path;
  settings["text"] = textDigest(setup.space->text());
  settings["columns"] = columns;
  nlohmann::json measures = nlohmann::json::array();
  for (const Measure& measure : setup.measures) measures.push_back(measure.name() + "=" + measure.text());
  settings["measures"] = measures;
  settings["seed"] = seed;
  const VariationOptions& variation = def.settings.variation;
  settings["evolve"] = {def.population, def.elite, def.crossover, variation.rate, variation.strength, def.evolveSeed,
                        variation.constants};
  settings["ranges"] = def.rangeTexts;
  settings["run"] = setup.rerunFlags;
  settings["size"] = def.sizeText.empty()
                         ? std::to_string(def.settings.width) + "x" + std::to_string(def.settings.height)
                         : def.sizeText;
  settings["view"] = def.settings.view;
  settings["limits"] = {setup.run.world.limits.maxCells, setup.run.world.limits.maxEventsPerStep,
                        setup.run.world.limits.maxSteps, setup.run.world.limits.maxMemoryBytes};
  return settings;
}

// Variants ranked by fitness, best first; ties go to the lower index, so the order is total.
std::vector<size_t> rankOf(const std::vector<double>& fitness) {
  std::vector<size_t> ranked(fitness.size());
  for (size_t i = 0; i < ranked.size(); ++i) ranked[i] = i;
  std::stable_sort(ranked.begin(), ranked.end(), [&](size_t a, size_t b) { return fitness[a] > fitness[b]; });
  return ranked;
}

GenerationSummary summaryOf(const std::vector<double>& fitness, const std::vector<size_t>& ranked, uint64_t failed) {
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
  summary.failed = failed;
  return summary;
}

// The next generation: the elite as they are, then children of tournament winners (two
// drawn at random, the fitter wins), bred by crossover or copied, then mutated.
std::vector<Genome> breed(const EvolutionDef& def, const VariationSpace& space, const std::vector<Genome>& genomes,
                          const std::vector<double>& fitness, const std::vector<size_t>& ranked, int nextGeneration) {
  const size_t population = genomes.size();
  RandomStream stream(mixKey(mixKey(def.evolveSeed, kBreedSalt), static_cast<uint64_t>(nextGeneration)));
  auto tournament = [&] {
    const size_t a = std::min(population - 1, static_cast<size_t>(stream.uniform() * static_cast<double>(population)));
    const size_t b = std::min(population - 1, static_cast<size_t>(stream.uniform() * static_cast<double>(population)));
    if (fitness[a] != fitness[b]) return fitness[a] > fitness[b] ? a : b;
    return std::min(a, b);
  };
  std::vector<Genome> next;
  for (int i = 0; i < def.elite; ++i) next.push_back(genomes[ranked[static_cast<size_t>(i)]]);
  while (next.size() < population) {
    const size_t a = tournament(), b = tournament();
    const bool cross = stream.uniform() < def.crossover;
    const uint64_t crossSeed = stream.next(), mutateSeed = stream.next();
    Genome child = cross ? space.crossover(genomes[a], genomes[b], crossSeed) : genomes[a];
    next.push_back(space.mutate(child, mutateSeed));
  }
  return next;
}

}  // namespace

std::string evolutionDefProblem(const EvolutionDef& def) {
  if (def.settings.measures.empty())
    return "evolve needs a fitness: --measure NAME=EXPR (the first --measure is maximised)";
  if (def.elite >= def.population)
    return "--elite " + std::to_string(def.elite) + " must be below --population " + std::to_string(def.population) +
           " (the elite are kept and the rest bred)";
  if (def.generations < 1 || def.population < 2 || def.elite < 0)
    return "an evolution needs a generation or more, a population of 2 or more and no negative elite";
  return "";
}

EvolutionResult runEvolution(EvolutionDef def, Cluster& cluster) {
  EvolutionResult result;
  auto refuse = [&result](BatchStatus status, std::string message) {
    result.status = status;
    result.message = std::move(message);
    return result;
  };
  if (std::string why = evolutionDefProblem(def); !why.empty()) return refuse(BatchStatus::Refused, why);
  SweepSetup setup;
  if (std::string why = prepareSweep(def.settings, setup); !why.empty()) return refuse(BatchStatus::Refused, why);
  const VariationSpace& space = *setup.space;
  if (space.genes().empty())
    return refuse(BatchStatus::Refused,
                  setup.path + " has nothing to evolve: no #define NAME NUMBER that is not fixed by --define" +
                      (def.settings.variation.constants ? " and no numeric constant"
                                                        : " (--vary-constants also varies its constants)"));
  result.fitnessName = setup.measures.front().name();
  const uint64_t seed = def.seed.value_or(setup.programSeed);
  const size_t population = static_cast<size_t>(def.population);
  setup.digits = std::max<int>(4, static_cast<int>(std::to_string(population - 1).size()));
  const int generationDigits = std::max<int>(3, static_cast<int>(std::to_string(def.generations - 1).size()));
  const std::vector<std::string> columns = columnsOf(setup);
  const size_t fitnessColumn = space.genes().size() + 1;
  const nlohmann::json settings = headerOf(def, setup, columns, seed);

  const std::filesystem::path out = def.out;
  std::vector<Genome> genomes;
  {
    RandomStream stream(mixKey(def.evolveSeed, kFirstGenerationSalt));
    genomes.push_back(space.original());
    while (genomes.size() < population) genomes.push_back(space.mutate(space.original(), stream.next()));
  }
  std::vector<ContactTile> bestTiles;
  double bestEver = -std::numeric_limits<double>::infinity();
  std::filesystem::path bestEverProgram;
  for (int generation = 0; generation < def.generations; ++generation) {
    result.generation = generation;
    const std::filesystem::path dir = out / generationName(generation, generationDigits);
    BatchDef batch;
    batch.dir = dir;
    batch.columns = columns;
    batch.count = population;
    batch.resume = def.resume;
    batch.workers = setup.workers;
    batch.progress = def.progress;
    batch.stop = def.stop;
    nlohmann::json header = settings;
    header["generation"] = generation;
    std::string populationText;
    for (const Genome& genome : genomes)
      for (double value : genome.values) populationText += formatValue(value) + ",";
    header["population"] = textDigest(populationText);
    batch.header = header.dump();
    batch.thumbnail = [&setup, dir](uint64_t i) { return dir / "thumbnails" / (variantStem(setup, i) + ".png"); };
    batch.sheet.tileWidth = def.settings.width;
    batch.sheet.tileHeight = def.settings.height;
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
    if (def.generationStarts) def.generationStarts(generation);
    const BatchResult batchResult = runBatch(batch, cluster);
    if (def.generationEnds) def.generationEnds(generation, batchResult);
    if (batchResult.status != BatchStatus::Done) {
      result.batchEnded = true;
      return refuse(batchResult.status, batchResult.message);
    }

    std::vector<double> fitness(population, -std::numeric_limits<double>::infinity());
    for (const SweepRow& row : batchResult.table.rows)
      if (row.variant < population) fitness[row.variant] = fitnessOf(row, fitnessColumn);
    const std::vector<size_t> ranked = rankOf(fitness);
    const GenerationSummary summary = summaryOf(fitness, ranked, batchResult.failed);
    result.generations.push_back(summary);
    const std::filesystem::path bestProgram = dir / "programs" / (variantStem(setup, summary.best) + ".cell");
    // The best of each generation, labelled with its generation and genes.
    const auto bestRow = std::find_if(batchResult.table.rows.begin(), batchResult.table.rows.end(),
                                      [&](const SweepRow& row) { return row.variant == summary.best; });
    const std::filesystem::path bestThumbnail = dir / "thumbnails" / (variantStem(setup, summary.best) + ".png");
    ContactTile bestTile = bestRow != batchResult.table.rows.end()
                               ? galleryTile(bestThumbnail, batchResult.table, *bestRow, fitnessColumn - 1)
                               : ContactTile{bestThumbnail, false, {}, 0};
    bestTile.failed = !std::isfinite(summary.bestFitness);
    bestTile.label = "G" + std::to_string(generation) + (bestTile.label.empty() ? "" : " ") + bestTile.label;
    bestTiles.push_back(std::move(bestTile));
    if (summary.bestFitness > bestEver || bestEverProgram.empty()) {
      bestEver = summary.bestFitness;
      bestEverProgram = bestProgram;
    }
    if (cluster.leader()) {
      try {
        std::error_code error;
        std::filesystem::create_directories(out / "best", error);
        const std::string text = readFile(bestProgram);
        writeFileAtomically(out / "best" / (generationName(generation, generationDigits) + ".cell"),
                            [&](std::ostream& file) { file << text; });
      } catch (const OutputError& error) {
        return refuse(BatchStatus::OutputError, error.what());
      }
    }
    if (generation + 1 == def.generations) break;
    genomes = breed(def, space, genomes, fitness, ranked, generation + 1);
  }
  result.bestFitness = bestEver;
  result.best = out / "best.cell";

  if (!cluster.leader()) return result;
  try {
    writeFileAtomically(out / "evolution.csv", [&](std::ostream& file) {
      file << "generation,best_variant,best_" << result.fitnessName << ",mean_" << result.fitnessName << ",failed\n";
      for (size_t g = 0; g < result.generations.size(); ++g)
        file << g << ',' << result.generations[g].best << ',' << formatValue(result.generations[g].bestFitness)
             << ',' << formatValue(result.generations[g].meanFitness) << ',' << result.generations[g].failed << '\n';
    });
    const std::string best = readFile(bestEverProgram);
    writeFileAtomically(result.best, [&](std::ostream& file) { file << best; });
    ContactSheetDef sheet;
    sheet.tileWidth = def.settings.width;
    sheet.tileHeight = def.settings.height;
    const Image gallery = contactSheet(bestTiles, sheet);
    writeFileAtomically(out / "gallery.png", [&](std::ostream& file) { writePng(gallery, file); });
    writeFileAtomically(out / "gallery.json", [&](std::ostream& file) { writeContactSheetJson(bestTiles, sheet, file); });
  } catch (const OutputError& error) {
    return refuse(BatchStatus::OutputError, error.what());
  }
  return result;
}

EvolutionResult runEvolution(EvolutionDef def) {
  Cluster alone(Cluster::Join::Alone);
  return runEvolution(std::move(def), alone);
}

}  // namespace ontogen
