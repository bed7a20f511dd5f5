#pragma once
// Live MIDI output through RtMidi: listing output ports, opening one by name or index
// (or a virtual port others connect to), and performing a MidiSequence in real time.
//
// Timing: every message has an absolute deadline, start + secondsAt(tick), on the steady
// clock; the performer sleeps until shortly before it and spins the rest, so errors do
// not accumulate from message to message as they would with sleeps between messages.
// Every note-on sent is matched by a note-off when the piece ends or is stopped, and a
// stopped performance also sends all-notes-off (controller 123) and sustain off on every
// channel it used.
//
// RtMidi is tried with JACK first, then ALSA's sequencer: machines without a sound card
// have no ALSA sequencer, and a JACK server is how they get a MIDI graph.

#include <atomic>
#include <chrono>
#include <memory>
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
  /// Per scheduled message, seconds it was sent after its deadline (negative: early).
  std::vector<double> lateness;
};

struct LiveMidiDef {
  std::string port;            ///< a port name (exact, else a unique part of one) or index
  bool virtualPort = false;    ///< open a port named `virtualName` instead of connecting
  std::string virtualName = "ontogen";
  /// Seconds between opening the port and the first beat, so peers can connect and the
  /// first deadlines are not already late.
  double lead = 0.2;
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

  /// Plays the sequence against the steady clock, returning early (all notes stopped)
  /// when `stop` becomes true. Throws LiveMidiError when sending fails.
  PerformanceReport perform(const MidiSequence& sequence, const std::atomic<bool>& stop);

 private:
  void send(uint8_t status, uint8_t data1, uint8_t data2, int size);

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
