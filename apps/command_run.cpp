#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <system_error>

#include "apps/commands.h"
#include "apps/live_playback.h"
#include "apps/program_loader.h"
#include "apps/progress_bar.h"
#include "interpreters/geometry/surface.h"
#include "interpreters/interpret.h"
#include "interpreters/music/music_set.h"
#include "interpreters/set_registry.h"

namespace ontogen::app {

int runRun(const RunOptions& options) {
  LoadedProgram loaded = loadProgram(options.common);
  if (!loaded.program) return loaded.exitCode;
  const Program& program = *loaded.program;

  SetOptions setOptions;
  setOptions.formats = options.format;
  if (options.view.size() == 2) {
    setOptions.render.azimuth = options.view[0];
    setOptions.render.elevation = options.view[1];
  }
  if (int width = 0, height = 0; std::sscanf(options.size.c_str(), "%dx%d", &width, &height) == 2) {
    setOptions.render.width = width;
    setOptions.render.height = height;
  } else {
    std::cerr << "ontogen: error: --size takes WIDTHxHEIGHT in pixels, as in 800x600, not '" << options.size << "'\n";
    return kExitUsage;
  }
  std::vector<std::unique_ptr<InterpretationSet>> sets;
  for (const auto& name : options.sets) {
    std::unique_ptr<InterpretationSet> set;
    try {
      set = makeInterpretationSet(name, program.rootSystem().settings, setOptions);
    } catch (const std::invalid_argument& bad) {
      std::cerr << "ontogen: error: " << bad.what() << "\n";
      return kExitUsage;
    }
    if (!set) {
      std::cerr << "ontogen: error: unknown interpretation set '" << name << "' (known:";
      for (const auto& known : interpretationSetNames()) std::cerr << " " << known;
      std::cerr << ")\n";
      return kExitUsage;
    }
    sets.push_back(std::move(set));
  }
  std::shared_ptr<LivePlayback> playback;
  if (int code = attachLivePlayback(options, sets, playback); code != kExitOk) return code;
  std::error_code error;
  std::filesystem::create_directories(options.out, error);
  if (error) {
    std::cerr << "ontogen: error: cannot create the output directory '" << options.out << "': " << error.message()
              << "\n";
    return kExitOutputError;
  }

  WorldDef def;
  def.seed = options.common.seed.value_or(program.seed);
  def.limits = options.common.limits;
  def.threads = options.common.threads;
  double dt = options.common.step.value_or(program.dt);
  double until = options.until.value_or(program.until);
  int frames = options.frames;
  auto started = std::chrono::steady_clock::now();
  size_t written = 0;
  try {
    World world(loaded.program, def);
    ProgressBar progress("growing " + loaded.stem);
    // Sets that follow the development (music in developmental time) see the word at the
    // start and after every step, between frames too; the others see one word a frame.
    std::vector<InterpretationSet*> following;
    for (auto& set : sets)
      if (set->followsDevelopment()) {
        following.push_back(set.get());
        set->beginFrame(FrameTarget{options.out, loaded.stem, 0, 1, 0});
        interpretWord(world, *set);
      }
    for (int frame = 0; frame < frames; ++frame) {
      // Frames are spread over [0, until] (one frame: the state at `until`).
      double t = frames == 1 ? until : until * frame / (frames - 1);
      if (!following.empty()) {
        // The next instant of the step grid k * dt, where per-step rules fire.
        auto nextStep = [&] { return (std::floor(world.time() / dt + 1e-9) + 1) * dt; };
        for (double next = nextStep(); next < t - timeTolerance(t); next = nextStep()) {
          world.advanceTo(next, dt);
          for (InterpretationSet* set : following) interpretWord(world, *set);
        }
      }
      bool moved = t > world.time();
      world.advanceTo(t, dt);
      if (moved)
        for (InterpretationSet* set : following) interpretWord(world, *set);
      for (auto& set : sets) {
        if (set->followsDevelopment()) continue;
        FrameTarget target{options.out, loaded.stem, frame, frames, world.time()};
        written += interpretFrame(world, *set, target).size();
      }
      progress.update(frame + 1, frames);
    }
    for (InterpretationSet* set : following) written += set->endFrame().size();
    progress.finish();
    for (auto& set : sets)
      if (const auto* music = dynamic_cast<const MusicSet*>(set.get()); music && music->warnings().total() > 0) {
        const MusicWarnings& w = music->warnings();
        std::cerr << "ontogen: warning: the music player skipped " << w.droppedNotes
                  << " notes outside MIDI's 0..127, " << w.badArguments << " commands with bad arguments and "
                  << w.unmatchedPops << " unmatched ']' (docs/LANGUAGE.md, \"Music\")\n";
      }
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (options.stats) {
      const WorldStats& stats = world.stats();
      std::cout << "time " << world.time() << ", cells " << world.totalCells() << ", steps " << stats.steps
                << ", events " << stats.events << ", cells born " << stats.cellsBorn << ", rule firings "
                << stats.ruleFirings << ", files " << written << ", wall " << seconds << " s\n";
    }
  } catch (const LimitError& limit) {
    std::cerr << "\nontogen: error: " << limit.what() << "\n";
    return kExitModelError;
  } catch (const ModelError& model) {
    std::cerr << "\n" << model.what();
    return kExitModelError;
  } catch (const OutputError& output) {
    std::cerr << "\nontogen: error: " << output.what() << "\n";
    return kExitOutputError;
  } catch (const SurfaceError& surface) {
    std::cerr << "\nontogen: error: " << surface.what() << "\n";
    return kExitModelError;
  } catch (const PlaybackInterrupted& interrupted) {
    std::cerr << "\nontogen: " << interrupted.what() << "\n";
    return kExitInterrupted;
  }
  std::cerr << "wrote " << written << " file" << (written == 1 ? "" : "s") << " to " << options.out << "\n";
  return kExitOk;
}

}  // namespace ontogen::app
