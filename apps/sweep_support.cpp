#include "apps/sweep_support.h"

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <thread>

#include "apps/cli_values.h"
#include "apps/program_loader.h"
#include "interpreters/output_file.h"
#include "interpreters/set_registry.h"

namespace ontogen::app {

namespace {

bool hasSet(const std::vector<std::string>& sets, std::string_view name) {
  return std::find(sets.begin(), sets.end(), name) != sets.end();
}

// A measure that reads a set's quantities needs that set among the variants' sets.
std::string missingSet(const Measure& measure, const std::vector<std::string>& sets) {
  for (QuantitySource source : measure.sources()) {
    const bool drawing = hasSet(sets, "geometry") || hasSet(sets, "creature") || hasSet(sets, "physics");
    const bool present = source == QuantitySource::World || (source == QuantitySource::Scene && drawing) ||
                         (source != QuantitySource::Scene && hasSet(sets, quantitySourceSet(source)));
    if (present) continue;
    if (source == QuantitySource::Scene)
      return "--measure " + measure.name() +
             " reads the bounding box of what the sets draw, and the variants run no set that draws (add "
             "--interpret geometry, or #interpret in the program)";
    const std::string set(quantitySourceSet(source));
    return "--measure " + measure.name() + " reads what the " + set + " set reports, and the variants run no " + set +
           " set (add --interpret " + set + ", or #interpret in the program)";
  }
  return {};
}

}  // namespace

std::string textDigest(const std::string& text) {
  uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : text) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  char buffer[20];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(hash));
  return buffer;
}

std::unique_ptr<Cluster> joinCluster() {
  try {
    return std::make_unique<Cluster>();
  } catch (const std::runtime_error& error) {
    std::cerr << "ontogen: error: " << error.what() << "\n";
    return nullptr;
  }
}

QuietFollowers::QuietFollowers(bool leader) {
  if (!leader) saved_ = std::cerr.rdbuf(nullptr);
}

QuietFollowers::~QuietFollowers() {
  if (!saved_) return;
  std::cerr.rdbuf(saved_);
  std::cerr.clear();
}

int prepareSweep(const SweepCommonOptions& options, VariationOptions variation,
                 const std::vector<std::string>& extraNames, SweepSetup& setup) {
  const CommonOptions& common = options.common;
  LoadedProgram loaded = loadProgram(common);
  if (!loaded.program) return loaded.exitCode;
  const Program& program = *loaded.program;
  ProgramText text = readProgramText(common.file, common.maxSourceBytes);
  if (!text.text) return text.exitCode;
  // The values given with --define (evolve's fixed ones) are written into the text, so
  // that every variant's program holds them.
  if (!common.defines.empty()) {
    VariationSpace all(*text.text);
    Genome genome = all.original();
    for (const ProgramDefine& define : program.defines) {
      if (!define.overridden) continue;
      bool gene = false;
      for (size_t i = 0; i < all.genes().size(); ++i)
        if (all.genes()[i].kind == Gene::Kind::Define && all.genes()[i].name == define.name) {
          genome.values[i] = define.value;
          gene = true;
        }
      if (!gene) {
        std::cerr << "ontogen: error: --define " << define.name << ": the program's #define " << define.name
                  << " is an expression, not a number; only a number can be written in\n";
        return kExitUsage;
      }
      variation.fixed.push_back(define.name);
    }
    text.text = all.programText(genome);
  }
  try {
    setup.space = std::make_unique<VariationSpace>(*text.text, variation);
  } catch (const std::invalid_argument& bad) {
    std::cerr << "ontogen: error: " << bad.what() << "\n";
    return kExitUsage;
  }
  setup.path = common.file;
  setup.stem = loaded.stem;
  setup.programSeed = program.seed;
  setup.sets = !options.sets.empty()               ? options.sets
               : !program.interpretSets.empty() ? program.interpretSets
                                                : std::vector<std::string>{"geometry"};
  const std::vector<std::string> known = interpretationSetNames();
  for (const std::string& set : setup.sets)
    if (!hasSet(known, set)) {
      std::string list;
      for (const std::string& name : known) list += (list.empty() ? "" : ", ") + name;
      std::cerr << "ontogen: error: --interpret: unknown interpretation set '" << set << "' (known: " << list << ")\n";
      return kExitUsage;
    }
  for (const std::string& given : options.measures) {
    try {
      setup.measures.push_back(parseMeasure(given, extraNames));
    } catch (const MeasureError& bad) {
      std::cerr << "ontogen: error: " << bad.what() << "\n";
      return kExitUsage;
    }
    const std::string& name = setup.measures.back().name();
    bool clash = hasSet(extraNames, name) || name == "seed" || name == "variant" || name == "error";
    for (size_t i = 0; i + 1 < setup.measures.size(); ++i) clash = clash || setup.measures[i].name() == name;
    if (clash) {
      std::cerr << "ontogen: error: --measure " << name << ": the name of another column of the table\n";
      return kExitUsage;
    }
    if (std::string missing = missingSet(setup.measures.back(), setup.sets); !missing.empty()) {
      std::cerr << "ontogen: error: " << missing << "\n";
      return kExitUsage;
    }
  }
  const std::optional<std::pair<int, int>> size = parsePictureSize(options.size);
  if (!size) {
    std::cerr << "ontogen: error: --size takes WIDTHxHEIGHT in pixels, as in 128x128, not '" << options.size << "'\n";
    return kExitUsage;
  }

  setup.compile.rootSystem = common.system;
  setup.compile.commandSets = commandSets();
  setup.compile.maxSourceBytes = common.maxSourceBytes;
  RunDef& run = setup.run;
  run.world.limits = common.limits;
  run.world.threads = 1;  // a variant is one task: the workers are the parallelism
  run.until = options.until;
  run.step = common.step;
  run.frames = options.frames;
  run.sets = setup.sets;
  run.setOptions.formats = "png";
  run.setOptions.render.width = size->first;
  run.setOptions.render.height = size->second;
  if (options.view.size() == 2) {
    run.setOptions.render.azimuth = options.view[0];
    run.setOptions.render.elevation = options.view[1];
  }
  if (options.until) setup.rerunFlags += " --until " + formatValue(*options.until);
  if (common.step) setup.rerunFlags += " --step " + formatValue(*common.step);
  if (options.frames) setup.rerunFlags += " --frames " + std::to_string(*options.frames);
  if (!common.system.empty()) setup.rerunFlags += " --system " + common.system;
  if (!options.sets.empty()) {
    std::string list;
    for (const std::string& set : options.sets) list += (list.empty() ? "" : ",") + set;
    setup.rerunFlags += " --interpret " + list;
  }
  setup.workers = options.workers > 0 ? options.workers : std::max(1u, std::thread::hardware_concurrency());
  return kExitOk;
}

std::string variantStem(const SweepSetup& setup, uint64_t index) {
  std::string number = std::to_string(index);
  if (static_cast<int>(number.size()) < setup.digits) number.insert(0, setup.digits - number.size(), '0');
  return "v" + number;
}

SweepRow runSweepVariant(const SweepSetup& setup, const std::filesystem::path& dir, uint64_t index,
                         const std::string& text, uint64_t seed, std::vector<std::string> leading,
                         std::vector<std::pair<std::string, double>> values, const std::string& note) {
  SweepRow row;
  row.variant = index;
  row.values = std::move(leading);
  row.values.push_back(std::to_string(seed));
  const size_t measuresAt = row.values.size();
  row.values.resize(measuresAt + setup.measures.size());
  try {
    const std::string stem = variantStem(setup, index);
    // The program as it ran, its values written in, and a note saying how to grow it alone.
    std::filesystem::create_directories(dir / "programs");
    writeFileAtomically(dir / "programs" / (stem + ".cell"), [&](std::ostream& out) {
      out << text;
      if (!text.empty() && text.back() != '\n') out << '\n';
      out << note << "// ontogen run " << stem << ".cell --seed " << seed << setup.rerunFlags << "\n";
    });
    VariantDef def;
    def.name = setup.path;
    def.text = text;
    def.compile = setup.compile;
    def.run = setup.run;
    def.run.world.seed = seed;
    def.run.out = dir / "thumbnails";
    def.run.stem = stem;
    def.measures = setup.measures;
    def.values = std::move(values);
    const VariantResult result = runVariant(std::move(def));
    for (size_t i = 0; i < result.measures.size(); ++i) row.values[measuresAt + i] = formatValue(result.measures[i]);
    row.error = result.error;
  } catch (const OutputError& error) {
    row.error = error.what();
  } catch (const std::exception& error) {
    row.error = std::string("internal error: ") + error.what();
  }
  return row;
}

}  // namespace ontogen::app
