#include "apps/sweep_terminal.h"

#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <stdexcept>

#include "apps/cli_values.h"
#include "apps/program_loader.h"

namespace ontogen::app {

namespace {

// Set by the SIGINT handler, read between rows; a lock-free atomic is safe to store from
// a handler.
std::atomic<bool> gInterrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free);
struct sigaction gPrevious {};

extern "C" void onBatchInterrupt(int) {
  gInterrupted.store(true);
  ::sigaction(SIGINT, &gPrevious, nullptr);
}

std::string formatSeconds(double seconds) {
  char text[32];
  if (seconds < 100)
    std::snprintf(text, sizeof text, "%.0f s", seconds);
  else if (seconds < 6000)
    std::snprintf(text, sizeof text, "%.0f min", seconds / 60);
  else
    std::snprintf(text, sizeof text, "%.1f h", seconds / 3600);
  return text;
}

}  // namespace

int readSweepSettings(const SweepCommonOptions& options, SweepSettings& settings) {
  const CommonOptions& common = options.common;
  LoadedProgram loaded = loadProgram(common);
  if (!loaded.program) return loaded.exitCode;
  ProgramText text = readProgramText(common.file, common.maxSourceBytes, common.limits);
  if (!text.text) return text.exitCode;
  const std::optional<std::pair<int, int>> size = parsePictureSize(options.size);
  if (!size) {
    std::cerr << "ontogen: error: --size takes WIDTHxHEIGHT in pixels, as in 128x128, not '" << options.size << "'\n";
    return kExitUsage;
  }
  settings.path = common.file;
  settings.stem = loaded.stem;
  settings.text = std::move(*text.text);
  settings.program = loaded.program;
  settings.measures = options.measures;
  settings.sets = options.sets;
  settings.system = common.system;
  settings.maxSourceBytes = common.maxSourceBytes;
  settings.limits = common.limits;
  settings.until = options.until;
  settings.step = common.step;
  settings.frames = options.frames;
  settings.width = size->first;
  settings.height = size->second;
  settings.view = options.view;
  settings.workers = options.workers;
  return kExitOk;
}

int prepareSweepReporting(const SweepSettings& settings, SweepSetup& setup) {
  if (std::string why = prepareSweep(settings, setup); !why.empty()) {
    std::cerr << "ontogen: error: " << why << "\n";
    return kExitUsage;
  }
  return kExitOk;
}

std::unique_ptr<Cluster> joinCluster() {
  try {
    return std::make_unique<Cluster>();
  } catch (const std::runtime_error& error) {
    std::cerr << "ontogen: error: " << error.what() << "\n";
    return nullptr;
  }
}

QuietFollowers::QuietFollowers(bool leader) {
  if (!leader) saved_ = std::cerr.rdbuf(nullptr);
}

QuietFollowers::~QuietFollowers() {
  if (!saved_) return;
  std::cerr.rdbuf(saved_);
  std::cerr.clear();
}

BatchInterrupt::BatchInterrupt() {
  gInterrupted.store(false);
  struct sigaction action {};
  action.sa_handler = onBatchInterrupt;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, &gPrevious);
}

BatchInterrupt::~BatchInterrupt() { ::sigaction(SIGINT, &gPrevious, nullptr); }

bool BatchInterrupt::requested() { return gInterrupted.load(); }

BatchProgressBar::BatchProgressBar(std::string label, std::optional<bool> show, bool leader)
    : bar_(std::move(label), show), leader_(leader) {
  if (!leader_) bar_.disable();
}

std::function<void(const BatchProgress&)> BatchProgressBar::callback() {
  return [this](const BatchProgress& progress) {
    bar_.update(static_cast<long>(progress.done), static_cast<long>(progress.total),
                std::to_string(progress.failed) + " failed, " + formatSeconds(progress.secondsLeft) + " left");
  };
}

int BatchProgressBar::finish(const BatchResult& result) {
  bar_.finish();
  switch (result.status) {
    case BatchStatus::Done: return kExitOk;
    case BatchStatus::Stopped: return kExitInterrupted;
    case BatchStatus::Refused:
      if (leader_) std::cerr << "ontogen: error: " << result.message << "\n";
      return kExitUsage;
    case BatchStatus::OutputError:
      if (leader_) std::cerr << "ontogen: error: " << result.message << "\n";
      return kExitOutputError;
  }
  return kExitInternalError;
}

}  // namespace ontogen::app
