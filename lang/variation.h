#pragma once
// The variation operators of interactive evolution and sweeps. A variant of a program is
// its main file's text with some of its numbers changed; each number that may change is
// a gene, and a genome holds one value per gene. The operators never touch the rest of
// the text, so a variant is as readable as its parent and diffs against it number by
// number.
//
// Genes are found in the text, not in the compiled program: a `#define NAME NUMBER`
// (the lexer's Directive token, a name and a number, optionally signed, alone up to the
// end of the statement) and, when asked for, the numeric literals of expressions. A
// define whose value is an expression (`#define B A / 2`) is no gene: its value follows
// the genes it names. Directive settings (#seed, #until, #dt, #angle ...) are how a
// program is run, not what it is, and are never genes. Literals are those the parser
// reads as number expressions, so digit modules under #letters and `group 1:` stay out,
// and so do the numbers of patterns, `A(3) -> ...` and a predecessor's terminal age
// `(A, 3)`: they choose what matches, not how much (and a symbol has one terminal age).
//
// Ranges: a gene of value v > 0 lives in [0, 2v], of v < 0 in [2v, 0], of 0 in [-1, 1]:
// a mutation may halve or double a value but never flips its sign, which would change
// what the number means (a length, a rate) rather than how big it is. An integer gene
// with v >= 1 has low 1, so counts such as SEGMENTS stay at least one. A program may
// declare a define's range itself, `#range NAME LOW HIGH` (in the define's block), and a
// caller may give one (VariationOptions::ranges, which win); an integer gene's declared
// range is narrowed to the whole numbers inside it.
//
// Randomness comes from RandomStream keyed by mixKey of the seed and the parents' values
// (model/random.h), so a variant depends on nothing but its inputs, on every platform.

#include <cstdint>
#include <string>
#include <vector>

#include "lang/compiler.h"

namespace ontogen {

/// The shortest text that reads back as the same double, as a variant writes its numbers:
/// integral values below 2^53 in fixed notation (1000000, not 1e+06), -0 as "0".
std::string shortestNumber(double value);

/// One number of a program text that a variant may change.
struct Gene {
  enum class Kind { Define, Constant };
  Kind kind = Kind::Define;
  std::string name;     ///< the define's name; for a constant, "line:column" of it
  uint32_t offset = 0;  ///< byte range of the number's text in the main file (a sign included)
  uint32_t length = 0;
  uint32_t line = 0;    ///< 1-based, of the number's first byte
  uint32_t column = 0;  ///< 1-based, in bytes
  double value = 0;     ///< as written
  double low = 0;       ///< the range a mutation keeps it in (see above)
  double high = 0;
  bool integer = false;  ///< written without fraction or exponent: stays an integer
};

/// A value per gene, in the order of VariationSpace::genes().
struct Genome {
  std::vector<double> values;
  friend bool operator==(const Genome&, const Genome&) = default;
};

/// A range given from outside for the genes named `name` (a define's name, or a
/// constant's "line:column").
struct GeneRange {
  std::string name;
  double low = 0;
  double high = 0;
};

struct VariationOptions {
  bool constants = false;  ///< also vary the numeric literals of rules and expressions
  std::vector<GeneRange> ranges = {};   ///< override the defaults and the program's #range; low < high, finite
  std::vector<std::string> fixed = {};  ///< define names that are no genes (held at a value from outside)
  double rate = 0.3;       ///< chance that mutate changes a gene, in [0, 1] (at least one always changes)
  double strength = 0.15;  ///< a mutation's standard deviation as a fraction of high - low; > 0
};

/// The genes of one program text and the operators on its genomes. Every operator that
/// takes a genome throws std::invalid_argument when it has the wrong size or a value
/// that is not finite.
class VariationSpace {
 public:
  /// Finds the genes of a program's main text, in text order. Throws
  /// std::invalid_argument when the text does not lex (with options.constants: does not
  /// parse), naming line:column and the error, when the options are out of range, or
  /// when a range (given or declared) names no gene or holds no whole number for an
  /// integer gene.
  explicit VariationSpace(std::string text, VariationOptions options = {});

  const std::vector<Gene>& genes() const { return genes_; }
  const std::string& text() const { return text_; }
  const VariationOptions& options() const { return options_; }
  /// The values as written.
  Genome original() const;

  /// A mutated copy of parent, deterministic in (parent, seed). Each gene changes with
  /// probability rate (if none did, one chosen gene changes) to value +
  /// strength * (high - low) * N(0, 1), clamped to [low, high], rounded for integer genes,
  /// and different from before (every range holds more than one value). With no genes,
  /// parent itself.
  Genome mutate(const Genome& parent, uint64_t seed) const;
  /// Uniform crossover: each gene from a or b with even odds, deterministic in (a, b, seed).
  Genome crossover(const Genome& a, const Genome& b, uint64_t seed) const;

  /// The text with genome's values written in place of the genes' numbers; the rest of
  /// the text is byte for byte the original. A value equal to the gene's keeps its
  /// spelling; another is written as the shortest text that reads back as the same double
  /// (integers without a point), a negative constant in parentheses so that `2^2` becomes
  /// `(-2)^2`, not `-2^2`.
  std::string programText(const Genome& genome) const;
  /// The define genes as CompileOptions::defines overrides, in gene order. A name defined
  /// in several blocks is a gene per #define, while an override sets every #define of its
  /// name: the compiler takes the last one's value for all of them.
  std::vector<DefineOverride> defines(const Genome& genome) const;

 private:
  void check(const Genome& genome) const;

  std::string text_;
  VariationOptions options_;
  std::vector<Gene> genes_;
};

}  // namespace ontogen
