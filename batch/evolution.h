#pragma once
// An evolution: a genetic algorithm over a program's genes (its #define values, and its
// numeric constants when asked), a generation at a time, each generation one batch
// (batch/batch_run.h) in OUT/generation_NNN, fitness the first measure, maximised. The
// first generation is the program and mutants of it; each next one keeps the elite and
// breeds the rest from tournament winners by crossover and mutation. Every draw comes
// from the evolution's seed, so a run, a resumed run and a run on several ranks make the
// same generations. What `ontogen evolve` runs after reading its command line. Nothing
// here prints: each generation's start, progress and end go to callbacks.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "batch/batch_run.h"
#include "batch/cluster.h"
#include "batch/sweep_setup.h"

namespace ontogen {

struct EvolutionDef {
  /// The program and what every variant runs; `settings.variation` holds the genes'
  /// mutation rate and strength, their ranges and whether constants are genes.
  SweepSettings settings;
  int generations = 10;
  int population = 12;
  int elite = 2;                  ///< the fittest kept as they are; below `population`
  double crossover = 0.7;         ///< chance a child is bred from two parents rather than one
  uint64_t evolveSeed = 1;        ///< of selection, crossover and mutation
  std::optional<uint64_t> seed;   ///< every variant's run; empty: the program's #seed
  std::vector<std::string> rangeTexts;  ///< the ranges as given (`NAME=LOW:HIGH`), for the journal's header
  std::filesystem::path out;      ///< the evolution's folder
  bool resume = false;            ///< continue the journals in `out`
  std::string sizeText;           ///< the thumbnails' size as given ("128x128"), for the journal's header
  std::function<bool()> stop;     ///< BatchDef::stop of every generation
  /// Called before generation g's batch runs and after it ended (with how), on the
  /// thread that called runEvolution; empty: none.
  std::function<void(int generation)> generationStarts;
  std::function<void(int generation, const BatchResult&)> generationEnds;
  std::function<void(const BatchProgress&)> progress;  ///< BatchDef::progress of every generation
};

/// One generation's fitness (the first measure): -infinity for a failed variant.
struct GenerationSummary {
  uint64_t best = 0;                ///< the fittest variant (the lower index on a tie)
  double bestFitness = 0;
  double meanFitness = 0;           ///< over the variants that grew; NaN when none did
  uint64_t failed = 0;
};

struct EvolutionResult {
  /// Done, or why the evolution ended early: a generation's batch (its status and
  /// message; `batchEnded` set), a refused definition, or an output not written.
  BatchStatus status = BatchStatus::Done;
  std::string message;               ///< why, unless Done or Stopped
  bool batchEnded = false;           ///< the status is that of generation `generation`'s batch
  int generation = 0;                ///< the generation it ended in
  std::vector<GenerationSummary> generations;
  double bestFitness = 0;            ///< the fittest variant of all generations
  std::filesystem::path best;        ///< OUT/best.cell, its program (rank 0 writes it)
  std::string fitnessName;           ///< the first measure's name
};

/// Why the definition's numbers cannot make an evolution (no measure, an elite not
/// below the population), or an empty string; what runEvolution refuses first.
std::string evolutionDefProblem(const EvolutionDef& def);

/// Runs the evolution into `def.out`: OUT/generation_NNN (each a batch's table, programs
/// and thumbnails), OUT/best/generation_NNN.cell, and at the end OUT/evolution.csv (a
/// generation a row), OUT/best.cell and OUT/gallery.png (each generation's fittest).
/// Every rank calls it with the same definition.
EvolutionResult runEvolution(EvolutionDef def, Cluster& cluster);

/// Runs an evolution on this machine alone.
EvolutionResult runEvolution(EvolutionDef def);

}  // namespace ontogen
