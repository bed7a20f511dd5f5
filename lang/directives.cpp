#include "lang/directives.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "model/message_number.h"
#include "model/program.h"

namespace ontogen {

namespace {

using Kind = DirectiveKind;
using Owner = DirectiveOwner;
using Value = DirectiveValue;
using Target = DirectiveTarget;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Seeds are whole numbers a double holds exactly: 2^53 - 1 is the largest below which
// every whole number is one.
constexpr double kMaxSeed = 9007199254740991.0;

constexpr std::array<std::string_view, 2> kMusicTimes{"sequential", "developmental"};
// The looks of pictures (interpreters/formats/look.h, lookNames(); a test keeps the two
// lists equal).
constexpr std::array<std::string_view, 3> kLookNames{"light", "dark", "paper"};
// The interpretation sets (interpreters/set_registry.h, interpretationSetNames(); a test
// keeps the two lists equal).
constexpr std::array<std::string_view, 7> kSetNames{"geometry", "creature", "dynamics", "physics", "image", "music", "trace"};
// What #allow accepts that is otherwise an error.
constexpr std::array<std::string_view, 1> kAllowances{"nonfinite"};

// The order is the one `unknown directive` lists and `ontogen help` prints.
// Limits: ppq and the beats per bar are what a MIDI file can hold (a 15-bit division, a
// byte); surface ids are 0..1023 as section ids are (interpreters/turtle.cpp); a
// relative error of 1 or more is no tolerance at all.
const std::array kDirectives{
    Directive{.name = "define",
              .kind = Kind::Define,
              .owner = Owner::Constants,
              .syntax = "#define NAME EXPR",
              .doc = "a named constant; its value may use the constants defined before it"},
    Directive{.name = "range",
              .kind = Kind::Range,
              .owner = Owner::Constants,
              .syntax = "#range NAME LOW HIGH",
              .doc = "the values `ontogen evolve` may give the block's #define NAME, LOW < HIGH (signed numbers)"},
    Directive{.name = "angle",
              .owner = Owner::Geometry,
              .rangeError = "#angle must be a finite number",
              .syntax = "#angle A",
              .doc = "default angle of + - & ^ \\ /; also sets #yawangle",
              .apply = [](const Value& v, Target& t) { t.settings.angle = t.settings.yawAngle = v.number; }},
    Directive{.name = "yawangle",
              .owner = Owner::Geometry,
              .rangeError = "#yawangle must be a finite number",
              .syntax = "#yawangle A",
              .doc = "default angle of < and >",
              .apply = [](const Value& v, Target& t) { t.settings.yawAngle = v.number; }},
    Directive{.name = "length",
              .owner = Owner::Geometry,
              .rangeError = "#length must be a finite number",
              .syntax = "#length L",
              .doc = "default length of F, f and cC, model units",
              .apply = [](const Value& v, Target& t) { t.settings.step = v.number; }},
    Directive{.name = "radius",
              .owner = Owner::Geometry,
              .range = {.min = 0},
              .rangeError = "#radius must be a number ≥ 0",
              .syntax = "#radius R",
              .doc = "initial radius of F and cC; 0 draws lines",
              .apply = [](const Value& v, Target& t) { t.settings.radius = v.number; }},
    Directive{.name = "radians",
              .kind = Kind::Flag,
              .owner = Owner::Geometry,
              .syntax = "#radians",
              .doc = "the turtle's angles, arguments and defaults are in radians",
              .apply = [](const Value&, Target& t) { t.settings.radians = true; }},
    Directive{.name = "degrees",
              .kind = Kind::Flag,
              .owner = Owner::Geometry,
              .syntax = "#degrees",
              .doc = "the turtle's angles, arguments and defaults are in degrees (the default)",
              .apply = [](const Value&, Target& t) { t.settings.radians = false; }},
    Directive{.name = "seed",
              .kind = Kind::Integer,
              .owner = Owner::World,
              .range = {.min = 0, .max = kMaxSeed},
              .rangeError = "#seed must be a whole number from 0 to 2^53 - 1 (9007199254740991)",
              .syntax = "#seed N",
              .doc = "seed of every random choice (--seed overrides)",
              .apply =
                  [](const Value& v, Target& t) {
                    t.program.seed = static_cast<uint64_t>(v.number);
                    t.program.hasSeed = true;
                  }},
    Directive{.name = "until",
              .owner = Owner::World,
              .range = {.min = 0, .minOpen = true},
              .rangeError = "#until must be a finite number greater than 0",
              .syntax = "#until T",
              .doc = "end of ontogen run, seconds of developmental time (--until overrides)",
              .apply = [](const Value& v, Target& t) { t.program.until = v.number; }},
    Directive{.name = "from",
              .owner = Owner::World,
              .range = {.min = 0},
              .rangeError = "#from must be a finite number, 0 or more",
              .syntax = "#from T",
              .doc = "time of ontogen run's first frame, seconds (frames spread over [from, until]; --from overrides)",
              .apply = [](const Value& v, Target& t) { t.program.from = v.number; }},
    Directive{.name = "fps",
              .owner = Owner::World,
              .range = {.min = 0, .max = 1000, .minOpen = true},
              .rangeError = "#fps is in frames per second of developmental time, above 0 and at most 1000",
              .syntax = "#fps F",
              .doc = "frames of ontogen run per second of developmental time when --frames is not given",
              .apply = [](const Value& v, Target& t) { t.program.framesPerSecond = v.number; }},
    // Its upper end: a second of movie showing more than 10^9 s of growth (thirty years)
    // has no use a model of development needs.
    Directive{.name = "speed",
              .owner = Owner::World,
              .range = {.min = 0, .max = 1e9, .minOpen = true},
              .rangeError = "#speed is in seconds of developmental time a second of the movie shows, above 0 and at most 1e9",
              .syntax = "#speed S",
              .doc = "seconds of developmental time each second of ontogen run's movie shows: frames S / --fps apart "
                     "(--speed overrides; before #fps, after --frames)",
              .apply = [](const Value& v, Target& t) { t.program.speed = v.number; }},
    Directive{.name = "look",
              .kind = Kind::Word,
              .owner = Owner::World,
              .words = kLookNames,
              .syntax = "#look WORD",
              .doc = "background, light and palette of ontogen run's pictures and movies (--look overrides)",
              .apply = [](const Value& v, Target& t) { t.program.look = std::string(v.word); }},
    Directive{.name = "interpret",
              .kind = Kind::Word,
              .owner = Owner::World,
              .words = kSetNames,
              .syntax = "#interpret SET",
              .doc = "an interpretation set ontogen run uses when --interpret is not given; repeat for several",
              .apply =
                  [](const Value& v, Target& t) {
                    auto& sets = t.program.interpretSets;
                    if (std::find(sets.begin(), sets.end(), v.word) == sets.end()) sets.emplace_back(v.word);
                  }},
    Directive{.name = "dt",
              .owner = Owner::World,
              .range = {.min = 0, .minOpen = true},
              .rangeError = "#dt must be a finite number greater than 0",
              .syntax = "#dt D",
              .doc = "step of the development, seconds (--step overrides)",
              .apply = [](const Value& v, Target& t) { t.program.dt = v.number; }},
    // Its upper end: a step past a tenth of a second resolves no contact a body makes.
    Directive{.name = "timestep",
              .owner = Owner::Geometry,
              .range = {.min = 0, .max = 0.1, .minOpen = true},
              .rangeError = "#timestep is the dynamics set's simulation step in seconds, above 0 and at most 0.1",
              .syntax = "#timestep H",
              .doc = "the dynamics set's simulation step, seconds (default 0.002); fixed, whatever the frames",
              .apply = [](const Value& v, Target& t) { t.settings.timestep = v.number; }},
    Directive{.name = "tolerance",
              .owner = Owner::World,
              .range = {.min = 0, .max = 1, .minOpen = true, .maxOpen = true},
              .rangeError = "#tolerance is between 0 and 1, as in 1e-6",
              .syntax = "#tolerance T",
              .doc = "integrate rate() adaptively (Dormand-Prince) to this absolute and relative error",
              .apply = [](const Value& v, Target& t) { t.program.rateTolerance = v.number; }},
    Directive{.name = "allow",
              .kind = Kind::Word,
              .owner = Owner::World,
              .words = kAllowances,
              .syntax = "#allow WORD",
              .doc = "accept what is otherwise an error: nonfinite, state that becomes an infinity or NaN",
              .apply = [](const Value&, Target& t) { t.program.allowsNonfinite = true; }},
    Directive{.name = "music",
              .kind = Kind::Word,
              .owner = Owner::Music,
              .words = kMusicTimes,
              .syntax = "#music WORD",
              .doc = "how the music set places notes in time: reading the word, or as cells are born",
              .apply =
                  [](const Value& v, Target& t) {
                    t.settings.music.time =
                        v.word == "developmental" ? MusicTime::Developmental : MusicTime::Sequential;
                  }},
    Directive{.name = "tempo",
              .owner = Owner::Music,
              .range = {.min = 0, .max = 1000, .minOpen = true},
              .rangeError = "#tempo is in quarter notes per minute, above 0 and at most 1000",
              .syntax = "#tempo BPM",
              .doc = "quarter notes per minute at the start of the music",
              .apply = [](const Value& v, Target& t) { t.settings.music.tempo = v.number; }},
    Directive{.name = "ppq",
              .kind = Kind::Integer,
              .owner = Owner::Music,
              .range = {.min = 1, .max = 32767},
              .rangeError = "#ppq must be a whole number of ticks per quarter note, 1 to 32767",
              .syntax = "#ppq N",
              .doc = "resolution of the MIDI file, ticks per quarter note",
              .apply = [](const Value& v, Target& t) { t.settings.music.ppq = static_cast<int>(v.number); }},
    Directive{.name = "midiformat",
              .kind = Kind::Integer,
              .owner = Owner::Music,
              .range = {.min = 0, .max = 1},
              .rangeError = "#midiformat must be 0 (one track) or 1 (a track per channel)",
              .syntax = "#midiformat F",
              .doc = "MIDI file format: 0 one track, 1 a conductor track and a track per channel",
              .apply = [](const Value& v, Target& t) { t.settings.music.format = static_cast<int>(v.number); }},
    Directive{.name = "timesig",
              .kind = Kind::TimeSignature,
              .owner = Owner::Music,
              .range = {.min = 1, .max = 255},
              .syntax = "#timesig N/D",
              .doc = "time signature written in the MIDI file: N beats of 1/D",
              .apply =
                  [](const Value& v, Target& t) {
                    t.settings.music.timeSignatureNumerator = v.numerator;
                    t.settings.music.timeSignatureDenominator = v.denominator;
                  }},
    Directive{.name = "track",
              .kind = Kind::NumberedName,
              .owner = Owner::Music,
              .range = {.min = 0, .max = 15},
              .rangeError = "#track takes a channel 0 to 15 before the name, as in #track 1 \"Bass\"",
              .syntax = "#track C \"NAME\"",
              .doc = "name of channel C's track in the MIDI file (default: the cells that play on it)",
              .apply =
                  [](const Value& v, Target& t) {
                    t.settings.music.trackNames[static_cast<size_t>(v.number)] = v.name;
                  }},
    Directive{.name = "surface",
              .kind = Kind::NumberedFile,
              .owner = Owner::Geometry,
              .range = {.min = 0, .max = 1023},
              .rangeError = "#surface takes a whole number 0 to 1023 before the file, as in #surface 1 \"bud.obj\"",
              .syntax = "#surface ID \"file.obj\"",
              .doc = "predefined surface ID read from a Wavefront OBJ file, relative to the program's file",
              .apply =
                  [](const Value& v, Target& t) {
                    t.settings.surfaces.push_back({static_cast<int>(v.number), v.path, v.location});
                  }},
    // The parser reads it (lang/parser.cpp); nothing is left to apply.
    Directive{
        .name = "letters",
        .kind = Kind::Flag,
        .owner = Owner::Notation,
        .syntax = "#letters",
        .doc =
            "one module per letter, digit or symbol in axioms and productions, as ABOP prints them (FF-[-F+F]+[+F-F])",
        .apply = [](const Value&, Target&) {}},
};

// Directives of cpfg and lpfg that ontogen writes another way.
struct ForeignDirective {
  std::string_view name;
  std::string_view instead;
};
constexpr ForeignDirective kForeignDirectives[] = {
    {"ignore", "cpfg's '#ignore' is written 'ignore: A B' (without '#') in an lsystem block"},
    {"consider", "cpfg's '#consider' is written 'consider: A B' (without '#') in an lsystem block"},
    {"include", "cpfg's '#include' is written 'import \"file.cell\"' at the top level"},
};

// Whole numbers in full (the largest seed has 16 digits), others as any message writes them.
std::string formatNumber(double value) {
  if (value == std::floor(value) && std::fabs(value) < 1e16) return messageNumber(value, 17);
  return messageNumber(value);
}

// "a, b or c".
template <typename Items>
std::string choices(const Items& items) {
  std::string text;
  for (size_t i = 0; i < items.size(); ++i)
    text += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + std::string(items[i]);
  return text;
}

}  // namespace

bool DirectiveRange::any() const {
  return min == -kInfinity && max == kInfinity && !minOpen && !maxOpen;
}

bool DirectiveRange::contains(double value) const {
  return (minOpen ? value > min : value >= min) && (maxOpen ? value < max : value <= max);
}

bool Directive::accepts(double value) const {
  // No setting means anything infinite or undefined: the turtle, the world and the
  // writers all take finite numbers only.
  if (!std::isfinite(value)) return false;
  const bool real = kind == DirectiveKind::Number || kind == DirectiveKind::Range;
  if (real && range.any()) return true;
  if (!real && value != std::floor(value)) return false;
  return range.contains(value);
}

std::span<const Directive> directives() {
  return kDirectives;
}

const Directive* findDirective(std::string_view name) {
  for (const Directive& directive : kDirectives)
    if (directive.name == name) return &directive;
  return nullptr;
}

std::string unknownDirectiveMessage(std::string_view name) {
  for (const ForeignDirective& foreign : kForeignDirectives)
    if (foreign.name == name) return std::string(foreign.instead);
  std::string known;
  for (const Directive& directive : kDirectives) known += (known.empty() ? "#" : ", #") + std::string(directive.name);
  return "unknown directive '#" + std::string(name) + "' (known: " + known + ")";
}

std::string wordChoices(const Directive& directive) {
  std::vector<std::string> quoted;
  for (std::string_view word : directive.words) quoted.push_back("'" + std::string(word) + "'");
  return choices(quoted);
}

bool isNoteValue(int value) {
  return value >= 1 && value <= kMaxNoteValue && (value & (value - 1)) == 0;
}

std::string noteValueChoices() {
  std::vector<std::string> values;
  for (int value = 1; value <= kMaxNoteValue; value *= 2) values.push_back(std::to_string(value));
  return choices(values);
}

std::string_view directiveKindName(DirectiveKind kind) {
  switch (kind) {
    case DirectiveKind::Define:
      return "constant";
    case DirectiveKind::Number:
      return "number";
    case DirectiveKind::Integer:
      return "integer";
    case DirectiveKind::Flag:
      return "flag";
    case DirectiveKind::Word:
      return "word";
    case DirectiveKind::TimeSignature:
      return "time signature";
    case DirectiveKind::NumberedFile:
      return "integer, file";
    case DirectiveKind::NumberedName:
      return "integer, name";
    case DirectiveKind::Range:
      return "name, range";
  }
  return "?";
}

std::string_view directiveOwnerName(DirectiveOwner owner) {
  switch (owner) {
    case DirectiveOwner::Constants:
      return "constants";
    case DirectiveOwner::World:
      return "world";
    case DirectiveOwner::Geometry:
      return "geometry";
    case DirectiveOwner::Music:
      return "music";
    case DirectiveOwner::Notation:
      return "notation";
  }
  return "?";
}

std::string describeRange(const DirectiveRange& range) {
  if (range.any()) return "finite";
  const bool closed = std::isfinite(range.min) && std::isfinite(range.max) && !range.minOpen && !range.maxOpen;
  if (closed) return formatNumber(range.min) + " to " + formatNumber(range.max);
  std::string text;
  if (std::isfinite(range.min)) text = (range.minOpen ? "> " : "≥ ") + formatNumber(range.min);
  if (std::isfinite(range.max))
    text += (text.empty() ? "" : " and ") + std::string(range.maxOpen ? "< " : "≤ ") + formatNumber(range.max);
  return text;
}

std::string describeValues(const Directive& directive) {
  switch (directive.kind) {
    case DirectiveKind::Define:
      return "any";
    case DirectiveKind::Range:
      return "LOW < HIGH";
    case DirectiveKind::Flag:
      return "-";
    case DirectiveKind::Word:
      return choices(directive.words);
    case DirectiveKind::TimeSignature:
      return "N " + describeRange(directive.range) + ", D 1, 2, 4 ... " + std::to_string(kMaxNoteValue);
    default:
      return describeRange(directive.range);
  }
}

}  // namespace ontogen
