// `ontogen studio FILE`: the live page (studio/). Serves 127.0.0.1 until Ctrl-C.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string_view>
#include <system_error>
#include <thread>

#include "apps/cli_values.h"
#include "apps/commands.h"
#include "apps/program_loader.h"
#include "interpreters/set_registry.h"
#include "studio/gallery.h"
#include "studio/http_server.h"
#include "studio/studio_assets.h"
#include "studio/studio_model.h"
#include "studio/studio_server.h"

namespace ontogen::app {

namespace {
volatile std::sig_atomic_t stopRequested = 0;

// The first Ctrl-C stops the studio once the requests at hand are answered and the growth
// at hand is cancelled (so no output is left half-written); a second one ends it at once.
extern "C" void requestStop(int) {
  if (stopRequested) ::_exit(kExitInterrupted);
  stopRequested = 1;
}

// A folder of the studio's own for the outputs it serves, removed when it stops.
std::filesystem::path makeWorkFolder() {
  std::error_code error;
  std::filesystem::path base = std::filesystem::temp_directory_path(error);
  if (error) base = ".";
  const std::filesystem::path folder = base / ("ontogen-studio-" + std::to_string(::getpid()));
  std::filesystem::create_directories(folder);
  return folder;
}
// The command line's settings as the studio grows with them; files of other tools are
// converted as `ontogen run` converts them. The defines were checked by loadProgram.
studio::StudioProgramOptions programOptionsOf(const CommonOptions& common) {
  studio::StudioProgramOptions program;
  program.file = common.file;
  program.system = common.system;
  for (const std::string& text : common.defines) {
    const std::size_t equals = text.find('=');
    if (equals == std::string::npos) continue;
    if (const std::optional<double> value = parseReal(std::string_view(text).substr(equals + 1)))
      program.defines[text.substr(0, equals)] = *value;
  }
  program.seed = common.seed;
  program.step = common.step;
  program.limits = common.limits;
  program.threads = common.threads;
  program.maxErrors = common.maxErrors;
  program.maxSourceBytes = common.maxSourceBytes;
  program.read = studioReader();
  return program;
}
}  // namespace

int runStudio(const StudioOptions& options) {
  // The program is loaded once before the page opens: a file that is no program, or a
  // --define it lacks, is a bad command line. A program with errors opens all the same,
  // with its errors in the page (and on the terminal), to be mended there.
  LoadedProgram loaded = loadProgram(options.common);
  if (!loaded.program && loaded.exitCode != kExitProgramError) return loaded.exitCode;

  const std::vector<std::string> known = interpretationSetNames();
  for (const std::string& name : options.sets)
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      std::string list;
      for (const std::string& set : known) list += (list.empty() ? "" : ", ") + set;
      std::cerr << "ontogen: error: --interpret: no set '" << name << "' (known: " << list << ")\n";
      return kExitUsage;
    }

  const std::filesystem::path work = makeWorkFolder();
  struct RemoveWork {
    std::filesystem::path folder;
    ~RemoveWork() {
      std::error_code ignored;
      std::filesystem::remove_all(folder, ignored);
    }
  } removeWork{work};

  studio::StudioModelDef modelDef;
  modelDef.program = programOptionsOf(options.common);
  modelDef.until = options.until;
  modelDef.frames = options.frames;
  modelDef.sets = options.sets;
  modelDef.work = work / "model";
  // The interactive limits start far below the command line's, unless its flags set them;
  // the command line's are the ceiling the page may raise them to.
  const WorldLimits defaults;
  if (options.common.limits.maxCells != defaults.maxCells) modelDef.maxCells = options.common.limits.maxCells;
  if (options.common.limits.maxMemoryBytes != defaults.maxMemoryBytes)
    modelDef.maxMemoryBytes = options.common.limits.maxMemoryBytes;
  studio::StudioModel model(modelDef);

  // The gallery grows within the page's limits as the model does (StudioServer gives them).
  studio::GalleryDef galleryDef;
  galleryDef.program = modelDef.program;
  galleryDef.until = options.until;
  galleryDef.seed = options.gallerySeed;
  galleryDef.constants = options.varyConstants;
  galleryDef.work = work / "gallery";
  galleryDef.saveTo = options.save.empty() ? std::filesystem::absolute(options.common.file).parent_path()
                                           : std::filesystem::path(options.save);
  studio::Gallery gallery(std::move(galleryDef));
  studio::StudioServer server(model, gallery);

  std::unique_ptr<studio::HttpServer> http;
  try {
    studio::HttpServerDef httpDef;
    httpDef.port = options.port;
    http = std::make_unique<studio::HttpServer>(
        httpDef, [&server](const studio::HttpRequest& request) { return server.handle(request); });
  } catch (const std::runtime_error& error) {
    std::cerr << "ontogen: error: " << error.what() << " (--port N picks another; 0 a free one)\n";
    return kExitUsage;
  }
  model.start();
  model.requestGrowth();
  if (studio::studioAssets().empty())
    std::cerr << "ontogen: warning: this build has no studio page (esbuild and three.js were missing at build "
                 "time; bash .ci/setup installs them); the page's routes answer all the same\n";
  std::cout << "ontogen studio: " << options.common.file << " at http://127.0.0.1:" << http->port()
            << "/ (Ctrl-C stops)" << std::endl;

  struct sigaction action {};
  action.sa_handler = requestStop;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
  http->start();
  // The file is looked at ten times a second; requests are answered on the server's threads.
  while (stopRequested == 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    server.idle();
  }
  http->stop();
  std::cerr << "ontogen studio: stopped\n";
  return kExitOk;
}

}  // namespace ontogen::app
