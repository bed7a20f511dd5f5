#include "interpreters/music/live_midi.h"

#include <RtMidi.h>
#include <jack/jack.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <limits>
#include <optional>
#include <cmath>
#include <filesystem>
#include <thread>

namespace ontogen {

namespace {

using Clock = std::chrono::steady_clock;

// The performer wakes this long before a deadline and spins the rest: the kernel's
// timer slack and a loaded machine's scheduling delay are of this order.
constexpr auto kSpin = std::chrono::microseconds(500);
// While waiting for a far deadline it wakes at least this often to notice a stop.
constexpr auto kStopPoll = std::chrono::milliseconds(20);

void silent(const char*) {}

/// A JACK server runs (RtMidi's JACK backend cannot tell "no server" from "no ports").
bool jackServerRuns() {
  // The JACK library prints its failures itself; the caller reports them instead.
  jack_set_error_function(silent);
  jack_set_info_function(silent);
  jack_status_t status;
  jack_client_t* client = jack_client_open("ontogen-probe", JackNoStartServer, &status);
  if (!client) return false;
  jack_client_close(client);
  return true;
}

/// The APIs to try, in order, with the RtMidi output of each that runs.
std::vector<std::pair<RtMidi::Api, std::unique_ptr<RtMidiOut>>> openSystems() {
  std::vector<RtMidi::Api> compiled;
  RtMidi::getCompiledApi(compiled);
  std::vector<std::pair<RtMidi::Api, std::unique_ptr<RtMidiOut>>> systems;
  for (RtMidi::Api api : {RtMidi::UNIX_JACK, RtMidi::LINUX_ALSA}) {
    if (std::find(compiled.begin(), compiled.end(), api) == compiled.end()) continue;
    if (api == RtMidi::UNIX_JACK && !jackServerRuns()) continue;
    // Without the sequencer device ALSA cannot run (and its library would print so).
    if (api == RtMidi::LINUX_ALSA && !std::filesystem::exists("/dev/snd/seq")) continue;
    try {
      auto out = std::make_unique<RtMidiOut>(api, "ontogen");
      out->setErrorCallback([](RtMidiError::Type, const std::string&, void*) {}, nullptr);
      systems.emplace_back(api, std::move(out));
    } catch (const RtMidiError&) {
      // This system does not run here (e.g. no /dev/snd/seq); try the next.
    }
  }
  return systems;
}

const char* apiName(RtMidi::Api api) { return api == RtMidi::UNIX_JACK ? "jack" : "alsa"; }

std::string portList(const std::vector<MidiPortInfo>& ports) {
  if (ports.empty()) return "there are no output ports";
  std::string list = "the output ports are:";
  for (const MidiPortInfo& port : ports) list += " " + std::to_string(port.index) + " '" + port.name + "'";
  return list;
}

}  // namespace

std::vector<MidiPortInfo> listMidiOutputPorts() {
  auto systems = openSystems();
  if (systems.empty())
    throw LiveMidiError("no MIDI system is running (no JACK server and no ALSA sequencer); start one, e.g. "
                        "'jackd -d dummy &' on a machine without a sound card");
  std::vector<MidiPortInfo> ports;
  for (auto& [api, out] : systems) {
    unsigned count = out->getPortCount();
    for (unsigned i = 0; i < count; ++i)
      ports.push_back({static_cast<unsigned>(ports.size()), out->getPortName(i), apiName(api)});
  }
  return ports;
}

LiveMidiOutput::LiveMidiOutput(const LiveMidiDef& def) : def_(def) {
  auto systems = openSystems();
  if (systems.empty())
    throw LiveMidiError("no MIDI system is running (no JACK server and no ALSA sequencer); start one, e.g. "
                        "'jackd -d dummy &' on a machine without a sound card");
  if (def.virtualPort) {
    for (auto& [api, out] : systems) {
      try {
        out->openVirtualPort(def.virtualName);
        out_ = std::move(out);
        portName_ = def.virtualName;
        return;
      } catch (const RtMidiError&) {
      }
    }
    throw LiveMidiError("cannot open a virtual MIDI port '" + def.virtualName + "'");
  }
  // Index across all systems, as listMidiOutputPorts numbers them; else a name.
  std::vector<MidiPortInfo> ports;
  std::vector<std::pair<size_t, unsigned>> where;  // system, port within it
  for (size_t s = 0; s < systems.size(); ++s) {
    unsigned count = systems[s].second->getPortCount();
    for (unsigned i = 0; i < count; ++i) {
      ports.push_back({static_cast<unsigned>(ports.size()), systems[s].second->getPortName(i), apiName(systems[s].first)});
      where.emplace_back(s, i);
    }
  }
  int chosen = -1;
  bool isIndex = !def.port.empty() && std::all_of(def.port.begin(), def.port.end(), ::isdigit);
  if (isIndex) {
    // from_chars, not stoul: an index of 30 digits is no port, not an exception.
    unsigned long index = 0;
    const auto [end, error] = std::from_chars(def.port.data(), def.port.data() + def.port.size(), index);
    if (error == std::errc() && end == def.port.data() + def.port.size() && index < ports.size())
      chosen = static_cast<int>(index);
  } else {
    for (size_t i = 0; i < ports.size() && chosen < 0; ++i)
      if (ports[i].name == def.port) chosen = static_cast<int>(i);
    if (chosen < 0) {
      int matches = 0;
      for (size_t i = 0; i < ports.size(); ++i)
        if (ports[i].name.find(def.port) != std::string::npos) {
          chosen = static_cast<int>(i);
          ++matches;
        }
      if (matches > 1)
        throw LiveMidiError("the MIDI port '" + def.port + "' is ambiguous; " + portList(ports));
    }
  }
  if (chosen < 0) throw LiveMidiError("no MIDI output port '" + def.port + "'; " + portList(ports));
  auto [system, port] = where[static_cast<size_t>(chosen)];
  try {
    systems[system].second->openPort(port, "out");
  } catch (const RtMidiError& error) {
    throw LiveMidiError("cannot open the MIDI port '" + ports[static_cast<size_t>(chosen)].name + "': " + error.getMessage());
  }
  out_ = std::move(systems[system].second);
  portName_ = ports[static_cast<size_t>(chosen)].name;
}

LiveMidiOutput::~LiveMidiOutput() = default;

void LiveMidiOutput::send(uint8_t status, uint8_t data1, uint8_t data2, int size) {
  const unsigned char bytes[3] = {status, data1, data2};
  try {
    out_->sendMessage(bytes, static_cast<size_t>(size));
  } catch (const RtMidiError& error) {
    throw LiveMidiError("sending to the MIDI port '" + portName_ + "' failed: " + error.getMessage());
  }
}

void LiveMidiStream::begin(int ppq) {
  std::lock_guard lock(mutex_);
  Piece piece;
  piece.sequence.ppq = ppq;
  pieces_.push_back(std::move(piece));
  changed_.notify_all();
}

void LiveMidiStream::add(std::span<const MidiMessage> messages, std::span<const MidiTempo> tempos, uint64_t released,
                         bool complete) {
  std::lock_guard lock(mutex_);
  if (pieces_.empty()) return;
  Piece& piece = pieces_.back();
  piece.sequence.messages.insert(piece.sequence.messages.end(), messages.begin(), messages.end());
  piece.sequence.tempos.assign(tempos.begin(), tempos.end());
  piece.released = std::max(piece.released, released);
  piece.complete = piece.complete || complete;
  changed_.notify_all();
}

void LiveMidiStream::close() {
  std::lock_guard lock(mutex_);
  closed_ = true;
  changed_.notify_all();
}

bool LiveMidiOutput::waitUntil(Clock::time_point deadline, const std::atomic<bool>& stop) {
  while (!stop.load(std::memory_order_relaxed)) {
    Clock::time_point now = Clock::now();
    if (now >= deadline - kSpin) break;
    std::this_thread::sleep_until(std::min(deadline - kSpin, now + kStopPoll));
  }
  if (stop.load(std::memory_order_relaxed)) return false;
  while (Clock::now() < deadline) std::this_thread::yield();
  return true;
}

PerformanceReport LiveMidiOutput::perform(const MidiSequence& sequence, const std::atomic<bool>& stop) {
  LiveMidiStream stream;
  stream.begin(sequence.ppq);
  stream.add(sequence.messages, sequence.tempos, std::numeric_limits<uint64_t>::max(), true);
  stream.close();
  return perform(stream, stop);
}

PerformanceReport LiveMidiOutput::perform(LiveMidiStream& stream, const std::atomic<bool>& stop) {
  PerformanceReport report;
  std::array<std::array<uint16_t, 128>, 16> sounding{};
  std::array<bool, 16> used{};
  auto seconds = [](double s) { return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s)); };
  Clock::time_point pieceStart{};  // of the piece playing; the next starts where it ended
  bool first = true;
  for (size_t index = 0;; ++index) {
    std::unique_lock lock(stream.mutex_);
    // Wait for the next piece, or the end.
    while (index >= stream.pieces_.size() && !stream.closed_ && !stop.load(std::memory_order_relaxed))
      stream.changed_.wait_for(lock, kStopPoll);
    if (stop.load(std::memory_order_relaxed)) {
      report.stopped = true;
      break;
    }
    if (index >= stream.pieces_.size()) break;  // closed
    LiveMidiStream::Piece& piece = stream.pieces_[index];
    const double ppq = piece.sequence.ppq;
    const double clockTicks = ppq / 24;  // 24 MIDI clocks a quarter note
    pieceStart = first ? Clock::now() + seconds(def_.lead) : std::max(pieceStart, Clock::now());
    first = false;
    Clock::duration stalled{};  // the piece's deadlines move on by its stalls
    size_t next = 0;            // the next message of the piece
    size_t clock = 0;           // the next clock's number
    bool started = false;       // 0xFA sent
    double endTick = 0;
    // The next event that is final: a message before the released tick (any of a whole
    // piece); a clock likewise, up to the piece's last message. Clocks go first at a tick.
    struct Next {
      double tick;
      bool clock;
    };
    auto nextEvent = [&]() -> std::optional<Next> {
      const MidiSequence& sequence = piece.sequence;
      std::optional<Next> event;
      if (next < sequence.messages.size() && (piece.complete || sequence.messages[next].tick < piece.released))
        event = Next{static_cast<double>(sequence.messages[next].tick), false};
      const double clockTick = static_cast<double>(clock) * clockTicks;
      const bool clockFinal =
          piece.complete ? !sequence.messages.empty() && clockTick <= static_cast<double>(sequence.messages.back().tick)
                         : clockTick < static_cast<double>(piece.released);
      if (def_.clock && clockFinal && (!event || clockTick <= event->tick)) event = Next{clockTick, true};
      return event;
    };
    for (;;) {
      std::optional<Next> event = nextEvent();
      if (!event && !piece.complete) {
        // Ahead of the development: wait for it. If what comes next was due while
        // waiting, the piece pauses by the delay instead of rushing to catch up.
        while (!(event = nextEvent()) && !piece.complete && !stop.load(std::memory_order_relaxed))
          stream.changed_.wait_for(lock, kStopPoll);
        if (stop.load(std::memory_order_relaxed)) break;
        if (event) {
          const Clock::time_point due = pieceStart + stalled + seconds(piece.sequence.secondsAt(event->tick));
          const Clock::time_point now = Clock::now();
          if (now > due) {
            stalled += now - due;
            ++report.stalls;
            report.stalledSeconds += std::chrono::duration<double>(now - due).count();
          }
        }
      }
      if (!event) {
        if (!piece.complete) continue;
        // The piece ends with its last message, or its last clock if the development
        // ran on past the music.
        endTick = piece.sequence.messages.empty() ? 0 : static_cast<double>(piece.sequence.messages.back().tick);
        if (clock > 0) endTick = std::max(endTick, static_cast<double>(clock - 1) * clockTicks);
        break;
      }
      const Clock::time_point deadline = pieceStart + stalled + seconds(piece.sequence.secondsAt(event->tick));
      const MidiMessage message = event->clock ? MidiMessage{} : piece.sequence.messages[next];
      lock.unlock();
      if (!waitUntil(deadline, stop)) {
        lock.lock();
        break;
      }
      if (event->clock) {
        if (!started) {
          send(0xFA, 0, 0, 1);
          started = true;
        }
        send(0xF8, 0, 0, 1);
        ++report.clocks;
        ++clock;
      } else {
        send(message.status, message.data1, message.data2, message.size());
        report.lateness.push_back(std::chrono::duration<double>(Clock::now() - deadline).count());
        ++report.sent;
        ++next;
        uint16_t& count = sounding[message.channel()][message.data1];
        used[message.channel()] = true;
        if (message.kind() == 0x90) ++count;
        if (message.kind() == 0x80 && count > 0) --count;
      }
      lock.lock();
    }
    const Clock::time_point end = pieceStart + stalled + seconds(piece.sequence.secondsAt(endTick));
    lock.unlock();
    if (stop.load(std::memory_order_relaxed)) {
      report.stopped = true;
      if (started) send(0xFC, 0, 0, 1);
      break;
    }
    if (started) send(0xFC, 0, 0, 1);
    pieceStart = end;
  }
  // Stop everything that was started.
  for (uint8_t channel = 0; channel < 16; ++channel) {
    for (uint8_t pitch = 0; pitch < 128; ++pitch)
      for (; sounding[channel][pitch] > 0; --sounding[channel][pitch]) {
        send(static_cast<uint8_t>(0x80 | channel), pitch, 64, 3);
        ++report.sent;
      }
    if (report.stopped && used[channel]) {
      send(static_cast<uint8_t>(0xB0 | channel), 64, 0, 3);   // sustain off
      send(static_cast<uint8_t>(0xB0 | channel), 123, 0, 3);  // all notes off
      report.sent += 2;
    }
  }
  // JACK delivers from a ring buffer in its next cycle: give it time before closing.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  return report;
}

TimingSummary summarizeTiming(std::vector<double> values) {
  TimingSummary summary;
  summary.count = values.size();
  if (values.empty()) return summary;
  std::sort(values.begin(), values.end());
  size_t n = values.size();
  summary.median = n % 2 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2;
  size_t rank = static_cast<size_t>(std::ceil(0.99 * static_cast<double>(n)));
  summary.p99 = values[std::min(n, std::max<size_t>(rank, 1)) - 1];
  summary.max = values.back();
  return summary;
}

}  // namespace ontogen
