#pragma once
// A Score turned into MIDI channel messages on a tick grid, in the order they are sent:
// the one encoding the file writer and the live player share. Every note-on gets its
// note-off; when two notes of the same pitch and channel overlap, the later one retriggers
// (note-off, note-on) and one note-off ends the pair, so no sounding note is cut short by
// the other's note-off and none is left hanging. At one tick, note-offs go first, then
// controllers and program changes, then note-ons; within each, notes and controls in the
// order the score holds them.
//
// MidiStreamEncoder encodes a score while it is still being played (developmental time
// streamed live): what lies before a horizon is final, so it is sent; a note still
// sounding (its duration infinite, `hold` of a living cell) sends its note-on now and its
// note-off when the score gives it an end. makeMidiSequence is the same encoder run over a
// finished score at once, so a file and a streamed performance hold the same messages.

#include <cstdint>
#include <vector>

#include "interpreters/music/score.h"

namespace ontogen {

/// One channel message (status byte with channel, then one or two data bytes).
struct MidiMessage {
  uint64_t tick = 0;
  uint8_t status = 0;  ///< 0x80 note-off, 0x90 note-on, 0xB0 controller, 0xC0 program, 0xE0 bend; | channel
  uint8_t data1 = 0;
  uint8_t data2 = 0;   ///< unused for program changes

  uint8_t channel() const { return status & 0x0F; }
  uint8_t kind() const { return status & 0xF0; }
  /// 2 for program changes, 3 for the others.
  int size() const { return kind() == 0xC0 ? 2 : 3; }
};

/// A tempo change on the tick grid.
struct MidiTempo {
  uint64_t tick = 0;
  uint32_t microsecondsPerQuarter = 500000;  ///< 24 bits in a file: 1 .. 16777215
};

struct MidiSequence {
  int ppq = 480;                      ///< ticks per quarter note
  std::vector<MidiMessage> messages;  ///< in sending order, ticks ascending
  std::vector<MidiTempo> tempos;      ///< ascending, the first at tick 0

  /// Seconds from the start to a tick (fractions of a tick too), through the tempo map.
  double secondsAt(double tick) const;
  /// The tick of the last message (0 when there is none).
  uint64_t endTick() const { return messages.empty() ? 0 : messages.back().tick; }
};

/// Encodes a growing score into a sequence, a horizon at a time. The score may only grow:
/// notes, controls and tempos appended, and notes of infinite duration (still sounding)
/// given a finite one. Times round to the nearest tick; a note lasts at least one tick.
class MidiStreamEncoder {
 public:
  /// ppq ticks per quarter note (1..32767), starting at `tempo` quarter notes per minute.
  /// Throws std::invalid_argument for a ppq or tempo out of range.
  MidiStreamEncoder(int ppq, double tempo);

  /// Appends to `out` the messages and tempo changes of `score` before `horizon` beats
  /// that were not yet appended; nothing the score may still add lies before it. Returns
  /// how many messages it appended. Throws std::invalid_argument for a time too far
  /// from the start.
  size_t advance(const Score& score, double horizon, MidiSequence& out);
  /// Appends everything left: the score is finished. Throws std::invalid_argument when a
  /// note still has no end.
  size_t finish(const Score& score, MidiSequence& out);
  /// The tick before which everything is appended (the last horizon's; all, once finished).
  uint64_t released() const { return released_; }

 private:
  // A message waiting to be sent, 24 bytes: its tick, then its place among the messages
  // of that tick (note-offs, other messages, note-ons; then the score's order).
  struct Pending {
    uint64_t tick;
    uint64_t order;  // priority << 62 | the index of its note or control in the score
    uint8_t status, data1, data2;
    bool operator<(const Pending& other) const {
      return tick != other.tick ? tick < other.tick : order < other.order;
    }
  };
  // priority: 0 note-off, 1 control, 2 note-on.
  static Pending pending(uint64_t tick, uint64_t priority, size_t index, uint8_t status, uint8_t data1,
                         uint8_t data2) {
    return {tick, priority << 62 | index, status, data1, data2};
  }
  void takeNoteOff(const ScoreNote& note, size_t index);
  void take(const Score& score);
  void release(uint64_t beforeTick, MidiSequence& out, size_t& appended);

  int ppq_;
  uint32_t initialTempo_;
  uint64_t released_ = 0;
  size_t nextNote_ = 0, nextControl_ = 0, nextTempo_ = 0;
  std::vector<size_t> open_;  // notes whose note-on is queued and whose end is not yet known
  // Messages not yet released, in sending order, and those taken since the last release.
  // A release sorts what was taken and merges it in: a priority queue of a million notes
  // took six times as long, each pop missing the cache down the heap.
  std::vector<Pending> pending_, taken_, merged_;
  std::vector<ScoreTempo> tempos_;  // changes given but not yet on the grid, by time
  std::vector<std::vector<uint32_t>> sounding_;  // [channel][pitch]: note-ons sent without their note-off
};

/// Encodes a finished score at ppq ticks per quarter note (1..32767), starting at
/// `tempo` quarter notes per minute. Throws std::invalid_argument for a ppq or tempo out
/// of range, or a time too far from the start.
MidiSequence makeMidiSequence(const Score& score, int ppq, double tempo);

/// Microseconds per quarter note for a tempo in quarter notes per minute, clamped to the
/// 24 bits a file holds (tempos below 3.6 bpm play at 3.6 bpm).
uint32_t microsecondsPerQuarter(double bpm);

}  // namespace ontogen
