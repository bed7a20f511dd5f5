#include "interpreters/music/music_commands.h"

#include <array>

namespace ontogen {

namespace {

constexpr std::array kCommands = {
    MusicCommand{"note", MusicOp::Note, 0, 2, "note(d, v)",
                 "play the current pitch for d beats (default: duration) at velocity v "
                 "(default: velocity; below 0.5: silent, a rest), then move the time on by d"},
    MusicCommand{"play", MusicOp::Play, 1, 3, "play(p, d, v)",
                 "set the pitch to MIDI note p, then play it like note(d, v)"},
    MusicCommand{"hold", MusicOp::Hold, 0, 1, "hold(v)",
                 "developmental time: sound the current pitch from the cell's birth for as "
                 "long as it lives, without moving the time; sequential time: like note"},
    MusicCommand{"rest", MusicOp::Rest, 0, 1, "rest(d)",
                 "move the time on by d beats (default: duration) in silence"},
    MusicCommand{"at", MusicOp::At, 1, 1, "at(t)",
                 "move the time to beat t from the start (negative: 0), e.g. a grid "
                 "site's column: at(me.x / 2)"},
    MusicCommand{"pitch", MusicOp::Pitch, 1, 1, "pitch(p)",
                 "set the pitch to MIDI note p (60: middle C), rounded to a semitone"},
    MusicCommand{"up", MusicOp::Up, 0, 1, "up(n)", "raise the pitch by n semitones (default 1)"},
    MusicCommand{"down", MusicOp::Down, 0, 1, "down(n)", "lower the pitch by n semitones (default 1)"},
    MusicCommand{"degree", MusicOp::Degree, 1, 1, "degree(n)",
                 "move the pitch n degrees of the scale up (n < 0: down); a pitch outside "
                 "the scale first falls to the scale note below it"},
    MusicCommand{"scale", MusicOp::Scale, 1, 1, "scale(s)",
                 "choose the scale of degree, + and -: major, minor, harmonic, melodic, "
                 "dorian, phrygian, lydian, mixolydian, locrian, pentatonic, "
                 "minorpentatonic, blues, wholetone, chromatic (default: major)"},
    MusicCommand{"key", MusicOp::Key, 1, 1, "key(k)",
                 "set the tonic of the scale to pitch class k mod 12 (0: C, 2: D ... 11: B; "
                 "a note number works too; default 0)"},
    MusicCommand{"velocity", MusicOp::Velocity, 1, 1, "velocity(v)",
                 "set the velocity of following notes, 0..127 (clamped; 0: they are silent; "
                 "default 100)"},
    MusicCommand{"duration", MusicOp::Duration, 1, 1, "duration(d)",
                 "set the default length of note and rest, beats > 0 (default 1)"},
    MusicCommand{"gate", MusicOp::Gate, 1, 1, "gate(g)",
                 "articulation: following notes sound for the fraction g of their length, "
                 "0 < g <= 1 (1: legato, the default; 0.5: staccato); the time still moves "
                 "on by the whole length"},
    MusicCommand{"channel", MusicOp::Channel, 1, 1, "channel(c)",
                 "send following messages on MIDI channel c, 0..15 (9: General MIDI drums)"},
    MusicCommand{"program", MusicOp::Program, 1, 1, "program(p)",
                 "change the instrument of the current channel to program p, 0..127 "
                 "(General MIDI number - 1: 0 piano, 40 violin, 73 flute)"},
    MusicCommand{"tempo", MusicOp::Tempo, 1, 1, "tempo(bpm)",
                 "from now on, bpm quarter notes per minute for the whole piece (default: "
                 "#tempo, else 120)"},
    MusicCommand{"cc", MusicOp::Controller, 2, 2, "cc(n, v)",
                 "send control change n (0..127) with value v (0..127, clamped) on the "
                 "current channel"},
    MusicCommand{"sustain", MusicOp::Sustain, 1, 1, "sustain(on)",
                 "sustain pedal (controller 64): down when on != 0, up otherwise"},
    MusicCommand{"modulation", MusicOp::Modulation, 1, 1, "modulation(v)",
                 "modulation wheel (controller 1), 0..127 (clamped)"},
    MusicCommand{"bend", MusicOp::Bend, 1, 1, "bend(s)",
                 "pitch bend of the current channel by s semitones, -2..2 (clamped; the "
                 "General MIDI bend range)"},
    MusicCommand{"[", MusicOp::Push, 0, 0, "[",
                 "push the player state (pitch, time, velocity, duration, gate, "
                 "channel, scale, key): the branch becomes a voice that starts at the same time"},
    MusicCommand{"]", MusicOp::Pop, 0, 0, "]",
                 "pop the player state; an unmatched ] is ignored and counted in a warning"},
    MusicCommand{"F", MusicOp::TurtleNote, 0, 1, "F(l)",
                 "turtle reading: play the current pitch for duration beats (l is ignored)"},
    MusicCommand{"f", MusicOp::TurtleRest, 0, 1, "f(l)",
                 "turtle reading: rest for duration beats (l is ignored)"},
    MusicCommand{"+", MusicOp::TurtleUp, 0, 1, "+(a)",
                 "turtle reading: one degree of the scale up (a is ignored)"},
    MusicCommand{"-", MusicOp::TurtleDown, 0, 1, "-(a)",
                 "turtle reading: one degree of the scale down (a is ignored)"},
};

constexpr std::array kMajor = {0, 2, 4, 5, 7, 9, 11};
constexpr std::array kMinor = {0, 2, 3, 5, 7, 8, 10};
constexpr std::array kHarmonic = {0, 2, 3, 5, 7, 8, 11};
constexpr std::array kMelodic = {0, 2, 3, 5, 7, 9, 11};
constexpr std::array kDorian = {0, 2, 3, 5, 7, 9, 10};
constexpr std::array kPhrygian = {0, 1, 3, 5, 7, 8, 10};
constexpr std::array kLydian = {0, 2, 4, 6, 7, 9, 11};
constexpr std::array kMixolydian = {0, 2, 4, 5, 7, 9, 10};
constexpr std::array kLocrian = {0, 1, 3, 5, 6, 8, 10};
constexpr std::array kPentatonic = {0, 2, 4, 7, 9};
constexpr std::array kMinorPentatonic = {0, 3, 5, 7, 10};
constexpr std::array kBlues = {0, 3, 5, 6, 7, 10};
constexpr std::array kWholeTone = {0, 2, 4, 6, 8, 10};
constexpr std::array kChromatic = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};

const std::array kScales = {
    MusicScale{"major", kMajor},         MusicScale{"minor", kMinor},
    MusicScale{"harmonic", kHarmonic},   MusicScale{"melodic", kMelodic},
    MusicScale{"dorian", kDorian},       MusicScale{"phrygian", kPhrygian},
    MusicScale{"lydian", kLydian},       MusicScale{"mixolydian", kMixolydian},
    MusicScale{"locrian", kLocrian},     MusicScale{"pentatonic", kPentatonic},
    MusicScale{"minorpentatonic", kMinorPentatonic}, MusicScale{"blues", kBlues},
    MusicScale{"wholetone", kWholeTone}, MusicScale{"chromatic", kChromatic},
};

}  // namespace

std::span<const MusicCommand> musicCommands() { return kCommands; }

const MusicCommand* findMusicCommand(std::string_view name) {
  for (const MusicCommand& command : kCommands)
    if (command.name == name) return &command;
  return nullptr;
}

std::span<const MusicScale> musicScales() { return kScales; }

std::optional<double> musicConstant(std::string_view name) {
  for (size_t i = 0; i < kScales.size(); ++i)
    if (kScales[i].name == name) return static_cast<double>(i);
  return std::nullopt;
}

}  // namespace ontogen
