#pragma once
// The table of directives (`#angle 30`, `#music developmental`, `#timesig 6/8` ...), one
// row per directive: its name, the kind of value it takes, the range that value must be
// in and the message when it is not, the set that owns it, a one-line doc and how its
// value is applied to the compiled program. The parser reads a directive's value by its
// kind and rejects unknown names with the table's list; the compiler checks ranges and
// applies values (lang/compile_directives.cpp); `ontogen help` prints the table; and
// docs/LANGUAGE.md section 3.2 describes the same rows (tests/lang/directives_test.cpp
// holds the four together).

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>

namespace ontogen {

struct InterpretSettings;
struct Program;

/// The shape of what follows a directive's name.
enum class DirectiveKind : uint8_t {
  Define,         ///< `#define NAME expression`: a named constant, kept in its block's scope
  Number,         ///< a constant expression
  Integer,        ///< a constant expression whose value is a whole number
  Flag,           ///< nothing: the name says it all (`#radians`)
  Word,           ///< one word of the directive's list (`#music developmental`)
  TimeSignature,  ///< two whole numbers as musicians write them, `6/8`: not a division
  NumberedFile,   ///< a whole number, then a file path in double quotes (`#surface 1 "bud.obj"`)
  NumberedName,   ///< a whole number, then a name in double quotes (`#track 1 "Bass"`)
  Range,          ///< a #define's name and two numbers, optionally signed (`#range WR 10 100`)
};

/// Whose setting a directive is; the owner also decides where its value holds.
enum class DirectiveOwner : uint8_t {
  Constants,  ///< the constants of the block it is written in
  World,      ///< the run of the whole program (Program): a block's value overrides the top level's
  Geometry,   ///< the geometry set's settings of its block (InterpretSettings); top-level ones start every block's
  Music,      ///< the music set's settings of its block (MusicSettings); likewise
  Notation,   ///< how the parser reads the text after it (`#letters`); the compiler has nothing to apply
};

/// The numbers a directive's value may be: from min to max, either end open or closed.
/// The default is every number, unchecked.
struct DirectiveRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool minOpen = false;  ///< min itself is outside the range
  bool maxOpen = false;  ///< max itself is outside the range

  /// No bounds: any finite value is taken (every directive refuses NaN and infinities).
  bool any() const;
  /// Within the bounds; NaN is within none.
  bool contains(double value) const;
};

/// A directive's value as the program wrote it, checked against its range.
struct DirectiveValue {
  double number = 0;      ///< Number, Integer, NumberedFile, NumberedName: the value
  std::string_view word;  ///< Word: the word written, one of Directive::words
  int numerator = 0;      ///< TimeSignature: beats per bar
  int denominator = 0;    ///< TimeSignature: the note value of a beat
  std::string path;       ///< NumberedFile: the file, resolved against the program file's folder
  std::string location;   ///< NumberedFile: "file:line:col" of the directive, for load errors
  std::string name;       ///< NumberedName: the name as written
};

/// What applying a directive writes into: its block's interpretation settings, or the
/// program's run settings.
struct DirectiveTarget {
  InterpretSettings& settings;
  Program& program;
};

using DirectiveApply = void (*)(const DirectiveValue& value, DirectiveTarget& target);

struct Directive {
  std::string_view name;  ///< without the '#'
  DirectiveKind kind = DirectiveKind::Number;
  DirectiveOwner owner = DirectiveOwner::Geometry;
  /// Number, Integer, NumberedFile: of the value; TimeSignature: of the beats per bar.
  DirectiveRange range = {};
  /// The message for a value outside the range, as in "#dt must be greater than 0";
  /// empty where the range is any number.
  std::string_view rangeError = {};
  std::span<const std::string_view> words = {};  ///< Word: the words it takes, in the order help lists them
  std::string_view syntax = {};                  ///< as docs/LANGUAGE.md writes it: "#tempo BPM"
  std::string_view doc = {};                     ///< one line
  DirectiveApply apply = nullptr;                ///< null for #define and #range, which apply to no setting

  /// Whether `value` may follow the name: finite, in the range, and whole unless the kind
  /// is Number.
  bool accepts(double value) const;
};

/// The longest note value a time signature may name below its '/': 64, a sixty-fourth
/// note (MIDI stores the value as a power of two; shorter beats do not occur in scores).
inline constexpr int kMaxNoteValue = 64;

/// Every directive, in the order messages and `ontogen help` list them.
std::span<const Directive> directives();
/// nullptr when there is no such directive; `name` without the '#'.
const Directive* findDirective(std::string_view name);
/// "unknown directive '#defne' (known: #define, #angle, ..., #surface)"; for the
/// directives of other L-system tools (cpfg's `#ignore`), what ontogen writes instead.
std::string unknownDirectiveMessage(std::string_view name);
/// "'sequential' or 'developmental'": the words of a Word directive.
std::string wordChoices(const Directive& directive);
/// A note value 1, 2, 4 ... kMaxNoteValue (a power of two).
bool isNoteValue(int value);
/// "1, 2, 4, 8, 16, 32 or 64".
std::string noteValueChoices();

/// "constant", "number", "integer", "flag", "word", "time signature", "integer, file",
/// "integer, name", "name, range".
std::string_view directiveKindName(DirectiveKind kind);
/// "constants", "world", "geometry", "music", "notation".
std::string_view directiveOwnerName(DirectiveOwner owner);
/// A range as messages print it: "finite" (any finite number), "1 to 32767", "> 0",
/// "> 0 and ≤ 1000", "≥ 0".
std::string describeRange(const DirectiveRange& range);
/// The values a directive takes, as `ontogen help` prints them: "> 0", "1 to 32767",
/// "sequential or developmental", "N 1 to 255, D 1, 2, 4 ... 64", "finite".
std::string describeValues(const Directive& directive);

}  // namespace ontogen
