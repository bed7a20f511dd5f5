#include "interpreters/run.h"

#include <chrono>
#include <algorithm>
#include <cmath>
#include <new>
#include <stdexcept>
#include <system_error>

#include "interpreters/formats/look.h"
#include "interpreters/geometry/surface.h"
#include "interpreters/interpret.h"
#include "model/message_number.h"

namespace ontogen {

namespace {
// Frames a run may have: a million frames is eleven hours of film at 25 a second.
constexpr double kMaxFrames = 1e6;
}  // namespace

std::string formatRunDiagnostic(const RunDiagnostic& diagnostic) {
  if (diagnostic.span.valid()) return formatDiagnostic(Diagnostic{diagnostic.severity, diagnostic.span, diagnostic.message});
  return std::string("ontogen: ") + severityName(diagnostic.severity) + ": " + diagnostic.message + "\n";
}

namespace {
// A diagnostic that belongs to no source text or time.
RunDiagnostic unlocated(Severity severity, std::string message) {
  RunDiagnostic diagnostic;
  diagnostic.severity = severity;
  diagnostic.message = std::move(message);
  return diagnostic;
}
}  // namespace

Run::Run(RunDef def) : def_(std::move(def)) {
  if (!def_.program) {
    setupErrors_.push_back(unlocated(Severity::Error, "the run has no program"));
    return;
  }
  if (def_.frames && *def_.frames < 1) setupErrors_.push_back(unlocated(Severity::Error, "a run needs at least one frame"));
  if (!(def_.from.value_or(def_.program->from) <= def_.until.value_or(def_.program->until)))
    setupErrors_.push_back(
        unlocated(Severity::Error, "the first frame's time (#from, --from) is after the end of the run (#until, --until)"));
  if (!(def_.setOptions.framesPerSecond > 0 && std::isfinite(def_.setOptions.framesPerSecond)))
    setupErrors_.push_back(unlocated(Severity::Error, "the movie's frames per second (--fps) must be a number above 0"));
  if (def_.speed && !(*def_.speed > 0 && std::isfinite(*def_.speed)))
    setupErrors_.push_back(unlocated(Severity::Error, "the speed (--speed) must be a number of seconds above 0"));
  if (const double speed = def_.speed.value_or(def_.program->speed); speed > 0 && !def_.frames && setupErrors_.empty()) {
    const double span = def_.until.value_or(def_.program->until) - def_.from.value_or(def_.program->from);
    const double frames = std::round(span / speed * def_.setOptions.framesPerSecond) + 1;
    if (frames > kMaxFrames) {
      // Every number in at most 15 significant digits: a speed of 1e-300 makes a count of
      // frames 300 digits long, which %.0f would print in full.
      setupErrors_.push_back(unlocated(
          Severity::Error, "a speed of " + messageNumber(speed) + " s a second over " + messageNumber(span) + " s at " +
                               messageNumber(def_.setOptions.framesPerSecond) + " frames a second makes " +
                               messageNumber(frames, 15) + " frames, more than " + messageNumber(kMaxFrames, 15) +
                               ": a larger --speed or a lower --fps"));
    }
  }
  if (const std::string look = def_.look.value_or(def_.program->look); !look.empty()) {
    if (const std::optional<Look> found = findLook(look))
      def_.setOptions.render.look = *found;
    else
      setupErrors_.push_back(unlocated(Severity::Error, "unknown look '" + look + "' (known: " + lookList() + ")"));
  }
  def_.setOptions.maxMemoryBytes = def_.world.limits.maxMemoryBytes;
  for (const std::string& name : def_.sets) {
    std::unique_ptr<InterpretationSet> set;
    try {
      set = makeInterpretationSet(name, def_.program->rootSystem().settings, def_.setOptions);
    } catch (const std::invalid_argument& bad) {
      setupErrors_.push_back(unlocated(Severity::Error, bad.what()));
      continue;
    }
    if (!set) {
      std::string known;
      for (const auto& candidate : interpretationSetNames()) known += " " + candidate;
      setupErrors_.push_back(unlocated(Severity::Error, "unknown interpretation set '" + name + "' (known:" + known + ")"));
      continue;
    }
    sets_.push_back(std::move(set));
  }
}

Run::~Run() = default;

RunReport Run::execute() {
  RunReport report;
  if (!setupErrors_.empty()) {
    report.status = RunStatus::BadDefinition;
    report.diagnostics = setupErrors_;
    return report;
  }
  const auto started = std::chrono::steady_clock::now();
  std::error_code error;
  if (!sets_.empty()) std::filesystem::create_directories(def_.out, error);
  if (error) {
    report.status = RunStatus::OutputFailed;
    report.diagnostics.push_back(unlocated(
        Severity::Error, "cannot create the output directory '" + def_.out.string() + "': " + error.message()));
    return report;
  }
  try {
    develop(report);
  } catch (const LimitError& limit) {
    report.status = RunStatus::ModelFailed;
    report.diagnostics.push_back(unlocated(Severity::Error, limit.what()));
    if (world_) report.diagnostics.back().time = world_->time();
  } catch (const ModelError& model) {
    report.status = RunStatus::ModelFailed;
    report.diagnostics.push_back(
        {Severity::Error, model.diagnostic.message, model.diagnostic.span, model.cell, model.time, 1});
  } catch (const InstructionError& instruction) {
    report.status = RunStatus::ModelFailed;
    report.diagnostics.push_back({Severity::Error,
                                  std::string(instruction.what()) + " (in the interpretation of '" + instruction.cell +
                                      "' at t = " + messageNumber(instruction.time) + ")",
                                  instruction.span, instruction.cell, instruction.time, 1});
  } catch (const SurfaceError& surface) {
    report.status = RunStatus::ModelFailed;
    report.diagnostics.push_back(unlocated(Severity::Error, surface.what()));
  } catch (const OutputError& output) {
    report.status = RunStatus::OutputFailed;
    report.diagnostics.push_back(unlocated(Severity::Error, output.what()));
  } catch (const RunInterrupted& interrupted) {
    report.status = RunStatus::Interrupted;
    report.diagnostics.push_back(unlocated(Severity::Note, interrupted.what()));
  } catch (const GrowthCancelled& cancelled) {
    report.status = RunStatus::Interrupted;
    report.diagnostics.push_back(unlocated(Severity::Note, cancelled.what()));
    if (world_) report.diagnostics.back().time = world_->time();
  } catch (const std::bad_alloc&) {
    // The machine's memory is a limit too, one the limits did not foresee.
    report.status = RunStatus::ModelFailed;
    report.diagnostics.push_back(unlocated(
        Severity::Error, "the machine ran out of memory; lower the limits with --max-memory MIB or --max-cells N"));
    if (world_) report.diagnostics.back().time = world_->time();
  } catch (const std::length_error& length) {
    // A frame's geometry past what 32-bit indices reach.
    report.status = RunStatus::ModelFailed;
    report.diagnostics.push_back(unlocated(Severity::Error, length.what()));
    if (world_) report.diagnostics.back().time = world_->time();
  }
  collectWarnings(report);
  if (world_) {
    report.stats = world_->stats();
    report.time = world_->time();
    report.cells = world_->totalCells();
    report.held = world_->held().bytes;
  }
  report.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return report;
}

namespace {
// Frames over [from, until]: --frames; else at a speed, a whole number of the movie's
// frame intervals, so that a speed of 2 over 4 s at 25 frames a second gives 51 frames;
// else at #fps, so that `#fps 30` over 2 s gives 61 frames 1/30 s apart; else, when the
// run writes a movie of a model that has time to grow, kDefaultMovieSeconds of it; else
// one. At most kMaxFrames (a larger count from a speed is refused when the run is made).
int framesOf(const RunDef& def, const Program& program, double from, double until, bool writesMovie) {
  if (def.frames) return *def.frames;
  const double fps = def.setOptions.framesPerSecond;
  double intervals = 0;
  if (const double speed = def.speed.value_or(program.speed); speed > 0)
    intervals = std::round((until - from) / speed * fps);
  else if (program.framesPerSecond > 0)
    intervals = std::round((until - from) * program.framesPerSecond);
  else if (writesMovie && until > from)
    intervals = std::round(kDefaultMovieSeconds * fps);
  return static_cast<int>(std::clamp(intervals, 0.0, kMaxFrames - 1)) + 1;
}

// Whether the run makes a movie: mp4 is asked for and a set draws pictures of its frames.
bool writesMovie(const RunDef& def, const std::vector<std::unique_ptr<InterpretationSet>>& sets) {
  SceneOutputDef formats;
  if (!applyGeometryFormats(def.setOptions.formats, formats).empty() || !formats.writeMp4) return false;
  for (const auto& set : sets)
    if (set->drawsScene() || set->name() == "image") return true;
  return false;
}
}  // namespace

// Frames are spread over [from, until] (one frame: the state at `until`). Sets that follow
// the development (music in developmental time) see the word at the start and after
// every step, between frames too; the others see one word a frame.
void Run::develop(RunReport& report) {
  const Program& program = *def_.program;
  const double dt = def_.step.value_or(program.dt);
  const double until = def_.until.value_or(program.until);
  const double from = def_.from.value_or(program.from);
  const int frames = framesOf(def_, program, from, until, writesMovie(def_, sets_));
  world_ = std::make_unique<World>(def_.program, def_.world);
  World& world = *world_;
  if (sets_.empty()) {
    // Nothing sees the frames, and the development does not depend on them.
    world.advanceTo(until, dt);
    return;
  }
  std::vector<InterpretationSet*> following, simulating;
  for (auto& set : sets_)
    if (set->followsDevelopment()) {
      following.push_back(set.get());
      set->beginFrame(FrameTarget{def_.out, def_.stem, 0, 1, 0});
      interpretWord(world, *set);
    } else if (set->simulates()) {
      simulating.push_back(set.get());
      interpretWord(world, *set);
    }
  for (int frame = 0; frame < frames; ++frame) {
    const double t = frames == 1 ? until : from + (until - from) * frame / (frames - 1);
    if (!following.empty() || !simulating.empty()) {
      // The next instant of the step grid k * dt, where per-step rules fire.
      auto nextStep = [&] { return (std::floor(world.time() / dt + 1e-9) + 1) * dt; };
      for (double next = nextStep(); next < t - timeTolerance(t); next = nextStep()) {
        world.advanceTo(next, dt);
        for (InterpretationSet* set : following) interpretWord(world, *set);
        for (InterpretationSet* set : simulating) interpretWord(world, *set);
      }
    }
    // A simulation sees the grid only: a frame between its instants changes nothing, and
    // a frame on one is grown to the instant as the grid's k * dt, to the bit.
    const bool onGrid = std::abs(t - std::round(t / dt) * dt) <= timeTolerance(t);
    const double frameTime = !simulating.empty() && onGrid ? std::round(t / dt) * dt : t;
    const bool moved = frameTime > world.time();
    world.advanceTo(frameTime, dt);
    if (moved) {
      for (InterpretationSet* set : following) interpretWord(world, *set);
      if (onGrid)
        for (InterpretationSet* set : simulating) interpretWord(world, *set);
    }
    // Every set that draws adds to one scene, which the output stage writes; the other
    // sets write their own files.
    const FrameTarget target{def_.out, def_.stem, frame, frames, world.time()};
    scene_.clear();
    bool drawn = false;
    for (auto& set : sets_) {
      if (set->followsDevelopment()) continue;
      if (set->simulates()) {
        set->beginFrame(target);
        set->contribute(scene_);
        drawn = true;
        continue;
      }
      if (set->drawsScene()) {
        set->beginFrame(target);
        interpretWord(world, *set);
        set->contribute(scene_);
        drawn = true;
        continue;
      }
      for (auto& path : interpretFrame(world, *set, target)) report.files.push_back(std::move(path));
    }
    if (drawn) {
      if (!output_) output_ = std::make_unique<SceneOutput>(sceneOutputDefOf(def_.setOptions));
      writeScene(target, report);
      if (def_.frameDrawn) def_.frameDrawn(scene_);
    }
    if (def_.progress) def_.progress(frame + 1, frames);
    if (def_.frameGrown) def_.frameGrown(world);
  }
  for (InterpretationSet* set : following)
    for (auto& path : set->endFrame()) report.files.push_back(std::move(path));
  for (InterpretationSet* set : simulating)
    for (auto& path : set->endFrame()) report.files.push_back(std::move(path));
}

// What the output stage holds (every frame of a .glb until the end) and renders (a
// picture) counts against the memory limit with the pools.
void Run::writeScene(const FrameTarget& target, RunReport& report) {
  World& world = *world_;
  const WorldLimits& limits = def_.world.limits;
  const uint64_t pools = world.held().bytes;
  if (const uint64_t picture = output_->pictureBytes(target); picture > 0) {
    const RenderDef& render = output_->def().render;
    checkOutsideMemory("a " + std::to_string(render.width) + "x" + std::to_string(render.height) + " picture", picture,
                       pools + output_->heldBytes(), limits);
  }
  for (auto& path : output_->write(scene_, target)) report.files.push_back(std::move(path));
  checkOutsideMemory("the .glb's " + std::to_string(output_->glbFrames()) + " frames held until the last",
                     output_->heldBytes(), pools, limits);
  world.holdOutside(output_->heldBytes());
}

void Run::collectWarnings(RunReport& report) {
  auto add = [&](std::vector<SetWarning> warnings) {
    for (SetWarning& warning : warnings)
      report.diagnostics.push_back(
          {Severity::Warning, std::move(warning.message), warning.span, std::move(warning.cell), warning.time, warning.count});
  };
  for (auto& set : sets_) add(set->takeWarnings());
  if (output_) add(output_->takeWarnings());
}

}  // namespace ontogen
