#include <cmath>
#include <iostream>
#include <sstream>

#include "apps/cli_values.h"
#include "apps/commands.h"
#include "apps/program_loader.h"
#include "apps/sweep_terminal.h"
#include "batch/sweep.h"

namespace ontogen::app {

namespace {

/// --define NAME=A:B:N: N values from A to B, at most this many (a sweep of more values
/// of one define than a table of kMaxVariants rows holds is a mistyped N).
constexpr uint64_t kMaxDefineValues = kMaxVariants;

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
  SweepDef def;
  if (int code = readSweepSettings(common, def.settings); code != kExitOk) return code;
  def.seeds = {options.sweep.common.seed.value_or(def.settings.program->seed),
               options.sweep.common.seed.value_or(def.settings.program->seed)};
  if (!options.seeds.empty()) {
    if (options.sweep.common.seed) {
      std::cerr << "ontogen: error: --seed and --seeds: a sweep takes one of them\n";
      return kExitUsage;
    }
    const auto parsed = parseSeeds(options.seeds);
    if (!parsed) return kExitUsage;
    def.seeds = *parsed;
  }
  def.defines = std::move(defines);
  def.out = options.sweep.out;
  def.resume = options.sweep.resume;
  def.sizeText = options.sweep.size;
  def.stop = &BatchInterrupt::requested;
  BatchProgressBar bar("sweeping " + def.settings.stem, options.sweep.progress, cluster->leader());
  def.progress = bar.callback();
  const std::filesystem::path dir = def.out;
  SweepResult result;
  {
    BatchInterrupt interrupt;
    result = runSweep(std::move(def), *cluster);
  }
  const int code = bar.finish(result.batch);
  if (code == kExitInterrupted && cluster->leader())
    std::cerr << "ontogen: stopped: " << result.batch.table.rows.size() << " of " << result.count
              << " variants done, in " << (dir / "results.csv").string() << "; --resume finishes the sweep\n";
  if (code != kExitOk) return code;
  if (cluster->leader())
    std::cerr << "swept " << result.count << " variant" << (result.count == 1 ? "" : "s") << " ("
              << result.batch.failed << " failed) into " << (dir / "results.csv").string() << "\n";
  return kExitOk;
}

}  // namespace ontogen::app
