#include "interpreters/music/midi_sequence.h"

#include <algorithm>
#include <cmath>
#include <limits>
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

MidiMessage controlMessage(const ScoreControl& control, uint64_t tick) {
  MidiMessage message{tick, 0, 0, 0};
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
  return message;
}

}  // namespace

uint32_t microsecondsPerQuarter(double bpm) {
  double micros = std::round(60e6 / bpm);
  return static_cast<uint32_t>(std::clamp(micros, 1.0, 16777215.0));
}

double MidiSequence::secondsAt(double tick) const {
  double seconds = 0;
  double from = 0;
  uint32_t tempo = 500000;
  for (const MidiTempo& change : tempos) {
    if (static_cast<double>(change.tick) > tick) break;
    seconds += (static_cast<double>(change.tick) - from) * tempo / (1e6 * ppq);
    from = static_cast<double>(change.tick);
    tempo = change.microsecondsPerQuarter;
  }
  return seconds + (tick - from) * tempo / (1e6 * ppq);
}

bool MidiStreamEncoder::Pending::operator>(const Pending& other) const {
  if (tick != other.tick) return tick > other.tick;
  if (priority != other.priority) return priority > other.priority;
  if (group != other.group) return group > other.group;
  return index > other.index;
}

MidiStreamEncoder::MidiStreamEncoder(int ppq, double tempo) : ppq_(ppq), sounding_(16, std::vector<uint32_t>(128, 0)) {
  if (ppq < 1 || ppq > 32767) throw std::invalid_argument("ppq must be 1..32767");
  if (!(tempo > 0) || !std::isfinite(tempo)) throw std::invalid_argument("the tempo must be > 0");
  initialTempo_ = microsecondsPerQuarter(tempo);
}

void MidiStreamEncoder::take(const Score& score) {
  for (; nextNote_ < score.notes.size(); ++nextNote_) {
    const ScoreNote& note = score.notes[nextNote_];
    if (note.pitch > 127 || note.channel > 15 || !(note.duration > 0) || !std::isfinite(note.start)) continue;
    uint8_t velocity = std::clamp<uint8_t>(note.velocity, 1, 127);
    uint64_t on = toTick(note.start, ppq_);
    pending_.push({on, 2, 0, nextNote_, {on, static_cast<uint8_t>(0x90 | note.channel), note.pitch, velocity}});
    open_.push_back(nextNote_);
  }
  // Notes whose end is now known, in the order they were given.
  std::erase_if(open_, [&](size_t index) {
    const ScoreNote& note = score.notes[index];
    if (std::isinf(note.duration)) return false;
    uint64_t on = toTick(note.start, ppq_);
    // A note closed before it could sound still ends: its note-on may have been sent.
    uint64_t off = note.duration > 0 ? std::max(on + 1, toTick(note.start + note.duration, ppq_)) : on + 1;
    pending_.push({off, 0, 0, index, {off, static_cast<uint8_t>(0x80 | note.channel), note.pitch, 64}});
    return true;
  });
  for (; nextControl_ < score.controls.size(); ++nextControl_) {
    const ScoreControl& control = score.controls[nextControl_];
    if (control.channel > 15 || !std::isfinite(control.time)) continue;
    uint64_t tick = toTick(control.time, ppq_);
    pending_.push({tick, 1, 1, nextControl_, controlMessage(control, tick)});
  }
  for (; nextTempo_ < score.tempos.size(); ++nextTempo_)
    if (score.tempos[nextTempo_].bpm > 0 && std::isfinite(score.tempos[nextTempo_].bpm))
      tempos_.push_back(score.tempos[nextTempo_]);
  // The changes by time; at one tick the last given wins (release()).
  std::stable_sort(tempos_.begin(), tempos_.end(), [](const ScoreTempo& a, const ScoreTempo& b) { return a.time < b.time; });
}

void MidiStreamEncoder::release(uint64_t beforeTick, MidiSequence& out, size_t& appended) {
  released_ = std::max(released_, beforeTick);
  if (out.tempos.empty()) out.tempos.push_back({0, initialTempo_});
  size_t tempo = 0;
  for (; tempo < tempos_.size(); ++tempo) {
    MidiTempo entry{toTick(tempos_[tempo].time, ppq_), microsecondsPerQuarter(tempos_[tempo].bpm)};
    if (entry.tick >= beforeTick) break;
    if (!out.tempos.empty() && entry.tick <= out.tempos.back().tick)
      out.tempos.back().microsecondsPerQuarter = entry.microsecondsPerQuarter;
    else
      out.tempos.push_back(entry);
  }
  tempos_.erase(tempos_.begin(), tempos_.begin() + static_cast<std::ptrdiff_t>(tempo));

  while (!pending_.empty() && pending_.top().tick < beforeTick) {
    MidiMessage message = pending_.top().message;
    pending_.pop();
    // An end given after later messages were sent (a cell found gone a step late) is
    // sent at once: the sequence stays in sending order.
    if (!out.messages.empty()) message.tick = std::max(message.tick, out.messages.back().tick);
    uint32_t& count = sounding_[message.channel()][message.data1];
    size_t before = out.messages.size();
    if (message.kind() == 0x90) {
      if (count > 0)
        out.messages.push_back({message.tick, static_cast<uint8_t>(0x80 | message.channel()), message.data1, 64});
      ++count;
      out.messages.push_back(message);
    } else if (message.kind() == 0x80) {
      if (count > 0 && --count == 0) out.messages.push_back(message);
    } else {
      out.messages.push_back(message);
    }
    appended += out.messages.size() - before;
  }
}

size_t MidiStreamEncoder::advance(const Score& score, double horizon, MidiSequence& out) {
  out.ppq = ppq_;
  take(score);
  size_t appended = 0;
  // Events at the horizon's own tick wait: another may still come at that tick.
  release(toTick(horizon, ppq_), out, appended);
  return appended;
}

size_t MidiStreamEncoder::finish(const Score& score, MidiSequence& out) {
  out.ppq = ppq_;
  take(score);
  if (!open_.empty()) throw std::invalid_argument("a note of the score has no end");
  size_t appended = 0;
  release(std::numeric_limits<uint64_t>::max(), out, appended);
  return appended;
}

MidiSequence makeMidiSequence(const Score& score, int ppq, double tempo) {
  MidiStreamEncoder encoder(ppq, tempo);
  MidiSequence sequence;
  encoder.finish(score, sequence);
  return sequence;
}

}  // namespace ontogen
