#pragma once
// A run as a library object: grows a program over frames spread evenly over [from, until],
// feeds the interpretation sets (one word a frame, or every step for the sets that follow
// the development), and returns a report of what happened: diagnostics (run-time errors
// and the sets' warnings, each with the cell, its source span and the time), the files
// written and the world's statistics. It never prints; `ontogen run`, a sweep or a viewer
// drive the same schedule through it.
//
//   RunDef def{.program = program, .stem = "piston", .frames = 26};
//   Run run(std::move(def));
//   RunReport report = run.execute();

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/world.h"
#include "interpreters/formats/scene_output.h"
#include "interpreters/interpretation_set.h"
#include "interpreters/scene.h"
#include "interpreters/set_registry.h"
#include "model/diagnostics.h"

namespace ontogen {

/// Seconds of movie a run writes when nothing says how many frames it has (no --frames,
/// speed or #fps): long enough to watch a model grow, short enough to loop and share;
/// 101 frames at 25 a second.
inline constexpr double kDefaultMovieSeconds = 4;

/// What to run; validated when the run starts.
struct RunDef {
  std::shared_ptr<const Program> program;
  std::string stem = "model";  ///< names the outputs: DIR/<stem>.glb, DIR/<stem>_0003.obj
  WorldDef world{};            ///< seed, limits, threads
  std::optional<double> until;  ///< seconds of developmental time; empty: the program's #until
  std::optional<double> step;   ///< seconds; empty: the program's #dt
  std::optional<double> from;   ///< time of the first frame, seconds; empty: the program's #from
  /// Spread evenly over [from, until]; one frame: the state at until. Empty: from the
  /// speed (below), else the program's #fps (round((until - from) * fps) + 1 frames), else
  /// a kDefaultMovieSeconds movie when the run writes one, else one frame.
  std::optional<int> frames;
  /// Seconds of developmental time a second of the movie shows: round((until - from) /
  /// speed * setOptions.framesPerSecond) + 1 frames. Empty: the program's #speed, if any.
  std::optional<double> speed;
  /// The look of pictures and movies by name (formats/look.h); empty: the program's
  /// #look, else setOptions.render.look as it is.
  std::optional<std::string> look;
  /// Interpretation sets by name. None: the run grows the world to `until` and writes
  /// nothing (not even the output directory); the report has its statistics.
  std::vector<std::string> sets{"geometry"};
  SetOptions setOptions{};                    ///< formats, picture size and view
  std::filesystem::path out = "out";          ///< the directory outputs go to (made if missing)
  /// Called after each frame with the frames done and the frames in all (a progress bar).
  std::function<void(int, int)> progress = {};
  /// Called after each frame that the sets drew into a scene, with that scene (valid
  /// during the call): what a sweep measures over the frames.
  std::function<void(const Scene&)> frameDrawn = {};
  /// Called after each frame with the world at the frame's time (valid during the call):
  /// what a viewer shows of a growth in progress.
  std::function<void(const World&)> frameGrown = {};
};

enum class RunStatus {
  Ok,
  BadDefinition,  ///< an unknown set, a bad format or size: nothing was grown
  ModelFailed,    ///< the model failed or passed a growth limit while it ran
  OutputFailed,   ///< an output could not be written
  Interrupted,    ///< stopped from outside: a set (live playback and Ctrl-C), or WorldLimits::cancel
};

/// A problem found while running: an error that ended the run, or a set's warning.
struct RunDiagnostic {
  Severity severity = Severity::Error;
  std::string message;
  SourceSpan span;   ///< the rule or instruction it comes from; invalid when none
  std::string cell;  ///< the cell's label, empty when none
  std::optional<double> time;  ///< seconds, when it happened at a time of the development
  uint64_t count = 1;          ///< how often (a warning counts each time it happened)
};

/// What a run did.
struct RunReport {
  RunStatus status = RunStatus::Ok;
  std::vector<RunDiagnostic> diagnostics;
  std::vector<std::filesystem::path> files;  ///< in the order written
  WorldStats stats{};
  double time = 0;     ///< the world's time at the end, seconds
  uint64_t cells = 0;  ///< cells in all pools at the end
  uint64_t held = 0;   ///< bytes the world's pools held at the end (WorldHeld::bytes)
  double wallSeconds = 0;

  bool ok() const { return status == RunStatus::Ok; }
};

/// Thrown by a set (or a wrapper around one, such as live playback) to stop a run from
/// outside; the run reports RunStatus::Interrupted with the message.
struct RunInterrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Renders a diagnostic the way the command line shows it: located ones like a compiler
/// (file:line:col, the line, a caret), the others as "ontogen: error: ...".
std::string formatRunDiagnostic(const RunDiagnostic& diagnostic);

class Run {
 public:
  /// Makes the sets; a definition that cannot run is reported by execute().
  explicit Run(RunDef def);
  ~Run();
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  /// The sets, made from the definition, before execute(): a caller may attach to them
  /// (live playback attaches to the music set).
  std::vector<std::unique_ptr<InterpretationSet>>& sets() { return sets_; }
  /// Grows the program and feeds the sets; returns the report. Call once.
  RunReport execute();
  /// The world, after execute() (null before, or when the definition was bad).
  const World* world() const { return world_.get(); }

 private:
  void collectWarnings(RunReport& report);
  void develop(RunReport& report);
  void writeScene(const FrameTarget& target, RunReport& report);

  RunDef def_;
  std::vector<std::unique_ptr<InterpretationSet>> sets_;
  Scene scene_;                         // the frame being drawn
  std::unique_ptr<SceneOutput> output_;  // writes the scenes (made at the first one)
  std::vector<RunDiagnostic> setupErrors_;
  std::unique_ptr<World> world_;
};

}  // namespace ontogen
