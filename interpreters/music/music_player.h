#pragma once
// The music player: the musical counterpart of the turtle (paper 002, section 4.2). It
// keeps a state - pitch, time position, velocity, duration, gate, channel, scale and key - that
// the commands of music_commands.h change, and writes the notes and controller messages
// they make into a Score. `[` and `]` save and restore the whole state, time included, so
// a branch is a voice that starts where the branch opens, as a turtle's branch starts
// where it was pushed.
//
// Bad values never reach the score: a note outside 0..127 is dropped, a velocity or a
// controller value is clamped, a non-finite argument or a length ≤ 0 makes the command do
// nothing; each is counted in MusicWarnings.

#include <cstdint>
#include <map>
#include <span>
#include <stdexcept>
#include <string_view>
#include <tuple>
#include <vector>

#include "interpreters/music/music_commands.h"
#include "interpreters/music/score.h"

namespace ontogen {

/// Everything [ saves and ] restores.
struct MusicState {
  double time = 0;      ///< beats from the start
  double pitch = 60;    ///< MIDI note number, whole; may leave 0..127 (such notes are dropped)
  int velocity = 100;   ///< 0..127; 0 silences notes
  double duration = 1;  ///< beats > 0, the default length of note and rest
  /// The fraction of a note's length that sounds, 0 < gate <= 1 (articulation: 1 legato,
  /// 0.5 staccato); the time moves on by the whole length.
  double gate = 1;
  int channel = 0;      ///< 0..15
  int scale = 0;        ///< index into musicScales()
  int key = 0;          ///< tonic pitch class 0..11
};

/// The player's settings; validated when a player is created.
struct MusicPlayerDef {
  double tempo = 120;    ///< quarter notes per minute at the start, > 0
  MusicState initial{};  ///< the state after reset()
  /// Latest time anything may sound or end, beats: what a MIDI file reaches at its
  /// resolution (musicBeatsWithin). Later is a MusicTimeError.
  double maxBeats = 559240;  // 2^28 - 1 ticks at 480 ppq
};

/// The latest time, beats, a MIDI file of `ppq` ticks a quarter note reaches with every
/// gap between its events in one variable-length quantity (2^28 - 1 ticks): 559 240 beats
/// at 480 ppq, 77 hours at 120 bpm. A score that long is a mistake, not music.
inline double musicBeatsWithin(int ppq) { return ppq > 0 ? static_cast<double>(0x0FFFFFFF) / ppq : 0; }

/// A command would move the time past MusicPlayerDef::maxBeats (note(1e308), at(1e9)):
/// the program's error, which the music set locates at the instruction.
struct MusicTimeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Problems the player skipped over; the run reports them as warnings.
struct MusicWarnings {
  int64_t droppedNotes = 0;    ///< pitch outside 0..127
  int64_t badArguments = 0;    ///< non-finite values, lengths ≤ 0, unknown scales: ignored
  int64_t unmatchedPops = 0;   ///< ] with an empty stack, ignored

  int64_t total() const { return droppedNotes + badArguments + unmatchedPops; }
};

class MusicPlayer {
 public:
  /// Throws std::invalid_argument when def is out of range.
  explicit MusicPlayer(const MusicPlayerDef& def = {});

  /// Back to the initial state, empty stack, no warnings, no remembered controller values.
  void reset();

  /// Executes the command named `command` into score. Returns false, doing nothing, when
  /// there is no such player command.
  bool execute(std::string_view command, std::span<const double> args, Score& score);
  void execute(const MusicCommand& command, std::span<const double> args, Score& score);

  /// Developmental time (MusicSet): note commands may be switched off for cells that
  /// already played, `hold` is collected by takeHeldNotes() instead of played, and
  /// controller messages that repeat the last value sent are left out, so a controller
  /// driven by a `rate` variable sends only its changes.
  void setNotesEnabled(bool enabled) { notesEnabled_ = enabled; }
  void setDevelopmental(bool developmental) { developmental_ = developmental; }
  /// The notes `hold` started since the last call (developmental time); their duration
  /// is left to the caller, which knows when the cell dies.
  std::vector<ScoreNote> takeHeldNotes();
  /// How many notes `hold` started that takeHeldNotes() has not yet taken.
  std::size_t heldCount() const { return held_.size(); }

  /// Moves the time position, beats (negative values are taken as 0).
  void setTime(double beats) { state_.time = beats > 0 ? beats : 0; }
  /// The state to start the next word from: the initial state, current stack emptied.
  void restart();

  const MusicState& state() const { return state_; }
  std::size_t depth() const { return stack_.size(); }
  const MusicWarnings& warnings() const { return warnings_; }
  const MusicPlayerDef& def() const { return def_; }

 private:
  /// Throws MusicTimeError when `beats` is past def.maxBeats; `what` leads the message.
  void checkTime(double beats, const char* what) const;
  void playNote(double duration, double velocity, Score& score);
  void moveDegrees(double degrees);
  void sendControl(ScoreControl::Kind kind, double number, double value, Score& score);
  bool finite(std::span<const double> args);

  MusicPlayerDef def_;
  MusicState state_;
  std::vector<MusicState> stack_;
  MusicWarnings warnings_;
  bool notesEnabled_ = true;
  bool developmental_ = false;
  std::vector<ScoreNote> held_;
  double tempo_ = 120;
  /// Last value sent per (kind, channel, number), to leave out repeats (developmental).
  std::map<std::tuple<int, int, int>, int> lastControl_;
};

}  // namespace ontogen
