#include "apps/live_playback.h"

#include <atomic>
#include <csignal>
#include <iostream>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>

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
  ~LivePlayback() {
    // A run that failed: stop the music at once rather than play what was made.
    gStop.store(true);
    join();
  }
  LivePlayback(const LivePlayback&) = delete;
  LivePlayback& operator=(const LivePlayback&) = delete;

  /// The music set's streamer: encodes what is final and hands it to the performer.
  void stream(const Score& score, double horizon, bool finished, const MidiFileDef& file) {
    if (gStop.load()) {
      join();  // its notes are stopped before the run ends
      throw PlaybackInterrupted("interrupted: every note stopped");
    }
    if (std::string failed = error(); !failed.empty()) throw OutputError(failed);
    if (!performer_.joinable()) start();
    if (!encoder_) {
      encoder_.emplace(file.ppq, file.tempo);
      sequence_ = MidiSequence{};
      forwarded_ = 0;
      stream_.begin(file.ppq);
    }
    try {
      if (finished)
        encoder_->finish(score, sequence_);
      else
        encoder_->advance(score, horizon, sequence_);
    } catch (const std::invalid_argument& bad) {
      throw OutputError(std::string("live MIDI: ") + bad.what());
    }
    stream_.add(std::span(sequence_.messages).subspan(forwarded_), sequence_.tempos, encoder_->released(), finished);
    forwarded_ = sequence_.messages.size();
    if (finished) encoder_.reset();
  }

  /// Lets the performance end, then reports it.
  int finish() {
    if (performer_.joinable()) std::cerr << "grown; the music plays to its end (Ctrl-C stops it)\n";
    stream_.close();
    join();
    guard_.reset();
    if (stats_) {
      TimingSummary timing = summarizeTiming(report_.lateness);
      std::cerr << "live: " << report_.sent << " messages sent, lateness against the schedule: median "
                << timing.median * 1e3 << " ms, p99 " << timing.p99 * 1e3 << " ms, max " << timing.max * 1e3
                << " ms; " << report_.clocks << " clocks; " << report_.stalls << " stalls waiting "
                << report_.stalledSeconds << " s for the development\n";
    }
    if (std::string failed = error(); !failed.empty()) {
      std::cerr << "ontogen: error: " << failed << "\n";
      return kExitOutputError;
    }
    if (report_.stopped) {
      std::cerr << "\nontogen: interrupted: every note stopped\n";
      return kExitInterrupted;
    }
    return kExitOk;
  }

 private:
  void start() {
    guard_.emplace();
    std::cerr << "playing on '" << output_.portName() << "' as the model develops\n";
    performer_ = std::thread([this] {
      try {
        report_ = output_.perform(stream_, gStop);
      } catch (const LiveMidiError& failure) {
        std::lock_guard lock(errorMutex_);
        error_ = failure.what();
      }
    });
  }
  void join() {
    stream_.close();
    if (performer_.joinable()) performer_.join();
  }
  std::string error() {
    std::lock_guard lock(errorMutex_);
    return error_;
  }

  LiveMidiOutput output_;
  bool stats_;
  LiveMidiStream stream_;
  std::thread performer_;
  std::optional<InterruptGuard> guard_;
  PerformanceReport report_;  // written by the performer, read after join
  std::mutex errorMutex_;
  std::string error_;
  // The piece being streamed: its encoder and the messages made so far.
  std::optional<MidiStreamEncoder> encoder_;
  MidiSequence sequence_;
  size_t forwarded_ = 0;
};

int attachLivePlayback(const RunOptions& options, std::vector<std::unique_ptr<InterpretationSet>>& sets,
                       std::shared_ptr<LivePlayback>& playback) {
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
    playback = std::make_shared<LivePlayback>(def, options.stats);
  } catch (const LiveMidiError& error) {
    std::cerr << "ontogen: error: " << error.what() << "\n";
    return kExitMidiError;
  }
  // The set holds the playback weakly: the run's owner decides when it ends.
  std::weak_ptr<LivePlayback> weak = playback;
  music->setStreamer([weak](const Score& score, double horizon, bool finished, const MidiFileDef& file) {
    if (auto live = weak.lock()) live->stream(score, horizon, finished, file);
  });
  return kExitOk;
}

int finishLivePlayback(const std::shared_ptr<LivePlayback>& playback) { return playback ? playback->finish() : kExitOk; }

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
  if (options.midiPort.empty() && !options.virtualPort && !options.midiClock) return kExitOk;
  std::cerr << "ontogen: error: this ontogen was built without live MIDI (ONTOGEN_LIVE_MIDI=OFF)\n";
  return kExitMidiError;
}

int runMidiPorts() {
  std::cerr << "ontogen: error: this ontogen was built without live MIDI (ONTOGEN_LIVE_MIDI=OFF)\n";
  return kExitMidiError;
}

int finishLivePlayback(const std::shared_ptr<LivePlayback>&) { return kExitOk; }

#endif

}  // namespace ontogen::app
