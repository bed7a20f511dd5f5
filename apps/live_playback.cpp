#include "apps/live_playback.h"

#include <atomic>
#include <csignal>
#include <iostream>
#include <optional>
#include <string>

#include "apps/program_loader.h"
#include "interpreters/music/music_set.h"
#ifdef ONTOGEN_HAVE_LIVE_MIDI
#include "interpreters/music/live_playback.h"
#endif

namespace ontogen::app {

#ifdef ONTOGEN_HAVE_LIVE_MIDI

namespace {

// Set by the SIGINT handler; read by the performer between messages. A lock-free atomic
// is safe to store from a signal handler.
std::atomic<bool> gStop{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void onInterrupt(int) { gStop.store(true); }

/// SIGINT stops the performance instead of killing the process, while it lives.
class InterruptGuard {
 public:
  InterruptGuard() {
    gStop.store(false);
    previous_ = std::signal(SIGINT, onInterrupt);
  }
  ~InterruptGuard() { std::signal(SIGINT, previous_); }
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;

 private:
  void (*previous_)(int) = SIG_DFL;
};

}  // namespace

// The playback with Ctrl-C's handler while it plays, and whether to print its statistics.
class LiveSession {
 public:
  LiveSession(const LiveMidiDef& midi, bool stats) : stats_(stats) {
    LivePlaybackDef def;
    def.midi = midi;
    def.stop = &gStop;
    def.started = [this](const std::string& port) {
      guard_.emplace();
      std::cerr << "playing on '" << port << "' as the model develops\n";
    };
    playback_ = std::make_shared<LivePlayback>(std::move(def));
  }
  void attach(MusicSet& music) { LivePlayback::attach(playback_, music); }

  int finish() {
    if (playback_->playing()) std::cerr << "grown; the music plays to its end (Ctrl-C stops it)\n";
    const PlaybackOutcome outcome = playback_->finish();
    guard_.reset();
    if (stats_) {
      const PerformanceReport& report = outcome.report;
      TimingSummary timing = summarizeTiming(report.lateness);
      std::cerr << "live: " << report.sent << " messages sent, lateness against the schedule: median "
                << timing.median * 1e3 << " ms, p99 " << timing.p99 * 1e3 << " ms, max " << timing.max * 1e3
                << " ms; " << report.clocks << " clocks; " << report.stalls << " stalls waiting "
                << report.stalledSeconds << " s for the development\n";
    }
    if (!outcome.error.empty()) {
      std::cerr << "ontogen: error: " << outcome.error << "\n";
      return kExitOutputError;
    }
    if (outcome.report.stopped) {
      std::cerr << "\nontogen: interrupted: every note stopped\n";
      return kExitInterrupted;
    }
    return kExitOk;
  }

 private:
  bool stats_;
  std::optional<InterruptGuard> guard_;
  std::shared_ptr<LivePlayback> playback_;  // last: its notes stop before Ctrl-C is given back
};

int attachLivePlayback(const RunOptions& options, std::vector<std::unique_ptr<InterpretationSet>>& sets,
                       std::shared_ptr<LiveSession>& session) {
  if (options.midiPort.empty() && !options.virtualPort) {
    if (!options.midiClock) return kExitOk;
    std::cerr << "ontogen: error: --midi-clock is sent with live playback: add --midi-port or --virtual-port\n";
    return kExitUsage;
  }
  MusicSet* music = nullptr;
  for (auto& set : sets)
    if (auto* candidate = dynamic_cast<MusicSet*>(set.get())) music = candidate;
  if (!music) {
    std::cerr << "ontogen: error: --midi-port and --virtual-port play the music set: add --interpret music\n";
    return kExitUsage;
  }
  LiveMidiDef def;
  def.port = options.midiPort;
  def.virtualPort = options.virtualPort;
  def.clock = options.midiClock;
  try {
    session = std::make_shared<LiveSession>(def, options.stats);
  } catch (const LiveMidiError& error) {
    std::cerr << "ontogen: error: " << error.what() << "\n";
    return kExitMidiError;
  }
  session->attach(*music);
  return kExitOk;
}

int finishLivePlayback(const std::shared_ptr<LiveSession>& session) { return session ? session->finish() : kExitOk; }

int runMidiPorts() {
  try {
    auto ports = listMidiOutputPorts();
    if (ports.empty()) std::cerr << "no MIDI output ports\n";
    for (const MidiPortInfo& port : ports) std::cout << port.index << "  " << port.name << "  (" << port.api << ")\n";
  } catch (const LiveMidiError& error) {
    std::cerr << "ontogen: error: " << error.what() << "\n";
    return kExitMidiError;
  }
  return kExitOk;
}

#else

class LiveSession {};

int attachLivePlayback(const RunOptions& options, std::vector<std::unique_ptr<InterpretationSet>>&,
                       std::shared_ptr<LiveSession>&) {
  if (options.midiPort.empty() && !options.virtualPort && !options.midiClock) return kExitOk;
  std::cerr << "ontogen: error: this ontogen was built without live MIDI (ONTOGEN_LIVE_MIDI=OFF)\n";
  return kExitMidiError;
}

int runMidiPorts() {
  std::cerr << "ontogen: error: this ontogen was built without live MIDI (ONTOGEN_LIVE_MIDI=OFF)\n";
  return kExitMidiError;
}

int finishLivePlayback(const std::shared_ptr<LiveSession>&) { return kExitOk; }

#endif

}  // namespace ontogen::app
