#include <cstdio>
#include <iostream>

#include "apps/commands.h"
#include "apps/live_playback.h"
#include "apps/program_loader.h"
#include "apps/progress_bar.h"
#include "interpreters/run.h"

namespace ontogen::app {

namespace {
std::string formatMebibytes(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return text;
}

int exitCodeOf(RunStatus status) {
  switch (status) {
    case RunStatus::Ok: return kExitOk;
    case RunStatus::BadDefinition: return kExitUsage;
    case RunStatus::ModelFailed: return kExitModelError;
    case RunStatus::OutputFailed: return kExitOutputError;
    case RunStatus::Interrupted: return kExitInterrupted;
  }
  return kExitModelError;
}
}  // namespace

// Parses nothing and grows nothing itself: the run (interpreters/run.h) does the work and
// reports; this prints the report.
int runRun(const RunOptions& options) {
  LoadedProgram loaded = loadProgram(options.common);
  if (!loaded.program) return loaded.exitCode;

  // `--format none` grows the model and interprets and writes nothing, whatever the
  // program's #interpret says: a run for measuring and for scripts (with --stats).
  const bool growOnly = options.format == "none";
  if (growOnly && (!options.sets.empty() || !options.midiPort.empty() || options.virtualPort || options.midiClock)) {
    std::cerr << "ontogen: error: --format none grows without interpreting; it takes no --interpret, --midi-port, "
                 "--virtual-port or --midi-clock\n";
    return kExitUsage;
  }

  RunDef def;
  def.program = loaded.program;
  def.stem = loaded.stem;
  def.world = worldDefOf(options.common, *loaded.program);
  def.until = options.until;
  def.step = options.common.step;
  def.from = options.from;
  def.frames = options.frames;
  def.speed = options.speed;
  def.look = options.look;
  if (options.frames && options.speed) {
    std::cerr << "ontogen: error: --frames and --speed both say how many frames the run has; give one\n";
    return kExitUsage;
  }
  def.setOptions.framesPerSecond = options.fps.value_or(kDefaultMovieFps);
  def.sets = growOnly                                    ? std::vector<std::string>{}
             : !options.sets.empty()                     ? options.sets
             : !loaded.program->interpretSets.empty() ? loaded.program->interpretSets
                                                      : std::vector<std::string>{"geometry"};
  def.out = options.out;
  if (!growOnly) def.setOptions.formats = options.format;
  def.setOptions.up = options.up;
  if (options.view.size() == 2) {
    def.setOptions.render.azimuth = options.view[0];
    def.setOptions.render.elevation = options.view[1];
  }
  if (int width = 0, height = 0; std::sscanf(options.size.c_str(), "%dx%d", &width, &height) == 2) {
    def.setOptions.render.width = width;
    def.setOptions.render.height = height;
  } else {
    std::cerr << "ontogen: error: --size takes WIDTHxHEIGHT in pixels, as in 800x600, not '" << options.size << "'\n";
    return kExitUsage;
  }
  ProgressBar progress("growing " + loaded.stem);
  def.progress = [&progress](int done, int total) { progress.update(done, total); };

  Run run(std::move(def));
  std::shared_ptr<LiveSession> playback;
  if (int code = attachLivePlayback(options, run.sets(), playback); code != kExitOk) return code;
  const RunReport report = run.execute();
  if (report.ok()) progress.finish();
  bool first = true;
  for (const RunDiagnostic& diagnostic : report.diagnostics) {
    // A failure ends the progress bar's line first.
    if (first && diagnostic.severity == Severity::Error && report.status != RunStatus::BadDefinition) std::cerr << "\n";
    first = false;
    if (report.status == RunStatus::Interrupted && diagnostic.severity == Severity::Note)
      std::cerr << "\nontogen: " << diagnostic.message << "\n";
    else
      std::cerr << formatRunDiagnostic(diagnostic);
  }
  if (!report.ok()) return exitCodeOf(report.status);
  if (int code = finishLivePlayback(playback); code != kExitOk) return code;
  if (options.stats) {
    const WorldStats& stats = report.stats;
    std::cout << "time " << report.time << ", cells " << report.cells << ", steps " << stats.steps << ", events "
              << stats.events << ", cells born " << stats.cellsBorn << ", rule firings " << stats.ruleFirings
              << ", held " << formatMebibytes(report.held) << ", files " << report.files.size() << ", wall "
              << report.wallSeconds << " s";
    // Which ways the linear words were rewritten (core/rewrite_plan.h), when any was.
    if (const std::string rewrites = formatRewriteCounts(stats.rewrites); !rewrites.empty())
      std::cout << ", rewrites: " << rewrites;
    std::cout << "\n";
  }
  if (growOnly) return kExitOk;
  std::cerr << "wrote " << report.files.size() << " file" << (report.files.size() == 1 ? "" : "s") << " to "
            << options.out << "\n";
  return kExitOk;
}

}  // namespace ontogen::app
