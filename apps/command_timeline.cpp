#include <filesystem>
#include <iostream>

#include "apps/commands.h"
#include "apps/program_loader.h"
#include "interpreters/timeline/timeline_recorder.h"
#include "interpreters/timeline/timeline_png.h"
#include "interpreters/timeline/timeline_svg.h"

namespace ontogen::app {

int runTimeline(const TimelineOptions& options) {
  const std::filesystem::path out = options.out;
  if (out.extension() != ".svg" && out.extension() != ".png") {
    std::cerr << "ontogen: error: --out must name an .svg or .png file, not '" << options.out << "'\n";
    return kExitUsage;
  }
  LoadedProgram loaded = loadProgram(options.common);
  if (!loaded.program) return loaded.exitCode;
  const Program& program = *loaded.program;
  const WorldDef def = worldDefOf(options.common, program);
  const double dt = options.common.step.value_or(program.dt);
  const double until = options.until.value_or(program.until);
  Timeline timeline;
  if (int failed =
          developReporting([&] { timeline = recordTimeline(loaded.program, def, until, dt, options.maxRows); }))
    return failed;
  try {
    if (out.has_parent_path()) std::filesystem::create_directories(out.parent_path());
    if (out.extension() == ".png")
      writeTimelinePng(out, timeline);
    else
      writeTimelineSvg(out, timeline, loaded.stem);
  } catch (const std::exception& error) {
    std::cerr << "ontogen: error: " << error.what() << "\n";
    return kExitOutputError;
  }
  std::cout << "wrote " << out.string() << ": " << timeline.rows.size() << " cells over [" << timeline.start << ", "
            << timeline.end << "]";
  if (timeline.omitted) std::cout << " (" << timeline.omitted << " more past --max-rows)";
  std::cout << "\n";
  return kExitOk;
}

}  // namespace ontogen::app
