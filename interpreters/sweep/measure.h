#pragma once
// What a sweep or an evolution measures of each run: `--measure NAME=EXPR`, an arithmetic
// expression over the quantities a finished run reports (cell count, count per label,
// drawn length, bounding box, time, and what the physics and creature sets report).
// Measures are parsed once, before any run, so that a misspelt quantity is a usage error
// rather than a column of failures; each run then evaluates them over its quantities.
//
//   Measure height = parseMeasure("h=height / cells");   // throws MeasureError
//   double value = height.evaluate(quantities);           // NaN when not finite
//
// The grammar (docs/SWEEPS.md, "Measures"): numbers, quantity names, + - * / ^ (right
// associative, above unary minus as in the language: -2^2 is -4), parentheses, and the
// functions abs, sqrt, exp, log, min, max and count(LABEL).

#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace ontogen {

/// Which part of a run a quantity comes from: a measure that reads a set's quantity
/// needs that set among the run's sets.
enum class QuantitySource : uint8_t {
  World,     ///< the world at the end: every run has them
  Scene,     ///< the last frame's scene: a set that draws (geometry, creature, physics)
  Geometry,  ///< the geometry set's turtle
  Physics,   ///< the physics set's solve of the last frame
  Creature,  ///< the creature set over every frame (or the dynamics set's simulation of it)
  Dynamics,  ///< the dynamics set's simulation
};

/// One quantity a measure may name.
struct QuantityInfo {
  std::string_view name;
  QuantitySource source;
  std::string_view doc;  ///< one line, with its unit
};

/// Every quantity, in the order docs/SWEEPS.md lists them.
std::span<const QuantityInfo> quantities();
/// "geometry", "physics", "creature"; empty for World, "a set that draws" for Scene.
std::string_view quantitySourceSet(QuantitySource source);

/// The values of one run's quantities by name, and its cells by label.
struct RunQuantities {
  std::map<std::string, double, std::less<>> values;
  std::map<std::string, uint64_t, std::less<>> labels;  ///< cells per label, every pool
};

/// A bad `--measure`: the message names the measure and what is wrong.
struct MeasureError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

class Measure {
 public:
  /// The measure's name (a column of the tables).
  const std::string& name() const { return name_; }
  /// The expression as given.
  const std::string& text() const { return text_; }
  /// The sets whose quantities it reads.
  const std::vector<QuantitySource>& sources() const { return sources_; }
  /// The labels count() asks for.
  const std::vector<std::string>& labels() const { return labels_; }
  /// The value over one run's quantities; NaN when a quantity is missing, and whatever
  /// the arithmetic gives otherwise (an infinity, a NaN): the caller reports it.
  double evaluate(const RunQuantities& quantities) const;

  struct Node;  ///< the parsed expression (measure.cpp)

 private:
  friend Measure parseMeasure(std::string_view, std::span<const std::string>);
  std::string name_, text_;
  std::vector<QuantitySource> sources_;
  std::vector<std::string> labels_;
  std::shared_ptr<const Node> root_;
};

/// Parses `NAME=EXPR`. NAME is a letter or '_' then letters, digits, '_'; EXPR may also
/// name `extra` quantities (a sweep's defines, whose values the caller puts in
/// RunQuantities::values). Throws MeasureError.
Measure parseMeasure(std::string_view text, std::span<const std::string> extra = {});

}  // namespace ontogen
