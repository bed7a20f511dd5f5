#pragma once
// A score: what the music player produced, in beats (quarter notes) from the start of the
// piece, before any MIDI encoding. The file writer and the live player both read it, so
// a file and a performance of the same run hold the same notes.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace ontogen {

/// One note. Values are already valid MIDI (the player drops or clamps bad ones).
struct ScoreNote {
  double start = 0;     ///< beats from the start, ≥ 0
  double duration = 1;  ///< beats, > 0
  uint8_t channel = 0;  ///< 0..15, as MIDI messages carry it (9: General MIDI percussion)
  uint8_t pitch = 60;   ///< MIDI note number 0..127 (60: middle C)
  uint8_t velocity = 100;  ///< 1..127
};

/// A channel message other than a note.
struct ScoreControl {
  enum class Kind : uint8_t {
    Controller,  ///< control change: number 0..127, value 0..127
    Program,     ///< program change: value 0..127 (General MIDI instrument - 1)
    PitchBend,   ///< pitch bend: value 0..16383, 8192 is the centre
  };
  double time = 0;  ///< beats from the start, ≥ 0
  Kind kind = Kind::Controller;
  uint8_t channel = 0;  ///< 0..15
  uint8_t number = 0;   ///< the controller number (Controller only)
  uint16_t value = 0;
};

/// A tempo change; tempo is global to the piece (the tempo map of the file).
struct ScoreTempo {
  double time = 0;   ///< beats from the start, ≥ 0
  double bpm = 120;  ///< quarter notes per minute, > 0
};

struct Score {
  std::vector<ScoreNote> notes;
  std::vector<ScoreControl> controls;
  std::vector<ScoreTempo> tempos;  ///< in the order they were given; the writer sorts
  /// The name of each channel's track (a track-name meta event in a format 1 file, what
  /// a DAW shows); empty: none.
  std::array<std::string, 16> trackNames;

  bool empty() const { return notes.empty() && controls.empty() && tempos.empty(); }
  void clear() {
    notes.clear();
    controls.clear();
    tempos.clear();
    trackNames = {};
  }
};

}  // namespace ontogen
