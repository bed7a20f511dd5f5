#include "interpreters/music/midi_sequence.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace ontogen {

namespace {

// Ticks are kept below 2^53 so that they convert to doubles exactly; a piece that long
// (at 480 ppq, 600 000 years at 120 bpm) is a mistake, not music.
constexpr double kMaxTick = 9007199254740992.0;

uint64_t toTick(double beats, int ppq) {
  double tick = std::round(std::max(beats, 0.0) * ppq);
  if (!(tick < kMaxTick)) throw std::invalid_argument("a time of the score is too far from the start");
  return static_cast<uint64_t>(tick);
}

/// Sending order within a tick: note-offs, then controllers and programs, then note-ons.
int priority(uint8_t kind) { return kind == 0x80 ? 0 : kind == 0x90 ? 2 : 1; }

}  // namespace

uint32_t microsecondsPerQuarter(double bpm) {
  double micros = std::round(60e6 / bpm);
  return static_cast<uint32_t>(std::clamp(micros, 1.0, 16777215.0));
}

double MidiSequence::secondsAt(uint64_t tick) const {
  double seconds = 0;
  uint64_t from = 0;
  uint32_t tempo = 500000;
  for (const MidiTempo& change : tempos) {
    if (change.tick > tick) break;
    seconds += static_cast<double>(change.tick - from) * tempo / (1e6 * ppq);
    from = change.tick;
    tempo = change.microsecondsPerQuarter;
  }
  return seconds + static_cast<double>(tick - from) * tempo / (1e6 * ppq);
}

MidiSequence makeMidiSequence(const Score& score, int ppq, double tempo) {
  if (ppq < 1 || ppq > 32767) throw std::invalid_argument("ppq must be 1..32767");
  if (!(tempo > 0) || !std::isfinite(tempo)) throw std::invalid_argument("the tempo must be > 0");
  MidiSequence sequence;
  sequence.ppq = ppq;

  // The tempo map: the initial tempo, then the changes by time (the last given wins at
  // one tick).
  std::vector<ScoreTempo> tempos = score.tempos;
  std::stable_sort(tempos.begin(), tempos.end(), [](const ScoreTempo& a, const ScoreTempo& b) { return a.time < b.time; });
  sequence.tempos.push_back({0, microsecondsPerQuarter(tempo)});
  for (const ScoreTempo& change : tempos) {
    if (!(change.bpm > 0) || !std::isfinite(change.bpm)) continue;
    MidiTempo entry{toTick(change.time, ppq), microsecondsPerQuarter(change.bpm)};
    if (entry.tick == sequence.tempos.back().tick)
      sequence.tempos.back() = entry;
    else
      sequence.tempos.push_back(entry);
  }

  struct Raw {
    MidiMessage message;
    size_t order;
  };
  std::vector<Raw> raw;
  raw.reserve(score.notes.size() * 2 + score.controls.size());
  for (const ScoreNote& note : score.notes) {
    if (note.pitch > 127 || note.channel > 15 || !(note.duration > 0) || !std::isfinite(note.start)) continue;
    uint8_t velocity = std::clamp<uint8_t>(note.velocity, 1, 127);
    uint64_t on = toTick(note.start, ppq);
    uint64_t off = std::max(on + 1, toTick(note.start + note.duration, ppq));
    raw.push_back({{on, static_cast<uint8_t>(0x90 | note.channel), note.pitch, velocity}, raw.size()});
    raw.push_back({{off, static_cast<uint8_t>(0x80 | note.channel), note.pitch, 64}, raw.size()});
  }
  for (const ScoreControl& control : score.controls) {
    if (control.channel > 15 || !std::isfinite(control.time)) continue;
    MidiMessage message{toTick(control.time, ppq), 0, 0, 0};
    switch (control.kind) {
      case ScoreControl::Kind::Controller:
        message.status = static_cast<uint8_t>(0xB0 | control.channel);
        message.data1 = std::min<uint8_t>(control.number, 127);
        message.data2 = static_cast<uint8_t>(std::min<uint16_t>(control.value, 127));
        break;
      case ScoreControl::Kind::Program:
        message.status = static_cast<uint8_t>(0xC0 | control.channel);
        message.data1 = static_cast<uint8_t>(std::min<uint16_t>(control.value, 127));
        break;
      case ScoreControl::Kind::PitchBend: {
        uint16_t value = std::min<uint16_t>(control.value, 16383);
        message.status = static_cast<uint8_t>(0xE0 | control.channel);
        message.data1 = value & 0x7F;
        message.data2 = static_cast<uint8_t>(value >> 7);
        break;
      }
    }
    raw.push_back({message, raw.size()});
  }
  std::sort(raw.begin(), raw.end(), [](const Raw& a, const Raw& b) {
    if (a.message.tick != b.message.tick) return a.message.tick < b.message.tick;
    int pa = priority(a.message.kind()), pb = priority(b.message.kind());
    if (pa != pb) return pa < pb;
    return a.order < b.order;
  });

  std::array<std::array<uint32_t, 128>, 16> sounding{};
  sequence.messages.reserve(raw.size());
  for (const Raw& entry : raw) {
    const MidiMessage& message = entry.message;
    uint32_t& count = sounding[message.channel()][message.data1];
    if (message.kind() == 0x90) {
      if (count > 0)
        sequence.messages.push_back({message.tick, static_cast<uint8_t>(0x80 | message.channel()), message.data1, 64});
      ++count;
      sequence.messages.push_back(message);
    } else if (message.kind() == 0x80) {
      if (count > 0 && --count == 0) sequence.messages.push_back(message);
    } else {
      sequence.messages.push_back(message);
    }
  }
  return sequence;
}

}  // namespace ontogen
