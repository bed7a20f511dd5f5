#pragma once
// A Score turned into MIDI channel messages on a tick grid, in the order they are sent:
// the one encoding the file writer and the live player share. Every note-on gets its
// note-off; when two notes of the same pitch and channel overlap, the later one retriggers
// (note-off, note-on) and one note-off ends the pair, so no sounding note is cut short by
// the other's note-off and none is left hanging. At one tick, note-offs go first, then
// controllers and program changes, then note-ons.

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

  /// Seconds from the start to a tick, through the tempo map.
  double secondsAt(uint64_t tick) const;
  /// The tick of the last message (0 when there is none).
  uint64_t endTick() const { return messages.empty() ? 0 : messages.back().tick; }
};

/// Encodes a score at ppq ticks per quarter note (1..32767), starting at `tempo` quarter
/// notes per minute. Times round to the nearest tick; a note lasts at least one tick.
/// Throws std::invalid_argument for a ppq or tempo out of range.
MidiSequence makeMidiSequence(const Score& score, int ppq, double tempo);

/// Microseconds per quarter note for a tempo in quarter notes per minute, clamped to the
/// 24 bits a file holds (tempos below 3.6 bpm play at 3.6 bpm).
uint32_t microsecondsPerQuarter(double bpm);

}  // namespace ontogen
