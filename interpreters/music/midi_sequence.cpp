#include "interpreters/music/midi_sequence.h"

#include <algorithm>
#include <cmath>
#include <iterator>
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

MidiStreamEncoder::MidiStreamEncoder(int ppq, double tempo) : ppq_(ppq), sounding_(16, std::vector<uint32_t>(128, 0)) {
  if (ppq < 1 || ppq > 32767) throw std::invalid_argument("ppq must be 1..32767");
  if (!(tempo > 0) || !std::isfinite(tempo)) throw std::invalid_argument("the tempo must be > 0");
  initialTempo_ = microsecondsPerQuarter(tempo);
}

// The note-off of a note whose end is known. A note closed before it could sound still
// ends: its note-on may have been sent.
void MidiStreamEncoder::takeNoteOff(const ScoreNote& note, size_t index) {
  const uint64_t on = toTick(note.start, ppq_);
  const uint64_t off = note.duration > 0 ? std::max(on + 1, toTick(note.start + note.duration, ppq_)) : on + 1;
  taken_.push_back(pending(off, 0, index, static_cast<uint8_t>(0x80 | note.channel), note.pitch, 64));
}

void MidiStreamEncoder::take(const Score& score) {
  // Room for what the score added (a note-on and -off each note), growing as a vector does.
  const size_t room = taken_.size() + 2 * (score.notes.size() - nextNote_) + (score.controls.size() - nextControl_);
  if (room > taken_.capacity()) taken_.reserve(std::max(room, 2 * taken_.capacity()));
  // Notes still sounding (an infinite duration) wait in open_ for their end.
  std::erase_if(open_, [&](size_t index) {
    const ScoreNote& note = score.notes[index];
    if (std::isinf(note.duration)) return false;
    takeNoteOff(note, index);
    return true;
  });
  for (; nextNote_ < score.notes.size(); ++nextNote_) {
    const ScoreNote& note = score.notes[nextNote_];
    if (note.pitch > 127 || note.channel > 15 || !(note.duration > 0) || !std::isfinite(note.start)) continue;
    uint8_t velocity = std::clamp<uint8_t>(note.velocity, 1, 127);
    uint64_t on = toTick(note.start, ppq_);
    taken_.push_back(pending(on, 2, nextNote_, static_cast<uint8_t>(0x90 | note.channel), note.pitch, velocity));
    if (std::isinf(note.duration))
      open_.push_back(nextNote_);
    else
      takeNoteOff(note, nextNote_);
  }
  for (; nextControl_ < score.controls.size(); ++nextControl_) {
    const ScoreControl& control = score.controls[nextControl_];
    if (control.channel > 15 || !std::isfinite(control.time)) continue;
    const MidiMessage message = controlMessage(control, toTick(control.time, ppq_));
    taken_.push_back(pending(message.tick, 1, nextControl_, message.status, message.data1, message.data2));
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

  if (!taken_.empty()) {
    std::sort(taken_.begin(), taken_.end());
    if (pending_.empty()) {
      pending_.swap(taken_);
    } else {
      merged_.clear();
      merged_.reserve(pending_.size() + taken_.size());
      std::merge(pending_.begin(), pending_.end(), taken_.begin(), taken_.end(), std::back_inserter(merged_));
      pending_.swap(merged_);
    }
    taken_.clear();
  }
  // What is released, sorted by tick: room for it in `out` at once (a note-on may add a
  // note-off before it; push_back makes room for those).
  const size_t end = static_cast<size_t>(
      std::partition_point(pending_.begin(), pending_.end(), [&](const Pending& p) { return p.tick < beforeTick; }) -
      pending_.begin());
  const size_t room = out.messages.size() + end;
  if (room > out.messages.capacity()) out.messages.reserve(std::max(room, 2 * out.messages.capacity()));
  size_t next = 0;
  for (; next < end; ++next) {
    const Pending& waiting = pending_[next];
    MidiMessage message{waiting.tick, waiting.status, waiting.data1, waiting.data2};
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
  pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(next));
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
