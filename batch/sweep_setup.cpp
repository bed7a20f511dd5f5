#include "batch/sweep_setup.h"

#include <algorithm>
#include <cstdio>
#include <thread>

#include "interpreters/output_file.h"
#include "interpreters/sweep/contact_sheet.h"
#include "interpreters/set_registry.h"

namespace ontogen {

namespace {

bool hasSet(const std::vector<std::string>& sets, std::string_view name) {
  return std::find(sets.begin(), sets.end(), name) != sets.end();
}

// A measure that reads a set's quantities needs that set among the variants' sets.
std::string missingSet(const Measure& measure, const std::vector<std::string>& sets) {
  for (QuantitySource source : measure.sources()) {
    const bool drawing = hasSet(sets, "geometry") || hasSet(sets, "creature") || hasSet(sets, "physics") ||
                         hasSet(sets, "dynamics");
    // The dynamics set reports a walk's quantities too, from its simulation.
    const bool present = source == QuantitySource::World || (source == QuantitySource::Scene && drawing) ||
                         (source != QuantitySource::Scene && hasSet(sets, quantitySourceSet(source))) ||
                         (source == QuantitySource::Creature && hasSet(sets, "dynamics"));
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

std::string prepareSweep(const SweepSettings& settings, SweepSetup& setup) {
  const Program& program = *settings.program;
  std::string text = settings.text;
  VariationOptions variation = settings.variation;
  // The values given to the program's defines (evolve's fixed ones) are written into the
  // text, so that every variant's program holds them.
  if (std::any_of(program.defines.begin(), program.defines.end(),
                  [](const ProgramDefine& define) { return define.overridden; })) {
    VariationSpace all(text);
    Genome genome = all.original();
    for (const ProgramDefine& define : program.defines) {
      if (!define.overridden) continue;
      bool gene = false;
      for (size_t i = 0; i < all.genes().size(); ++i)
        if (all.genes()[i].kind == Gene::Kind::Define && all.genes()[i].name == define.name) {
          genome.values[i] = define.value;
          gene = true;
        }
      if (!gene)
        return "--define " + define.name + ": the program's #define " + define.name +
               " is an expression, not a number; only a number can be written in";
      variation.fixed.push_back(define.name);
    }
    text = all.programText(genome);
  }
  try {
    setup.space = std::make_unique<VariationSpace>(text, variation);
  } catch (const std::invalid_argument& bad) {
    return bad.what();
  }
  setup.path = settings.path;
  setup.stem = settings.stem;
  setup.programSeed = program.seed;
  setup.sets = !settings.sets.empty()              ? settings.sets
               : !program.interpretSets.empty() ? program.interpretSets
                                                : std::vector<std::string>{"geometry"};
  const std::vector<std::string> known = interpretationSetNames();
  for (const std::string& set : setup.sets)
    if (!hasSet(known, set)) {
      std::string list;
      for (const std::string& name : known) list += (list.empty() ? "" : ", ") + name;
      return "--interpret: unknown interpretation set '" + set + "' (known: " + list + ")";
    }
  for (const std::string& given : settings.measures) {
    try {
      setup.measures.push_back(parseMeasure(given, settings.extraNames));
    } catch (const MeasureError& bad) {
      return bad.what();
    }
    const std::string& name = setup.measures.back().name();
    bool clash = hasSet(settings.extraNames, name) || name == "seed" || name == "variant" || name == "error";
    for (size_t i = 0; i + 1 < setup.measures.size(); ++i) clash = clash || setup.measures[i].name() == name;
    if (clash) return "--measure " + name + ": the name of another column of the table";
    if (std::string missing = missingSet(setup.measures.back(), setup.sets); !missing.empty()) return missing;
  }

  setup.compile.rootSystem = settings.system;
  setup.compile.commandSets = commandSets();
  setup.compile.maxSourceBytes = settings.maxSourceBytes;
  RunDef& run = setup.run;
  run.world.limits = settings.limits;
  run.world.threads = 1;  // a variant is one task: the workers are the parallelism
  run.until = settings.until;
  run.step = settings.step;
  run.frames = settings.frames;
  run.sets = setup.sets;
  run.setOptions.formats = "png";
  run.setOptions.render.width = settings.width;
  run.setOptions.render.height = settings.height;
  if (settings.view.size() == 2) {
    run.setOptions.render.azimuth = settings.view[0];
    run.setOptions.render.elevation = settings.view[1];
  }
  if (settings.until) setup.rerunFlags += " --until " + formatValue(*settings.until);
  if (settings.step) setup.rerunFlags += " --step " + formatValue(*settings.step);
  if (settings.frames) setup.rerunFlags += " --frames " + std::to_string(*settings.frames);
  if (!settings.system.empty()) setup.rerunFlags += " --system " + settings.system;
  if (!settings.sets.empty()) {
    std::string list;
    for (const std::string& set : settings.sets) list += (list.empty() ? "" : ",") + set;
    setup.rerunFlags += " --interpret " + list;
  }
  setup.workers = settings.workers > 0 ? settings.workers : std::max(1u, std::thread::hardware_concurrency());
  return {};
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
    const std::filesystem::path thumbnail = dir / "thumbnails" / (stem + ".png");
    if (result.pixelsPerUnit > 0 && std::filesystem::is_regular_file(thumbnail))
      writeThumbnailScale(thumbnail, result.pixelsPerUnit);
  } catch (const OutputError& error) {
    row.error = error.what();
  } catch (const std::exception& error) {
    row.error = std::string("internal error: ") + error.what();
  }
  return row;
}

}  // namespace ontogen
