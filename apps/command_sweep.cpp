#include <cmath>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "apps/cli_values.h"
#include "apps/cluster.h"
#include "apps/commands.h"
#include "apps/program_loader.h"
#include "apps/sweep_batch.h"
#include "apps/sweep_support.h"

namespace ontogen::app {

namespace {

/// --define NAME=A:B:N: N values from A to B, at most this many (a sweep of more values
/// of one define than a table of kMaxVariants rows holds is a mistyped N).
constexpr uint64_t kMaxDefineValues = kMaxVariants;

struct SweptDefine {
  std::string name;
  std::vector<double> values;
  std::vector<std::string> written;  // as the table writes them
};

// `NAME=A:B:N` or `NAME=v1,v2,...`; prints why not.
std::optional<SweptDefine> parseSweptDefine(const std::string& text) {
  const size_t equals = text.find('=');
  auto bad = [&](const std::string& why) -> std::optional<SweptDefine> {
    std::cerr << "ontogen: error: --define " << text << ": " << why
              << " (a sweep takes NAME=A:B:N, N values from A to B, or NAME=v1,v2,...)\n";
    return std::nullopt;
  };
  if (equals == std::string::npos || equals == 0) return bad("no NAME=");
  SweptDefine define;
  define.name = text.substr(0, equals);
  const std::string spec = text.substr(equals + 1);
  if (spec.find(':') != std::string::npos) {
    std::vector<std::string> parts;
    std::stringstream in(spec);
    for (std::string part; std::getline(in, part, ':');) parts.push_back(part);
    if (parts.size() != 3 || spec.back() == ':') return bad("'" + spec + "' is not A:B:N");
    const std::optional<double> a = parseReal(parts[0]), b = parseReal(parts[1]);
    const std::optional<uint64_t> n = parseWhole(parts[2]);
    if (!a || !b) return bad("A and B must be numbers");
    if (!n || *n < 1 || *n > kMaxDefineValues)
      return bad("N must be a whole number from 1 to " + std::to_string(kMaxDefineValues));
    if (*n == 1 && *a != *b) return bad("one value (N = 1) from A to B needs A = B");
    // (A (N-1-i) + B i) / (N-1): one rounding, so 0:1:11 gives 0.3, not 0.30000000000000004.
    for (uint64_t i = 0; i < *n; ++i) {
      const double value =
          *n == 1 ? *a : (*a * static_cast<double>(*n - 1 - i) + *b * static_cast<double>(i)) / static_cast<double>(*n - 1);
      if (!std::isfinite(value)) return bad("the values must be finite");
      define.values.push_back(value);
    }
  } else {
    std::stringstream in(spec);
    for (std::string part; std::getline(in, part, ',');) {
      const std::optional<double> value = parseReal(part);
      if (!value) return bad("'" + part + "' is not a number");
      define.values.push_back(*value);
    }
    if (define.values.empty() || spec.back() == ',') return bad("an empty list");
  }
  for (double value : define.values) define.written.push_back(formatValue(value));
  return define;
}

// `S1:S2` (inclusive) or `S`; prints why not.
std::optional<std::pair<uint64_t, uint64_t>> parseSeeds(const std::string& text) {
  const size_t colon = text.find(':');
  const std::optional<uint64_t> first = parseWhole(text.substr(0, colon));
  const std::optional<uint64_t> last = colon == std::string::npos ? first : parseWhole(text.substr(colon + 1));
  if (!first || !last || *last < *first) {
    std::cerr << "ontogen: error: --seeds takes S1:S2, whole numbers with S1 <= S2 (or one seed S), not '" << text
              << "'\n";
    return std::nullopt;
  }
  return std::make_pair(*first, *last);
}

}  // namespace

int runSweep(const SweepOptions& options) {
  const std::unique_ptr<Cluster> cluster = joinCluster();
  if (!cluster) return kExitUsage;
  QuietFollowers quiet(cluster->leader());

  std::vector<SweptDefine> defines;
  for (const std::string& text : options.sweep.common.defines) {
    std::optional<SweptDefine> define = parseSweptDefine(text);
    if (!define) return kExitUsage;
    for (const SweptDefine& other : defines)
      if (other.name == define->name) {
        std::cerr << "ontogen: error: --define " << define->name << " is given twice; a sweep takes one list a name\n";
        return kExitUsage;
      }
    defines.push_back(std::move(*define));
  }
  SweepCommonOptions common = options.sweep;
  common.common.defines.clear();  // swept, not fixed: written into each variant's text
  std::vector<std::string> names;
  for (const SweptDefine& define : defines) names.push_back(define.name);
  SweepSetup setup;
  if (int code = prepareSweep(common, {}, names, setup); code != kExitOk) return code;

  // Each swept define is a gene of the text: a #define whose value is one number.
  std::vector<std::vector<size_t>> genesOf;
  for (const SweptDefine& define : defines) {
    std::vector<size_t> genes;
    for (size_t i = 0; i < setup.space->genes().size(); ++i)
      if (setup.space->genes()[i].kind == Gene::Kind::Define && setup.space->genes()[i].name == define.name)
        genes.push_back(i);
    if (genes.empty()) {
      std::cerr << "ontogen: error: --define " << define.name << ": the program has no #define " << define.name
                << " whose value is a number (a sweep writes each value into the text; a #define that is an "
                   "expression follows the numbers it names)\n";
      return kExitUsage;
    }
    genesOf.push_back(std::move(genes));
  }
  std::pair<uint64_t, uint64_t> seeds{options.sweep.common.seed.value_or(setup.programSeed),
                                      options.sweep.common.seed.value_or(setup.programSeed)};
  if (!options.seeds.empty()) {
    if (options.sweep.common.seed) {
      std::cerr << "ontogen: error: --seed and --seeds: a sweep takes one of them\n";
      return kExitUsage;
    }
    const auto parsed = parseSeeds(options.seeds);
    if (!parsed) return kExitUsage;
    seeds = *parsed;
  }
  // The product, the first --define outermost and the seed innermost: row i is variant i.
  uint64_t count = 1;
  const uint64_t seedCount = seeds.second - seeds.first + 1;
  bool tooMany = seedCount == 0 || seedCount > kMaxVariants;
  for (const SweptDefine& define : defines) {
    if (tooMany) break;
    count *= define.values.size();
    tooMany = count > kMaxVariants;
  }
  if (!tooMany) {
    count *= seedCount;
    tooMany = count > kMaxVariants;
  }
  if (tooMany) {
    std::cerr << "ontogen: error: the sweep has more than " << kMaxVariants
              << " variants (the product of the --define lists and the --seeds)\n";
    return kExitUsage;
  }
  setup.digits = std::max<int>(4, static_cast<int>(std::to_string(count - 1).size()));

  BatchDef batch;
  batch.dir = options.sweep.out;
  batch.count = count;
  batch.resume = options.sweep.resume;
  batch.progress = options.sweep.progress;
  batch.workers = setup.workers;
  batch.label = "sweeping " + setup.stem;
  for (const SweptDefine& define : defines) batch.columns.push_back(define.name);
  batch.columns.push_back("seed");
  for (const Measure& measure : setup.measures) batch.columns.push_back(measure.name());
  {
    nlohmann::json header;
    header["ontogen"] = "sweep";
    header["program"] = setup.path;
    header["text"] = textDigest(setup.space->text());
    header["columns"] = batch.columns;
    nlohmann::json values = nlohmann::json::array();
    for (const SweptDefine& define : defines) values.push_back(define.written);
    header["defines"] = values;
    header["seeds"] = {seeds.first, seeds.second};
    nlohmann::json measures = nlohmann::json::array();
    for (const Measure& measure : setup.measures) measures.push_back(measure.name() + "=" + measure.text());
    header["measures"] = measures;
    header["run"] = setup.rerunFlags;
    header["size"] = options.sweep.size;
    header["view"] = options.sweep.view;
    header["limits"] = {setup.run.world.limits.maxCells, setup.run.world.limits.maxEventsPerStep,
                        setup.run.world.limits.maxSteps, setup.run.world.limits.maxMemoryBytes};
    batch.header = header.dump();
  }
  const std::filesystem::path dir = options.sweep.out;
  batch.thumbnail = [&setup, dir](uint64_t i) { return dir / "thumbnails" / (variantStem(setup, i) + ".png"); };
  if (const auto size = parsePictureSize(options.sweep.size)) {
    batch.sheet.tileWidth = size->first;
    batch.sheet.tileHeight = size->second;
  }
  batch.run = [&](uint64_t index) {
    // Mixed radix: the seed varies fastest, then the last define, ..., then the first.
    uint64_t rest = index;
    const uint64_t seed = seeds.first + rest % seedCount;
    rest /= seedCount;
    std::vector<size_t> choice(defines.size());
    for (size_t d = defines.size(); d-- > 0;) {
      choice[d] = static_cast<size_t>(rest % defines[d].values.size());
      rest /= defines[d].values.size();
    }
    Genome genome = setup.space->original();
    std::vector<std::string> leading;
    std::vector<std::pair<std::string, double>> values;
    std::string note = "// ontogen sweep of " + setup.path + ", variant " + std::to_string(index) + ":";
    for (size_t d = 0; d < defines.size(); ++d) {
      const double value = defines[d].values[choice[d]];
      for (size_t gene : genesOf[d]) genome.values[gene] = value;
      leading.push_back(defines[d].written[choice[d]]);
      values.emplace_back(defines[d].name, value);
      note += " " + defines[d].name + " = " + defines[d].written[choice[d]] + ",";
    }
    note += " seed " + std::to_string(seed) + "\n";
    return runSweepVariant(setup, dir, index, setup.space->programText(genome), seed, std::move(leading),
                           std::move(values), note);
  };

  const BatchResult result = runBatch(batch, *cluster);
  if (result.exitCode == kExitInterrupted && cluster->leader())
    std::cerr << "ontogen: stopped: " << result.table.rows.size() << " of " << count << " variants done, in "
              << (dir / "results.csv").string() << "; --resume finishes the sweep\n";
  if (result.exitCode != kExitOk) return result.exitCode;
  if (cluster->leader())
    std::cerr << "swept " << count << " variant" << (count == 1 ? "" : "s") << " (" << result.failed
              << " failed) into " << (dir / "results.csv").string() << "\n";
  return kExitOk;
}

}  // namespace ontogen::app
