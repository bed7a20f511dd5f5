#include "batch/sweep.h"

#include <algorithm>

#include <nlohmann/json.hpp>

namespace ontogen {

SweepResult runSweep(SweepDef def, Cluster& cluster) {
  SweepResult result;
  auto refuse = [&result](std::string message) {
    result.batch.status = BatchStatus::Refused;
    result.batch.message = std::move(message);
    return result;
  };
  for (size_t d = 0; d < def.defines.size(); ++d) {
    if (def.defines[d].values.empty()) return refuse("--define " + def.defines[d].name + ": no values");
    for (size_t e = 0; e < d; ++e)
      if (def.defines[e].name == def.defines[d].name)
        return refuse("--define " + def.defines[d].name + " is given twice; a sweep takes one list a name");
  }
  std::vector<SweptDefine>& defines = def.defines;
  for (SweptDefine& define : defines) {
    if (define.written.size() != define.values.size()) {
      define.written.clear();
      for (double value : define.values) define.written.push_back(formatValue(value));
    }
    def.settings.extraNames.push_back(define.name);
  }
  SweepSetup setup;
  if (std::string why = prepareSweep(def.settings, setup); !why.empty()) return refuse(why);
  result.stem = setup.stem;

  // Each swept define is a gene of the text: a #define whose value is one number.
  std::vector<std::vector<size_t>> genesOf;
  for (const SweptDefine& define : defines) {
    std::vector<size_t> genes;
    for (size_t i = 0; i < setup.space->genes().size(); ++i)
      if (setup.space->genes()[i].kind == Gene::Kind::Define && setup.space->genes()[i].name == define.name)
        genes.push_back(i);
    if (genes.empty())
      return refuse("--define " + define.name + ": the program has no #define " + define.name +
                    " whose value is a number (a sweep writes each value into the text; a #define that is an "
                    "expression follows the numbers it names)");
    genesOf.push_back(std::move(genes));
  }
  const std::pair<uint64_t, uint64_t> seeds = def.seeds;
  // The product, the first --define outermost and the seed innermost: row i is variant i.
  uint64_t count = 1;
  const uint64_t seedCount = seeds.second - seeds.first + 1;
  bool tooMany = seeds.second < seeds.first || seedCount == 0 || seedCount > kMaxSweepVariants;
  for (const SweptDefine& define : defines) {
    if (tooMany) break;
    count *= define.values.size();
    tooMany = count > kMaxSweepVariants;
  }
  if (!tooMany) {
    count *= seedCount;
    tooMany = count > kMaxSweepVariants;
  }
  if (tooMany)
    return refuse("the sweep has more than " + std::to_string(kMaxSweepVariants) +
                  " variants (the product of the --define lists and the --seeds)");
  result.count = count;
  setup.digits = std::max<int>(4, static_cast<int>(std::to_string(count - 1).size()));

  BatchDef batch;
  batch.dir = def.out;
  batch.count = count;
  batch.resume = def.resume;
  batch.workers = setup.workers;
  batch.stop = def.stop;
  batch.progress = def.progress;
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
    header["size"] = def.sizeText.empty() ? std::to_string(def.settings.width) + "x" +
                                                std::to_string(def.settings.height)
                                          : def.sizeText;
    header["view"] = def.settings.view;
    header["limits"] = {setup.run.world.limits.maxCells, setup.run.world.limits.maxEventsPerStep,
                        setup.run.world.limits.maxSteps, setup.run.world.limits.maxMemoryBytes};
    batch.header = header.dump();
  }
  const std::filesystem::path dir = def.out;
  batch.thumbnail = [&setup, dir](uint64_t i) { return dir / "thumbnails" / (variantStem(setup, i) + ".png"); };
  batch.sheet.tileWidth = def.settings.width;
  batch.sheet.tileHeight = def.settings.height;
  // The tiles are labelled with the defines, and with the seed when there are several.
  batch.labelColumns = defines.size() + (seedCount > 1 ? 1 : 0);
  // Mixed radix: the seed varies fastest, then the last define, ..., then the first.
  auto variantOf = [&](uint64_t index, std::vector<size_t>& choice) {
    uint64_t rest = index;
    const uint64_t seed = seeds.first + rest % seedCount;
    rest /= seedCount;
    choice.assign(defines.size(), 0);
    for (size_t d = defines.size(); d-- > 0;) {
      choice[d] = static_cast<size_t>(rest % defines[d].values.size());
      rest /= defines[d].values.size();
    }
    return seed;
  };
  batch.leading = [&](uint64_t index) {
    std::vector<size_t> choice;
    const uint64_t seed = variantOf(index, choice);
    std::vector<std::string> leading;
    for (size_t d = 0; d < defines.size(); ++d) leading.push_back(defines[d].written[choice[d]]);
    leading.push_back(std::to_string(seed));
    return leading;
  };
  batch.run = [&](uint64_t index) {
    std::vector<size_t> choice;
    const uint64_t seed = variantOf(index, choice);
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
  result.batch = runBatch(batch, cluster);
  return result;
}

SweepResult runSweep(SweepDef def) {
  Cluster alone(Cluster::Join::Alone);
  return runSweep(std::move(def), alone);
}

}  // namespace ontogen
