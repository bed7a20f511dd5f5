#pragma once
// The table of player commands of the "music" interpretation set (paper 002, section
// 4.2: a state-based player turns commands into MIDI messages). The player executes from
// it, the compiler checks arities against it, and `ontogen help` prints it.
//
// Units: pitches are MIDI note numbers (60 = middle C), times and durations are beats
// (quarter notes), velocities and controller values 0..127, channels and programs 0-based
// as MIDI messages carry them. The turtle's F f + - [ ] are read as music too, so any
// L-system word plays as a melody (Prusinkiewicz's "score generation" reading): F plays,
// f rests, + and - move a degree of the scale, and their turtle arguments are ignored.

#include <optional>
#include <span>
#include <string_view>

namespace ontogen {

/// What a player command does; the player dispatches on it.
enum class MusicOp {
  Note,        ///< note(d, v)
  Play,        ///< play(p, d, v)
  Hold,        ///< hold(v)
  Rest,        ///< rest(d)
  At,          ///< at(t)
  Pitch,       ///< pitch(p)
  Up,          ///< up(n)
  Down,        ///< down(n)
  Degree,      ///< degree(n)
  Scale,       ///< scale(s)
  Key,         ///< key(k)
  Velocity,    ///< velocity(v)
  Duration,    ///< duration(d)
  Gate,        ///< gate(g)
  Channel,     ///< channel(c)
  Program,     ///< program(p)
  Tempo,       ///< tempo(bpm)
  Controller,  ///< cc(n, v)
  Sustain,     ///< sustain(on)
  Modulation,  ///< modulation(v)
  Bend,        ///< bend(s)
  Push,        ///< [
  Pop,         ///< ]
  TurtleNote,  ///< F
  TurtleRest,  ///< f
  TurtleUp,    ///< +
  TurtleDown,  ///< -
};

/// One row of the table.
struct MusicCommand {
  std::string_view name;       ///< as it appears in a block or a word
  MusicOp op;
  int minArity;
  int maxArity;
  std::string_view signature;  ///< e.g. "note(d, v)"
  std::string_view doc;        ///< one line, with units and defaults
};

/// Every player command, in the order `ontogen help` lists them.
std::span<const MusicCommand> musicCommands();

/// The command named `name`, or nullptr.
const MusicCommand* findMusicCommand(std::string_view name);

/// A scale: the semitones of its degrees above the tonic, ascending, first 0.
struct MusicScale {
  std::string_view name;  ///< the name programs write, as in `scale(dorian)`
  std::span<const int> steps;
};

/// Every scale; a scale's number (what `scale(minor)` passes) is its index here.
std::span<const MusicScale> musicScales();

/// The number of the scale named `name` (for the compiler's names in `interpret music`
/// blocks), or nothing.
std::optional<double> musicConstant(std::string_view name);

}  // namespace ontogen
