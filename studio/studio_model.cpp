#include "studio/studio_model.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "interpreters/music/music_set.h"
#include "interpreters/run.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"
#include "lang/convert/convert.h"
#include "lang/imports.h"
#include "model/message_number.h"
#include "lang/source_reader.h"
#include "lang/variation.h"
#include "studio/file_bytes.h"

namespace ontogen::studio {

struct StudioModel::Grown {
  std::optional<std::string> text;  // empty: the file could not be read (the last text stays)
  std::string stem;
  std::string sourceName;  // names the program's diagnostics the page marks at their lines
  std::string shown;       // the text the page shows: the file's own, converted or not
  bool converted = false;
  std::optional<std::vector<StudioDefine>> defines;  // empty: the sliders stay as they are
  std::vector<std::string> dropped;  // defines whose number the file changed: the page's value goes
  std::vector<std::string> watched;  // imports and surfaces read
  bool compiled = false;             // else the surfaces of the last growth stay watched
  std::vector<Diagnostic> diagnostics;
  bool grew = false;  // a model grew: what follows is its
  std::vector<StudioNote> notes;
  std::shared_ptr<const std::string> glb;
  double from = 0, until = 0;
  std::vector<double> frames;  // the developmental time of each frame, in order
  std::shared_ptr<const std::vector<std::string>> pictures;
  uint64_t cells = 0;
  bool stopped = false;
};

StudioModel::StudioModel(StudioModelDef def)
    : def_(std::move(def)),
      overrides_(def_.program.defines),  // --define values are where the sliders start
      maxCells_(std::min(def_.maxCells, def_.program.limits.maxCells)),
      maxMemoryBytes_(std::min(def_.maxMemoryBytes, def_.program.limits.maxMemoryBytes)) {}

StudioModel::~StudioModel() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
    pending_ = false;
    cancel_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

std::optional<StudioModel::FileStamp> StudioModel::stampOf(const std::string& path) {
  std::error_code error;
  const auto time = std::filesystem::last_write_time(path, error);
  if (error) return std::nullopt;
  const auto size = std::filesystem::file_size(path, error);
  if (error) return std::nullopt;
  return FileStamp{time, size};
}

void StudioModel::changed() {
  ++changes_;
  changedSignal_.notify_all();
}

void StudioModel::start() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (started_) return;
  started_ = true;
  thread_ = std::thread([this] { work(); });
}

void StudioModel::requestGrowth() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    pending_ = true;
    if (running_) cancel_ = true;  // a newer request makes the growth at hand stale
    changed();
  }
  wake_.notify_all();
}

bool StudioModel::refresh() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    // An editor that writes the file in pieces changes its stamp again: the next look
    // grows the whole text.
    if (pending_) return false;
    bool same = !stamps_.empty();  // before a growth, a file that exists is new
    for (const auto& [path, stamp] : stamps_) same = same && stampOf(path) == stamp;
    if (stamps_.empty() && !stampOf(def_.program.file)) same = true;
    if (same) return false;
  }
  requestGrowth();
  return true;
}

void StudioModel::stop() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    pending_ = false;
    if (running_) cancel_ = true;
    changed();
  }
  wake_.notify_all();
}

bool StudioModel::waitIdle(std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return changedSignal_.wait_for(lock, timeout, [this] { return !pending_ && !running_; });
}

uint64_t StudioModel::changes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return changes_;
}

uint64_t StudioModel::waitForChange(uint64_t seen, std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  changedSignal_.wait_for(lock, timeout, [&] { return changes_ != seen; });
  return changes_;
}

void StudioModel::work() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return pending_ || quit_; });
    if (quit_) return;
    lock.unlock();
    growOnce();
    lock.lock();
  }
}

void StudioModel::regrow() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    pending_ = true;
  }
  growOnce();
}

void StudioModel::growOnce() {
  const std::lock_guard<std::mutex> one(growing_);
  std::map<std::string, double> overrides;
  WorldLimits limits = def_.program.limits;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    // stop() since the growth was asked for takes it back.
    if (!pending_ || quit_) return;
    pending_ = false;
    running_ = true;
    cancel_ = false;
    // Stamped before they are read: a save while the growth reads is seen by the next look.
    stamps_.clear();
    stamps_[def_.program.file] = stampOf(def_.program.file);
    for (const std::string& path : watched_) stamps_[path] = stampOf(path);
    overrides = overrides_;
    limits.maxCells = maxCells_;
    limits.maxMemoryBytes = maxMemoryBytes_;
    began_ = std::chrono::steady_clock::now();
    growingCells_ = 0;
    growingTime_ = 0;
    changed();
  }
  limits.cancel = &cancel_;
  Grown grown;
  for (int attempt = 0;; ++attempt) {
    grown = Grown();
    try {
      grow(grown, overrides, limits);
    } catch (const std::exception& error) {
      grown.diagnostics.push_back(
          {"error", 0, 0, error.what(), std::string("ontogen: error: ") + error.what() + "\n", ""});
    }
    const InteractiveLimits wording{limits.maxCells, limits.maxMemoryBytes, def_.program.limits.maxCells,
                                    def_.program.limits.maxMemoryBytes};
    for (Diagnostic& diagnostic : grown.diagnostics) {
      diagnostic.message = wording.worded(diagnostic.message);
      diagnostic.formatted = wording.worded(diagnostic.formatted);
    }
    // A text with errors may be a save caught half-written: an editor truncates the file,
    // then writes it, or writes it in pieces. Its errors are shown only once the files
    // held still a moment after the read; a file that changed meanwhile is read again.
    if (grown.grew || grown.stopped || attempt >= kMaxRereads) break;
    const Settling settling = settle();
    if (settling == Settling::Changed) continue;
    if (settling == Settling::Superseded) {
      // A newer request grows the newer text: these errors may be of no text the user wrote.
      const std::lock_guard<std::mutex> lock(mutex_);
      running_ = false;
      changed();
      return;
    }
    break;
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  ++version_;
  wallSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - began_).count();
  diagnostics_ = std::move(grown.diagnostics);
  stopped_ = grown.stopped;
  if (grown.text) {
    text_ = std::move(*grown.text);
    sourceName_ = std::move(grown.sourceName);
    shown_ = std::move(grown.shown);
    converted_ = grown.converted;
    stem_ = std::move(grown.stem);
  }
  if (grown.defines) defines_ = std::move(*grown.defines);
  if (grown.text) {
    // A text that did not compile names no surfaces: those of the last growth stay watched.
    if (!grown.compiled)
      for (const std::string& path : watched_)
        if (std::find(grown.watched.begin(), grown.watched.end(), path) == grown.watched.end())
          grown.watched.push_back(path);
    std::map<std::string, std::optional<FileStamp>> stamps{{def_.program.file, stamps_[def_.program.file]}};
    for (const std::string& path : grown.watched) {
      const auto known = stamps_.find(path);
      stamps[path] = known != stamps_.end() ? known->second : stampOf(path);  // first read: stamped now
    }
    stamps_ = std::move(stamps);
    watched_ = std::move(grown.watched);
  }
  for (const std::string& name : grown.dropped) overrides_.erase(name);
  if (grown.grew) {
    notes_ = std::move(grown.notes);
    glb_ = std::move(grown.glb);
    from_ = grown.from;
    until_ = grown.until;
    cells_ = grown.cells;
    frames_ = std::move(grown.frames);
    pictures_ = std::move(grown.pictures);
    ++modelVersion_;
  }
  running_ = false;
  growingCells_ = 0;
  growingTime_ = 0;
  changed();
}

StudioModel::Settling StudioModel::settle() {
  std::unique_lock<std::mutex> lock(mutex_);
  // Cut short by a newer request, a stop or the end.
  wake_.wait_for(lock, kSettleTime, [this] { return pending_ || quit_ || cancel_.load(); });
  if (pending_ || quit_) return Settling::Superseded;
  if (cancel_.load()) return Settling::Settled;
  Settling settling = Settling::Settled;
  for (auto& [path, stamp] : stamps_) {
    const std::optional<FileStamp> now = stampOf(path);
    if (now == stamp) continue;
    settling = Settling::Changed;
    stamp = now;  // stamped before it is read again
  }
  return settling;
}

void StudioModel::setDefine(const std::string& name, double value) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const StudioDefine& define : defines_) {
    if (define.name != name) continue;
    // The slider's range is the define's #range (or the gallery's default): a value
    // past it is a request no page makes, and may grow a model past any use.
    if (!(value >= define.low && value <= define.high))
      throw std::invalid_argument(name + " = " + messageNumber(value) + " is outside its range [" +
                                  messageNumber(define.low) + ", " + messageNumber(define.high) + "]");
    overrides_[name] = value;
    changed();
    return;
  }
  throw std::invalid_argument("the program has no #define " + name);
}

std::string StudioModel::writeDefine(const std::string& name) {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto given = overrides_.find(name);
  if (given == overrides_.end()) throw std::invalid_argument("#define " + name + " has no value of the page's to write");
  if (converted_)
    throw std::invalid_argument("the program was converted from another tool's file; the studio writes only .cell files");
  // The text the page shows must be the file's: an edit the studio has not read yet would
  // be lost under the write.
  const SourceText now = readSourceFile(def_.program.file, def_.program.maxSourceBytes);
  if (!now.text || *now.text != text_)
    throw std::invalid_argument(def_.program.file + " changed since it was read; write again once it has grown");
  const VariationSpace space(text_);
  Genome genome = space.original();
  bool found = false;
  for (std::size_t i = 0; i < space.genes().size(); ++i) {
    if (space.genes()[i].kind != Gene::Kind::Define || space.genes()[i].name != name) continue;
    genome.values[i] = given->second;
    found = true;
  }
  if (!found) throw std::invalid_argument("the program writes no number for #define " + name);
  const std::string text = space.programText(genome);
  // Written beside the file and renamed over it, so no reader (the studio's own look at
  // the file included) ever sees it half-written; the file keeps its permissions.
  std::error_code error;
  std::filesystem::path target = std::filesystem::canonical(def_.program.file, error);
  if (error) target = def_.program.file;
  const std::filesystem::path temporary = target.string() + ".ontogen-studio-write";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) {
      std::filesystem::remove(temporary, error);
      throw std::invalid_argument("cannot write " + temporary.string());
    }
  }
  const auto permissions = std::filesystem::status(target, error).permissions();
  if (!error) std::filesystem::permissions(temporary, permissions, error);
  std::filesystem::rename(temporary, target, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw std::invalid_argument("cannot write " + target.string() + ": " + error.message());
  }
  overrides_.erase(given);
  changed();
  return def_.program.file;
}

void StudioModel::dropDefine(const std::string& name) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (overrides_.erase(name) == 0) throw std::invalid_argument("#define " + name + " has no value of the page's to drop");
  changed();
}

void StudioModel::setLimits(uint64_t maxCells, uint64_t maxMemoryBytes) {
  const WorldLimits& ceiling = def_.program.limits;
  if (maxCells == 0 || maxCells > ceiling.maxCells)
    throw std::invalid_argument("the cell limit is 1 to " + std::to_string(ceiling.maxCells) +
                                " (--max-cells raises the ceiling)");
  if (maxMemoryBytes < (uint64_t{1} << 20) || maxMemoryBytes > ceiling.maxMemoryBytes)
    throw std::invalid_argument("the memory limit is 1 MiB to " + std::to_string(ceiling.maxMemoryBytes >> 20) +
                                " MiB (--max-memory raises the ceiling)");
  const std::lock_guard<std::mutex> lock(mutex_);
  maxCells_ = maxCells;
  maxMemoryBytes_ = maxMemoryBytes;
  changed();
}

InteractiveLimits StudioModel::limits() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return {maxCells_, maxMemoryBytes_, def_.program.limits.maxCells, def_.program.limits.maxMemoryBytes};
}

uint64_t StudioModel::version() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return version_;
}
uint64_t StudioModel::modelVersion() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return modelVersion_;
}
std::string StudioModel::glb() const {
  std::shared_ptr<const std::string> glb;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    glb = glb_;
  }
  return glb ? *glb : std::string();
}
std::string StudioModel::text() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return text_;
}
std::string StudioModel::stem() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return stem_;
}
std::string StudioModel::picture(std::size_t frame) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return pictures_ && frame < pictures_->size() ? (*pictures_)[frame] : std::string();
}

std::vector<std::string> StudioModel::watchedFiles() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return watched_;
}

std::vector<StudioDefine> StudioModel::definesInEffect() const {
  std::vector<StudioDefine> defines = defines_;
  for (StudioDefine& define : defines) {
    const auto given = overrides_.find(define.name);
    define.value = given != overrides_.end() ? given->second : define.written;
    define.overridden = given != overrides_.end() && given->second != define.written;
  }
  return defines;
}

std::vector<StudioDefine> StudioModel::defines() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return definesInEffect();
}
std::vector<StudioNote> StudioModel::notes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return notes_;
}

std::map<std::string, double> StudioModel::defineValues() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::map<std::string, double> values;
  for (const StudioDefine& define : definesInEffect()) values[define.name] = define.value;
  return values;
}

void StudioModel::grow(Grown& grown, const std::map<std::string, double>& given, const WorldLimits& limits) {
  // Read within the interactive limits, as it grows: the page's limits hold every part.
  const StudioSource read = readStudioSource(def_.program, limits);
  if (!read.text) {
    const std::string why =
        "cannot read or convert " + def_.program.file + (read.error.empty() ? "" : ": " + read.error);
    grown.diagnostics.push_back({"error", 0, 0, why, "ontogen: error: " + why + "\n", ""});
    return;
  }
  grown.text = *read.text;
  // A file of another tool is shown as it is, its diagnostics at its own lines.
  grown.sourceName = read.original ? read.original->name() : read.name;
  grown.shown = read.original ? read.original->text() : *read.text;
  grown.converted = !read.name.empty() && read.name != def_.program.file;
  auto placed = [&read](const ontogen::Diagnostic& diagnostic) {
    const ontogen::Diagnostic at =
        read.original && diagnostic.span.valid() && diagnostic.span.file->name() == read.name
            ? convert::mapToOriginal(diagnostic, *read.original, read.lineOrigins)
            : diagnostic;
    return Diagnostic{severityName(at.severity), at.span.line(),        at.span.column(), at.message,
                      formatDiagnostic(at),       at.span.valid() ? at.span.file->name() : ""};
  };
  grown.stem = std::filesystem::path(def_.program.file).stem().string();
  const std::string& text = *grown.text;

  // The sliders: one per define name the text writes, ranged as a variant's would be.
  // A define whose number the file changed since the last growth takes the file's: an
  // edit of the file wins over a slider moved before it.
  const std::vector<StudioDefine> before = this->defines();
  std::map<std::string, double> overrides = given;
  std::vector<StudioDefine> defines;
  try {
    const VariationSpace space(text);
    for (const Gene& gene : space.genes()) {
      if (gene.kind != Gene::Kind::Define) continue;
      bool seen = false;
      for (const StudioDefine& define : defines) seen = seen || define.name == gene.name;
      if (seen) continue;
      for (const StudioDefine& old : before)
        if (old.name == gene.name && old.written != gene.value && overrides.erase(gene.name))
          grown.dropped.push_back(gene.name);
      defines.push_back({gene.name, gene.value, gene.value, gene.low, gene.high, gene.integer,
                         static_cast<int>(gene.line)});
    }
  } catch (const std::invalid_argument&) {
    // The text does not lex: the compiler below says where.
  }
  if (!defines.empty() || text.find("#define") == std::string::npos) grown.defines = std::move(defines);
  // The defines the compiler sees: this text's, or the last ones while it does not lex.
  const std::vector<StudioDefine> sliders = grown.defines ? *grown.defines : this->defines();

  CompileOptions options;
  options.commandSets = commandSets();
  options.rootSystem = def_.program.system;
  options.maxSourceBytes = def_.program.maxSourceBytes;
  for (const StudioDefine& define : sliders)
    if (overrides.count(define.name)) options.defines.push_back({define.name, overrides.at(define.name)});
  DiagnosticSink sink(def_.program.maxErrors);
  // Parsed and compiled as compileSource does, keeping the files it read: each is watched,
  // whether or not the program compiles.
  ParsedProgram parsed =
      parseWithImports(std::make_shared<const SourceFile>(read.name, text), sink, def_.program.maxSourceBytes);
  for (std::size_t i = 1; i < parsed.sources.size(); ++i) grown.watched.push_back(parsed.sources[i]->name());
  std::shared_ptr<const Program> program;
  if (!sink.hasErrors()) program = compile(parsed.tree, parsed.sources, sink, options);
  for (const ontogen::Diagnostic& diagnostic : sink.diagnostics()) grown.diagnostics.push_back(placed(diagnostic));
  if (!program) return;
  grown.compiled = true;
  for (const SystemDefinition& system : program->systems)
    for (const SurfaceFile& surface : system.settings.surfaces)
      if (std::find(grown.watched.begin(), grown.watched.end(), surface.path) == grown.watched.end())
        grown.watched.push_back(surface.path);

  RunDef run;
  run.program = program;
  run.stem = grown.stem;
  run.world = worldDefOf(def_.program, *program);
  run.world.limits = limits;
  run.frameGrown = [this, &grown](const World& world) {
    grown.frames.push_back(world.time());
    const std::lock_guard<std::mutex> lock(mutex_);
    growingCells_ = world.totalCells();
    growingTime_ = world.time();
    changed();
  };
  run.until = def_.until;
  run.step = def_.program.step;
  run.frames = def_.frames;
  if (!run.frames && program->framesPerSecond <= 0) run.frames = kDefaultStudioFrames;
  run.sets = !def_.sets.empty()                   ? def_.sets
             : !program->interpretSets.empty() ? program->interpretSets
                                               : std::vector<std::string>{"geometry"};
  run.setOptions.formats = "glb";
  run.out = def_.work / "model";
  std::filesystem::remove_all(run.out);
  Run running(std::move(run));
  const RunReport report = running.execute();
  grown.stopped = report.status == RunStatus::Interrupted;
  for (const RunDiagnostic& diagnostic : report.diagnostics)
    grown.diagnostics.push_back(diagnostic.span.valid()
                                    ? placed(ontogen::Diagnostic{diagnostic.severity, diagnostic.span, diagnostic.message})
                                    : Diagnostic{severityName(diagnostic.severity), 0, 0, diagnostic.message,
                                                 formatRunDiagnostic(diagnostic), ""});
  if (!report.ok()) return;

  std::vector<StudioNote> notes;
  for (const std::unique_ptr<InterpretationSet>& set : running.sets()) {
    const auto* music = dynamic_cast<const MusicSet*>(set.get());
    if (!music) continue;
    const Score& score = music->score();
    // Music that follows the development has a beat a second of developmental time;
    // a word read as a piece plays at its first tempo: a tempo() at its start, else #tempo.
    const bool developmental = music->def().time == MusicTime::Developmental;
    const double bpm = !score.tempos.empty() && score.tempos.front().time <= 0 ? score.tempos.front().bpm
                                                                               : music->def().file.tempo;
    const double secondsPerBeat = developmental ? 1.0 : 60.0 / bpm;
    for (const ScoreNote& note : score.notes) {
      // A held note whose cell was gone before it sounded stays in the score with no
      // length; the MIDI file leaves it out, and so does the page.
      if (!(note.duration > 0)) continue;
      notes.push_back({note.start * secondsPerBeat, note.duration * secondsPerBeat, note.channel, note.pitch,
                       note.velocity});
    }
  }
  grown.notes = std::move(notes);
  grown.glb = std::make_shared<const std::string>(readFileBytes(def_.work / "model" / (grown.stem + ".glb")));
  // The image set's pictures, a frame each in the order written (no other set writes
  // PNG here: the studio asks for glb alone).
  auto pictures = std::make_shared<std::vector<std::string>>();
  for (const std::filesystem::path& path : report.files)
    if (path.extension() == ".png") pictures->push_back(readFileBytes(path));
  grown.pictures = std::move(pictures);
  grown.from = program->from;
  grown.until = def_.until.value_or(program->until);
  grown.cells = report.cells;
  grown.grew = true;
}

nlohmann::json StudioModel::state() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  nlohmann::json state = {{"version", version_},
                          {"modelVersion", modelVersion_},
                          {"file", def_.program.file},
                          {"stem", stem_},
                          {"hasModel", glb_ && !glb_->empty()},
                          {"from", from_},
                          {"until", until_},
                          {"cells", cells_},
                          {"frames", frames_},
                          {"pictures", pictures_ ? pictures_->size() : 0},
                          {"notes", notes_.size()},
                          {"seconds", wallSeconds_},
                          {"source", shown_},
                          {"sourceName", sourceName_},
                          {"converted", converted_}};
  nlohmann::json diagnostics = nlohmann::json::array();
  bool failed = false;
  for (const Diagnostic& d : diagnostics_) {
    failed = failed || d.severity == "error";
    diagnostics.push_back(
        {{"severity", d.severity}, {"line", d.line}, {"column", d.column}, {"message", d.message}, {"text", d.formatted},
         {"file", d.file}});
  }
  state["ok"] = !failed;
  state["diagnostics"] = diagnostics;
  nlohmann::json defines = nlohmann::json::array();
  for (const StudioDefine& d : definesInEffect())
    defines.push_back({{"name", d.name},
                       {"value", d.value},
                       {"written", d.written},
                       {"low", d.low},
                       {"high", d.high},
                       {"integer", d.integer},
                       {"line", d.line},
                       {"overridden", d.overridden}});
  state["defines"] = defines;
  state["stopped"] = stopped_;
  state["growth"] = {
      {"running", running_ || pending_},
      {"cells", growingCells_},
      {"time", growingTime_},
      {"seconds", running_ ? std::chrono::duration<double>(std::chrono::steady_clock::now() - began_).count() : 0.0}};
  state["limits"] = {{"maxCells", maxCells_},
                     {"maxMemoryBytes", maxMemoryBytes_},
                     {"ceilingCells", def_.program.limits.maxCells},
                     {"ceilingMemoryBytes", def_.program.limits.maxMemoryBytes}};
  return state;
}

}  // namespace ontogen::studio
