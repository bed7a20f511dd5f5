#pragma once
// Standard MIDI File writer (SMF 1.0, formats 0 and 1). Format 1 puts the tempo map and
// time signature in a conductor track and each channel in a track of its own, in channel
// order, named by the score's track name for it (meta event 0x03); format 0 puts
// everything in one track, named after the sequence only. Channel messages use running status;
// every track ends with an end-of-track event; delta times are variable-length
// quantities. Values are validated before a byte is written, so a bad value gives an
// exception and no file, never a corrupt one.

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "interpreters/music/score.h"

namespace ontogen {

/// Settings of the file; validated by writeMidiFile.
struct MidiFileDef {
  int format = 1;            ///< 0: one track; 1: conductor track + one track per channel
  int ppq = 480;             ///< ticks per quarter note, 1..32767
  double tempo = 120;        ///< quarter notes per minute at the start, > 0
  int timeSignatureNumerator = 4;    ///< beats per bar, 1..255
  int timeSignatureDenominator = 4;  ///< note value of a beat: 1, 2, 4 ... 64
  std::string name;          ///< sequence name in the first track; empty: none
};

/// Throws std::invalid_argument naming the first field of def that is out of range.
void checkMidiFileDef(const MidiFileDef& def);

/// The bytes of the file for a score. Throws std::invalid_argument for a bad def or a
/// score whose gaps between events do not fit a delta time (28 bits of ticks).
std::vector<uint8_t> encodeMidiFile(const Score& score, const MidiFileDef& def);

/// Writes encodeMidiFile(score, def) to out.
void writeMidiFile(const Score& score, const MidiFileDef& def, std::ostream& out);

/// Appends value as a variable-length quantity (7 bits a byte, most significant first,
/// the high bit set on all but the last). Throws std::invalid_argument above 0x0FFFFFFF,
/// the largest a MIDI file allows.
void appendVariableLength(std::vector<uint8_t>& bytes, uint32_t value);

}  // namespace ontogen
