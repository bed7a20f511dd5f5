#include "apps/live_playback.h"

#include <atomic>
#include <csignal>
#include <iostream>

#include "apps/program_loader.h"
#include "interpreters/music/music_set.h"
#ifdef ONTOGEN_HAVE_LIVE_MIDI
#include "interpreters/music/live_midi.h"
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

class LivePlayback {
 public:
  LivePlayback(const LiveMidiDef& def, bool stats) : output_(def), stats_(stats) {}

  void perform(const Score& score, const MidiFileDef& file) {
    MidiSequence sequence = makeMidiSequence(score, file.ppq, file.tempo);
    std::cerr << "playing " << sequence.messages.size() << " MIDI messages ("
              << sequence.secondsAt(sequence.endTick()) << " s) on '" << output_.portName() << "'\n";
    PerformanceReport report;
    {
      InterruptGuard guard;
      report = output_.perform(sequence, gStop);
    }
    if (stats_) {
      TimingSummary timing = summarizeTiming(report.lateness);
      std::cerr << "live: " << report.sent << " messages sent, lateness against the schedule: median "
                << timing.median * 1e3 << " ms, p99 " << timing.p99 * 1e3 << " ms, max " << timing.max * 1e3
                << " ms\n";
    }
    if (report.stopped) throw PlaybackInterrupted("interrupted: every note stopped");
  }

 private:
  LiveMidiOutput output_;
  bool stats_;
};

int attachLivePlayback(const RunOptions& options, std::vector<std::unique_ptr<InterpretationSet>>& sets,
                       std::shared_ptr<LivePlayback>& playback) {
  if (options.midiPort.empty() && !options.virtualPort) return kExitOk;
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
  try {
    playback = std::make_shared<LivePlayback>(def, options.stats);
  } catch (const LiveMidiError& error) {
    std::cerr << "ontogen: error: " << error.what() << "\n";
    return kExitMidiError;
  }
  music->setPerformer([playback](const Score& score, const MidiFileDef& file) {
    try {
      playback->perform(score, file);
    } catch (const LiveMidiError& error) {
      throw OutputError(error.what());
    }
  });
  return kExitOk;
}

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

class LivePlayback {};

int attachLivePlayback(const RunOptions& options, std::vector<std::unique_ptr<InterpretationSet>>&,
                       std::shared_ptr<LivePlayback>&) {
  if (options.midiPort.empty() && !options.virtualPort) return kExitOk;
  std::cerr << "ontogen: error: this ontogen was built without live MIDI (ONTOGEN_LIVE_MIDI=OFF)\n";
  return kExitMidiError;
}

int runMidiPorts() {
  std::cerr << "ontogen: error: this ontogen was built without live MIDI (ONTOGEN_LIVE_MIDI=OFF)\n";
  return kExitMidiError;
}

#endif

}  // namespace ontogen::app
