#pragma once
// Live MIDI output through RtMidi: listing output ports, opening one by name or index
// (or a virtual port others connect to), and performing MIDI in real time while the
// model that makes it still develops.
//
// Streaming: a LiveMidiStream is filled by the run (one thread) and played by
// LiveMidiOutput::perform (another). It holds pieces played one after another (a frame's
// score each in sequential time, the whole run in developmental time); the run adds a
// piece's messages as the development reaches them and says up to which tick nothing more
// will come (the released tick). The performer never sends past it: when the development
// is slower than the music, the piece waits for it (a stall), and the deadlines after the
// stall move on by its length, so the rhythm stays whole.
//
// Timing: every message has an absolute deadline, start + stalls + secondsAt(tick), on
// the steady clock; the performer sleeps until shortly before it and spins the rest, so
// errors do not accumulate from message to message as they would with sleeps between
// messages. Every note-on sent is matched by a note-off when the piece ends or is
// stopped, and a stopped performance also sends all-notes-off (controller 123) and
// sustain off on every channel it used.
//
// MIDI clock (LiveMidiDef::clock): start (0xFA) at each piece's beat 0, timing clock
// (0xF8) 24 times a quarter note through the tempo map up to the piece's last message,
// stop (0xFC) at its end, so a DAW or drum machine follows the tempo and the stalls.
//
// RtMidi is tried with JACK first, then ALSA's sequencer: machines without a sound card
// have no ALSA sequencer, and a JACK server is how they get a MIDI graph.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "interpreters/music/midi_sequence.h"

class RtMidiOut;

namespace ontogen {

/// Live MIDI cannot start: no MIDI system runs, or the port asked for does not exist.
struct LiveMidiError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct MidiPortInfo {
  unsigned index = 0;  ///< what --midi-port INDEX means
  std::string name;    ///< e.g. "midi-monitor:input" (JACK) or "FLUID Synth:0" (ALSA)
  std::string api;     ///< "jack" or "alsa"
};

/// The output ports of every MIDI system that runs. Throws LiveMidiError when none does
/// (no JACK server and no ALSA sequencer).
std::vector<MidiPortInfo> listMidiOutputPorts();

/// What a performance did, for the caller's report and the timing measurements.
struct PerformanceReport {
  size_t sent = 0;              ///< channel messages sent, note-offs at the end included
  bool stopped = false;         ///< the stop flag ended it early
  /// Per scheduled channel message, seconds it was sent after its deadline (negative: early).
  std::vector<double> lateness;
  size_t clocks = 0;            ///< timing clocks (0xF8) sent
  size_t stalls = 0;            ///< times the performance waited for the development
  double stalledSeconds = 0;    ///< how long it waited in all
};

/// What the development has made of the music so far: pieces, each a sequence that grows.
/// Thread-safe: one thread adds, LiveMidiOutput::perform plays.
class LiveMidiStream {
 public:
  /// Starts a new piece at `ppq` ticks per quarter note; it plays when the one before it
  /// has ended.
  void begin(int ppq);
  /// Adds `messages` to the current piece (ticks ascending, none before the last added),
  /// replaces its tempo map by `tempos` (changes only at or after the released tick), and
  /// releases it up to `released` ticks: nothing more will come before. `complete`: the
  /// piece is whole.
  void add(std::span<const MidiMessage> messages, std::span<const MidiTempo> tempos, uint64_t released,
           bool complete);
  /// No more pieces: the performance ends after the last.
  void close();

 private:
  friend class LiveMidiOutput;
  struct Piece {
    MidiSequence sequence;
    uint64_t released = 0;
    bool complete = false;
  };
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Piece> pieces_;  // played ones stay, so indices hold
  bool closed_ = false;
};

struct LiveMidiDef {
  std::string port;            ///< a port name (exact, else a unique part of one) or index
  bool virtualPort = false;    ///< open a port named `virtualName` instead of connecting
  std::string virtualName = "ontogen";
  /// Seconds between the first piece's arrival and its first beat, so peers can connect
  /// and the first deadlines are not already late.
  double lead = 0.2;
  bool clock = false;  ///< send MIDI clock: start, 24 timing clocks a quarter note, stop
};

class LiveMidiOutput {
 public:
  /// Opens the port. Throws LiveMidiError naming the ports that exist when there is no
  /// such port, or when no MIDI system runs.
  explicit LiveMidiOutput(const LiveMidiDef& def);
  ~LiveMidiOutput();
  LiveMidiOutput(const LiveMidiOutput&) = delete;
  LiveMidiOutput& operator=(const LiveMidiOutput&) = delete;

  /// The name of the port ontogen sends to (or its own virtual port).
  const std::string& portName() const { return portName_; }

  /// Plays the stream's pieces against the steady clock as they are added, until the
  /// stream is closed and its last piece played, or (all notes stopped) when `stop`
  /// becomes true. Throws LiveMidiError when sending fails.
  PerformanceReport perform(LiveMidiStream& stream, const std::atomic<bool>& stop);
  /// Plays a finished sequence: a stream of one whole piece.
  PerformanceReport perform(const MidiSequence& sequence, const std::atomic<bool>& stop);

 private:
  void send(uint8_t status, uint8_t data1, uint8_t data2, int size);
  /// Sleeps towards `deadline`, waking to notice `stop`, then spins; false when stopped.
  static bool waitUntil(std::chrono::steady_clock::time_point deadline, const std::atomic<bool>& stop);

  LiveMidiDef def_;
  std::unique_ptr<RtMidiOut> out_;
  std::string portName_;
};

/// Median and 99th percentile (nearest rank) of values, in their unit; 0 when empty.
struct TimingSummary {
  double median = 0;
  double p99 = 0;
  double max = 0;
  size_t count = 0;
};
TimingSummary summarizeTiming(std::vector<double> values);

}  // namespace ontogen
