#include "studio/gallery.h"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "interpreters/output_file.h"
#include "interpreters/run.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"
#include "model/random.h"
#include "studio/file_bytes.h"

namespace ontogen::studio {

namespace {
// Salts that keep a generation's mutations and crossovers apart.
constexpr uint64_t kMutationSalt = 0x6d75746174696f6eull;   // "mutation"
constexpr uint64_t kCrossoverSalt = 0x63726f73736f7665ull;  // "crossove"

}  // namespace

Gallery::Gallery(GalleryDef def)
    : def_(std::move(def)),
      limits_{def_.program.limits.maxCells, def_.program.limits.maxMemoryBytes, def_.program.limits.maxCells,
              def_.program.limits.maxMemoryBytes} {
  if (def_.size < 1 || def_.size > 64) throw std::invalid_argument("a gallery holds 1 to 64 variants");
}

uint64_t Gallery::seedOf(int index, uint64_t salt) const {
  return mixKey(mixKey(def_.seed, salt), mixKey(static_cast<uint64_t>(generation_), static_cast<uint64_t>(index)));
}

void Gallery::reset(const std::string& text, const std::string& stem) {
  VariationOptions options;
  options.constants = def_.constants;
  space_ = std::make_unique<VariationSpace>(text, options);
  text_ = text;
  stem_ = stem;
  generation_ = 1;
  ++epoch_;
  variants_.clear();
  held_.clear();
  // The program as written, then each define at the ends of its range that differ from
  // its value, the low end first (probeNeeded skips the high one when the low one differed).
  probes_.assign(1, Probe{});
  for (std::size_t g = 0; g < space_->genes().size(); ++g) {
    const Gene& gene = space_->genes()[g];
    if (gene.kind != Gene::Kind::Define) continue;
    for (const double end : {gene.low, gene.high})
      if (end != gene.value) probes_.push_back({static_cast<int>(g), end, false, {}});
  }
  probing_ = probes_.size() > 1;
  if (!probing_) {
    // Nothing to probe: the program as written grows as variant 0.
    probes_.clear();
    decideFirstGeneration();
  }
}

bool Gallery::changesThePicture(const Probe& probe) const {
  const GalleryPicture& written = probes_.front().picture;
  return probe.picture.png != written.png || (probe.picture.png.empty() && probe.picture.error != written.error);
}

bool Gallery::probeNeeded(std::size_t index) const {
  // A high end is not needed when the low end of the same define already changed the picture.
  for (std::size_t i = 1; i < index; ++i)
    if (probes_[i].gene == probes_[index].gene && probes_[i].grown && changesThePicture(probes_[i])) return false;
  return true;
}

void Gallery::decideFirstGeneration() {
  probing_ = false;
  std::vector<std::string> changing;
  for (std::size_t i = 1; i < probes_.size(); ++i)
    if (probes_[i].grown && changesThePicture(probes_[i]))
      changing.push_back(space_->genes()[static_cast<std::size_t>(probes_[i].gene)].name);
  for (const Gene& gene : space_->genes())
    if (gene.kind == Gene::Kind::Define && std::find(changing.begin(), changing.end(), gene.name) == changing.end() &&
        std::find(held_.begin(), held_.end(), gene.name) == held_.end())
      held_.push_back(gene.name);
  if (!held_.empty()) {
    VariationOptions options = space_->options();
    options.fixed = held_;
    space_ = std::make_unique<VariationSpace>(text_, options);
  }
  variants_.assign(static_cast<std::size_t>(def_.size), {});
  const Genome original = space_->original();
  for (int i = 0; i < def_.size; ++i) {
    GalleryVariant& variant = variants_[static_cast<std::size_t>(i)];
    // The first stays the program as written, so every gallery shows where it started.
    variant.genome = i == 0 || space_->genes().empty() ? original : space_->mutate(original, seedOf(i, kMutationSalt));
  }
  writeVariantTexts();
  // The program as written grew as the first probe: its variants need not grow again.
  if (probes_.empty() || !probes_.front().grown) return;
  for (GalleryVariant& variant : variants_)
    if (variant.text == text_) {
      variant.png = probes_.front().picture.png;
      variant.error = probes_.front().picture.error;
      variant.grown = true;
    }
}

void Gallery::writeVariantTexts() {
  for (GalleryVariant& variant : variants_) variant.text = space_->programText(variant.genome);
}

void Gallery::breed(const std::vector<int>& picked) {
  if (!space_) throw std::invalid_argument("the gallery has no program yet");
  if (probing_)
    throw std::invalid_argument("the gallery is still finding which #defines change the picture; breed once it shows "
                                "its variants");
  if (picked.empty()) throw std::invalid_argument("pick at least one variant to breed from");
  for (int index : picked)
    if (index < 0 || index >= static_cast<int>(variants_.size()))
      throw std::invalid_argument("no variant " + std::to_string(index));
  const std::vector<GalleryVariant> parents = variants_;
  ++generation_;
  variants_.assign(static_cast<std::size_t>(def_.size), {});
  const int kept = std::min(static_cast<int>(picked.size()), def_.size);
  for (int i = 0; i < def_.size; ++i) {
    GalleryVariant& child = variants_[static_cast<std::size_t>(i)];
    if (i < kept) {
      child.genome = parents[static_cast<std::size_t>(picked[static_cast<std::size_t>(i)])].genome;
      child.parents = {picked[static_cast<std::size_t>(i)]};
    } else {
      const int k = i - kept;
      const int a = picked[static_cast<std::size_t>(k) % picked.size()];
      const int b = picked[static_cast<std::size_t>(k + 1 + k / static_cast<int>(picked.size())) % picked.size()];
      const Genome mixed = space_->crossover(parents[static_cast<std::size_t>(a)].genome,
                                             parents[static_cast<std::size_t>(b)].genome, seedOf(i, kCrossoverSalt));
      child.genome = space_->genes().empty() ? mixed : space_->mutate(mixed, seedOf(i, kMutationSalt));
      child.parents = a == b ? std::vector<int>{a} : std::vector<int>{a, b};
    }
  }
  ++epoch_;
  writeVariantTexts();
}

std::optional<GalleryTask> Gallery::nextTask() const {
  if (probing_) {
    for (std::size_t i = 0; i < probes_.size(); ++i) {
      if (probes_[i].grown || !probeNeeded(i)) continue;
      Genome genome = space_->original();
      if (probes_[i].gene >= 0) genome.values[static_cast<std::size_t>(probes_[i].gene)] = probes_[i].value;
      return GalleryTask{epoch_, static_cast<int>(i), true, space_->programText(genome), stem_, limits_};
    }
    return std::nullopt;
  }
  for (std::size_t i = 0; i < variants_.size(); ++i)
    if (!variants_[i].grown) return GalleryTask{epoch_, static_cast<int>(i), false, variants_[i].text, stem_, limits_};
  return std::nullopt;
}

int Gallery::grown() const {
  int count = 0;
  for (const GalleryVariant& variant : variants_) count += variant.grown ? 1 : 0;
  return count;
}

void Gallery::keep(const GalleryTask& task, GalleryPicture picture) {
  if (task.epoch != epoch_ || task.index < 0) return;
  if (task.probe) {
    if (!probing_ || task.index >= static_cast<int>(probes_.size())) return;
    Probe& probe = probes_[static_cast<std::size_t>(task.index)];
    probe.picture = std::move(picture);
    probe.grown = true;
    if (!nextTask()) decideFirstGeneration();
    return;
  }
  if (probing_ || task.index >= static_cast<int>(variants_.size())) return;
  GalleryVariant& variant = variants_[static_cast<std::size_t>(task.index)];
  variant.png = std::move(picture.png);
  variant.error = std::move(picture.error);
  variant.grown = true;
}

void Gallery::growAll() {
  while (const std::optional<GalleryTask> task = nextTask()) keep(*task, grow(*task));
}

GalleryPicture Gallery::grow(const GalleryTask& task, const std::atomic<bool>* cancel) const {
  GalleryPicture picture;
  DiagnosticSink sink(1);
  CompileOptions options;
  options.commandSets = commandSets();
  options.rootSystem = def_.program.system;
  options.maxSourceBytes = def_.program.maxSourceBytes;
  const std::string name = (def_.saveTo / (task.stem + ".cell")).string();
  std::shared_ptr<const Program> program;
  try {
    program = compileSource(name, task.text, sink, options);
  } catch (const std::exception& error) {
    picture.error = error.what();
    return picture;
  }
  if (!program) {
    picture.error = sink.diagnostics().empty() ? "the variant does not compile" : sink.diagnostics().front().message;
    return picture;
  }
  RunDef run;
  run.program = program;
  run.stem = "variant";
  run.world = worldDefOf(def_.program, *program);
  run.world.limits.cancel = cancel;
  const WorldLimits& ceiling = def_.program.limits;
  const InteractiveLimits limits =
      task.limits.maxCells > 0
          ? task.limits
          : InteractiveLimits{ceiling.maxCells, ceiling.maxMemoryBytes, ceiling.maxCells, ceiling.maxMemoryBytes};
  run.world.limits.maxCells = limits.maxCells;
  run.world.limits.maxMemoryBytes = limits.maxMemoryBytes;
  run.until = def_.until;
  run.step = def_.program.step;
  run.frames = 1;
  run.sets = {"geometry"};
  for (const std::string& set : program->interpretSets)
    if (set == "image" || set == "creature" || set == "physics") run.sets = {set};
  run.setOptions.formats = "png";
  run.setOptions.render.width = def_.thumbnailSide;
  run.setOptions.render.height = def_.thumbnailSide;
  run.out = def_.work / ((task.probe ? "probe" : "variant") + std::to_string(task.index));
  std::filesystem::remove_all(run.out);
  Run grown(std::move(run));
  const RunReport report = grown.execute();
  if (!report.ok()) {
    picture.error =
        report.diagnostics.empty() ? "the variant failed" : limits.worded(report.diagnostics.front().message);
    return picture;
  }
  for (const std::filesystem::path& file : report.files)
    if (file.extension() == ".png") picture.png = readFileBytes(file);
  if (picture.png.empty()) picture.error = "the variant draws nothing to picture";
  return picture;
}

namespace {
// A file name of letters, digits, '_', '-' and inner dots only: no separator, no "..", no
// hidden file, so a saved variant lands in the save folder whatever its stem.
std::string fileNamePart(const std::string& stem) {
  std::string part;
  for (const char c : stem) {
    const bool plain = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
    if (part.empty() && c == '.') continue;
    part += plain && !(c == '.' && part.back() == '.') ? c : '_';
  }
  return part.empty() ? std::string("variant") : part;
}
}  // namespace

std::filesystem::path Gallery::save(int index) const {
  if (!space_ || index < 0 || index >= static_cast<int>(variants_.size()))
    throw std::invalid_argument("no variant " + std::to_string(index));
  const std::filesystem::path path =
      def_.saveTo / (fileNamePart(stem_) + "_g" + std::to_string(generation_) + "_v" + std::to_string(index) + ".cell");
  const std::string& text = variants_[static_cast<std::size_t>(index)].text;
  writeFileAtomically(path, [&text](std::ostream& out) { out << text; });
  return path;
}

nlohmann::json Gallery::state() const {
  const int grownSoFar = grown();
  int probes = 0, probed = 0;
  for (std::size_t i = 0; i < probes_.size(); ++i) {
    probes += probes_[i].grown || probeNeeded(i) ? 1 : 0;
    probed += probes_[i].grown ? 1 : 0;
  }
  nlohmann::json state = {{"generation", generation_},
                          {"epoch", epoch_},
                          {"seed", def_.seed},
                          {"grown", grownSoFar},
                          {"growing", probing_ || grownSoFar < static_cast<int>(variants_.size())},
                          {"probing", probing_},
                          {"probes", probes},
                          {"probed", probed},
                          {"held", held_}};
  nlohmann::json genes = nlohmann::json::array();
  if (space_)
    for (const Gene& gene : space_->genes())
      genes.push_back({{"name", gene.name}, {"value", gene.value}, {"low", gene.low}, {"high", gene.high},
                       {"integer", gene.integer}, {"line", gene.line}});
  state["genes"] = genes;
  // A gallery of twelve of the same looks like a broken one: say why, and what would vary it.
  std::string warning;
  std::string heldNames;
  for (const std::string& name : held_) heldNames += (heldNames.empty() ? "" : ", ") + name;
  if (space_ && space_->genes().empty() && !held_.empty())
    warning = "no #define changes the picture between the ends of its range (" + heldNames +
              "): every variant is the same" +
              (def_.constants ? "" : " (vary its rules' numbers with --vary-constants)");
  else if (space_ && space_->genes().empty() && !probing_)
    warning = def_.constants ? "the program has no #define NAME NUMBER and no number in its rules to vary: every "
                               "variant is the same"
                             : "the program has no #define NAME NUMBER to vary: every variant is the same (vary its "
                               "rules' numbers with --vary-constants)";
  state["warning"] = warning;
  nlohmann::json variants = nlohmann::json::array();
  for (std::size_t i = 0; i < variants_.size(); ++i) {
    const GalleryVariant& variant = variants_[i];
    variants.push_back({{"index", i},
                        {"values", variant.genome.values},
                        {"parents", variant.parents},
                        {"grown", variant.grown},
                        {"picture", !variant.png.empty()},
                        {"error", variant.error}});
  }
  state["variants"] = variants;
  return state;
}

}  // namespace ontogen::studio
