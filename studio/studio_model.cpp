#include "studio/studio_model.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "interpreters/music/music_set.h"
#include "interpreters/run.h"
#include "interpreters/set_registry.h"
#include "lang/compiler.h"
#include "lang/variation.h"
#include "studio/file_bytes.h"

namespace ontogen::studio {

StudioModel::StudioModel(StudioModelDef def) : def_(std::move(def)) {
  // --define values given when the studio starts are where the sliders start.
  overrides_ = def_.program.defines;
}

std::optional<StudioModel::FileStamp> StudioModel::stampOf() const {
  std::error_code error;
  const auto time = std::filesystem::last_write_time(def_.program.file, error);
  if (error) return std::nullopt;
  const auto size = std::filesystem::file_size(def_.program.file, error);
  if (error) return std::nullopt;
  return FileStamp{time, size};
}

bool StudioModel::refresh() {
  const std::optional<FileStamp> stamp = stampOf();
  if (stamp == stamp_) return false;
  // An editor that writes the file in pieces changes its stamp again: the next look
  // grows the whole text.
  regrow();
  return true;
}

bool StudioModel::setDefine(const std::string& name, double value) {
  if (!std::isfinite(value)) return false;
  bool known = false;
  for (const StudioDefine& define : defines_) known = known || define.name == name;
  if (!known) return false;
  overrides_[name] = value;
  regrow();
  return true;
}

std::map<std::string, double> StudioModel::defineValues() const {
  std::map<std::string, double> values;
  for (const StudioDefine& define : defines_) values[define.name] = define.value;
  return values;
}

void StudioModel::regrow() {
  const auto started = std::chrono::steady_clock::now();
  ++version_;
  diagnostics_.clear();
  try {
    grow();
  } catch (const std::exception& error) {
    diagnostics_.push_back({"error", 0, 0, error.what(), std::string("ontogen: error: ") + error.what() + "\n"});
  }
  wallSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

void StudioModel::grow() {
  stamp_ = stampOf();
  const StudioSource read = readStudioSource(def_.program);
  if (!read.text) {
    const std::string why = "cannot read or convert " + def_.program.file + (read.error.empty() ? "" : ": " + read.error);
    diagnostics_.push_back({"error", 0, 0, why, "ontogen: error: " + why + "\n"});
    return;
  }
  text_ = *read.text;
  stem_ = std::filesystem::path(def_.program.file).stem().string();

  // The sliders: one per define name the text writes, ranged as a variant's would be.
  std::vector<StudioDefine> defines;
  try {
    const VariationSpace space(text_);
    for (const Gene& gene : space.genes()) {
      if (gene.kind != Gene::Kind::Define) continue;
      bool seen = false;
      for (const StudioDefine& define : defines) seen = seen || define.name == gene.name;
      if (seen) continue;
      const auto given = overrides_.find(gene.name);
      defines.push_back({gene.name, given != overrides_.end() ? given->second : gene.value, gene.value, gene.low,
                         gene.high, gene.integer, static_cast<int>(gene.line)});
    }
  } catch (const std::invalid_argument&) {
    // The text does not lex: the compiler below says where.
  }
  if (!defines.empty() || text_.find("#define") == std::string::npos) defines_ = std::move(defines);

  CompileOptions options;
  options.commandSets = commandSets();
  options.rootSystem = def_.program.system;
  options.maxSourceBytes = def_.program.maxSourceBytes;
  for (const StudioDefine& define : defines_)
    if (overrides_.count(define.name)) options.defines.push_back({define.name, overrides_.at(define.name)});
  DiagnosticSink sink(def_.program.maxErrors);
  std::shared_ptr<const Program> program = compileSource(read.name, text_, sink, options);
  for (const ontogen::Diagnostic& diagnostic : sink.diagnostics())
    diagnostics_.push_back({severityName(diagnostic.severity), diagnostic.span.line(), diagnostic.span.column(),
                            diagnostic.message, formatDiagnostic(diagnostic)});
  if (!program) return;

  RunDef run;
  run.program = program;
  run.stem = stem_;
  run.world = worldDefOf(def_.program, *program);
  run.until = def_.until;
  run.step = def_.program.step;
  run.frames = def_.frames;
  if (!run.frames && program->framesPerSecond <= 0) run.frames = kDefaultStudioFrames;
  run.sets = program->interpretSets.empty() ? std::vector<std::string>{"geometry"} : program->interpretSets;
  run.setOptions.formats = "glb";
  run.out = def_.work / "model";
  std::filesystem::remove_all(run.out);
  Run grown(std::move(run));
  const RunReport report = grown.execute();
  for (const RunDiagnostic& diagnostic : report.diagnostics)
    diagnostics_.push_back({severityName(diagnostic.severity), diagnostic.span.line(), diagnostic.span.column(),
                            diagnostic.message, formatRunDiagnostic(diagnostic)});
  if (!report.ok()) return;

  std::vector<StudioNote> notes;
  for (const std::unique_ptr<InterpretationSet>& set : grown.sets()) {
    const auto* music = dynamic_cast<const MusicSet*>(set.get());
    if (!music) continue;
    const Score& score = music->score();
    // Music that follows the development has a beat a second of developmental time;
    // a word read as a piece plays at its first tempo.
    const bool developmental = music->def().time == MusicTime::Developmental;
    const double secondsPerBeat = developmental || score.tempos.empty() ? (developmental ? 1.0 : 0.5)
                                                                         : 60.0 / score.tempos.front().bpm;
    for (const ScoreNote& note : score.notes) {
      // A held note whose cell was gone before it sounded stays in the score with no
      // length; the MIDI file leaves it out, and so does the page.
      if (!(note.duration > 0)) continue;
      notes.push_back({note.start * secondsPerBeat, note.duration * secondsPerBeat, note.channel, note.pitch,
                       note.velocity});
    }
  }
  notes_ = std::move(notes);
  glb_ = readFileBytes(def_.work / "model" / (stem_ + ".glb"));
  from_ = program->from;
  until_ = def_.until.value_or(program->until);
  cells_ = report.cells;
  ++modelVersion_;
}

nlohmann::json StudioModel::state() const {
  nlohmann::json state = {{"version", version_},
                          {"modelVersion", modelVersion_},
                          {"file", def_.program.file},
                          {"stem", stem_},
                          {"hasModel", !glb_.empty()},
                          {"from", from_},
                          {"until", until_},
                          {"cells", cells_},
                          {"notes", notes_.size()},
                          {"seconds", wallSeconds_},
                          {"source", text_}};
  nlohmann::json diagnostics = nlohmann::json::array();
  bool failed = false;
  for (const Diagnostic& d : diagnostics_) {
    failed = failed || d.severity == "error";
    diagnostics.push_back(
        {{"severity", d.severity}, {"line", d.line}, {"column", d.column}, {"message", d.message}, {"text", d.formatted}});
  }
  state["ok"] = !failed;
  state["diagnostics"] = diagnostics;
  nlohmann::json defines = nlohmann::json::array();
  for (const StudioDefine& d : defines_)
    defines.push_back({{"name", d.name},
                       {"value", d.value},
                       {"written", d.written},
                       {"low", d.low},
                       {"high", d.high},
                       {"integer", d.integer},
                       {"line", d.line}});
  state["defines"] = defines;
  return state;
}

}  // namespace ontogen::studio
