#pragma once
// Live playback: a run's music set played on a live MIDI port as it is made. The set
// streams its score as the development makes it, and a performer thread plays it in time
// (interpreters/music/live_midi.h): in developmental time the first notes sound while the
// model is still growing, in sequential time each frame as soon as it is grown, while the
// next ones grow. A stop flag (set by a signal handler, say) stops every note and ends the
// run. Nothing here prints: the start and the end of the performance go to the caller.

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "interpreters/music/live_midi.h"
#include "interpreters/music/music_set.h"
#include "interpreters/run.h"

namespace ontogen {

/// Thrown out of a run when the stop flag stopped a performance (its notes already stopped).
struct PlaybackInterrupted : RunInterrupted {
  using RunInterrupted::RunInterrupted;
};

struct LivePlaybackDef {
  LiveMidiDef midi;                    ///< the port, and whether MIDI clock is sent
  std::atomic<bool>* stop = nullptr;   ///< true stops every note; required, outlives the playback
  /// Called on the run's thread as the performance starts, before its first note, with
  /// the port's name; empty: none.
  std::function<void(const std::string& portName)> started;
};

/// How a performance ended.
struct PlaybackOutcome {
  PerformanceReport report;  ///< report.stopped: the stop flag ended it
  std::string error;         ///< why sending failed; empty: it did not
};

class LivePlayback {
 public:
  /// Opens the port; throws LiveMidiError when no MIDI system runs or the port does not exist.
  explicit LivePlayback(LivePlaybackDef def);
  /// A run that failed: stops the music at once rather than play what was made.
  ~LivePlayback();
  LivePlayback(const LivePlayback&) = delete;
  LivePlayback& operator=(const LivePlayback&) = delete;

  /// Has `music` stream its score to `playback` for as long as the playback lives (the
  /// set holds it weakly: the run's owner decides when it ends).
  static void attach(const std::shared_ptr<LivePlayback>& playback, MusicSet& music);

  /// The music set's streamer: encodes what is final and hands it to the performer.
  /// Throws PlaybackInterrupted when stopped, OutputError when sending failed.
  void stream(const Score& score, double horizon, bool finished, const MidiFileDef& file);

  /// Whether a performance is under way: started (a score was streamed) and not yet
  /// waited for by finish().
  bool playing() const { return performer_.joinable(); }

  /// Lets the performance end (the development may have finished long before the
  /// music), waits for it and says how it went.
  PlaybackOutcome finish();

 private:
  void start();
  void join();
  std::string error();

  LivePlaybackDef def_;
  LiveMidiOutput output_;
  LiveMidiStream stream_;
  std::thread performer_;
  PerformanceReport report_;  // written by the performer, read after join
  std::mutex errorMutex_;
  std::string error_;
  // The piece being streamed: its encoder and the messages made so far.
  std::optional<MidiStreamEncoder> encoder_;
  MidiSequence sequence_;
  size_t forwarded_ = 0;
};

}  // namespace ontogen
