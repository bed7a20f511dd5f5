#pragma once
// The notation cpfg and L-Py share, read into cell-language text: module strings
// (`F(2)+[A]`, modules written without spaces), the expressions in their parameters and
// conditions (C's in cpfg, Python's in L-Py), and productions
// `left < predecessor > right : condition --> successors : probability`. Every position
// is a byte offset into the whole file, so errors name the file, line and column.
// Modules and productions are read in foreign_syntax.cpp, expressions in
// foreign_expression.cpp; the predefined modules are foreign_vocabulary.h's table.

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lang/convert/cpfg_function.h"
#include "lang/convert/lsystem_file.h"
#include "lang/convert/python_operators.h"
#include "lang/source_reader.h"

namespace ontogen::convert {

/// Why a file cannot be converted, at bytes [begin, end) of it.
struct ConvertError {
  uint32_t begin = 0;
  uint32_t end = 0;
  std::string message;
  bool untranslatable = true;  ///< true: a construct ontogen cannot express (code); false: malformed text
};

/// The text the converter writes grew past the limit it is held to (ForeignSyntax's
/// `maxWrittenBytes`): it stops there rather than build the rest.
struct ConvertedTextTooLarge {
  uint64_t limit = 0;  ///< bytes
};

class ForeignSyntax {
 public:
  /// `maxWrittenBytes`: what the converted text may reach (convertFile's limit).
  ForeignSyntax(Dialect dialect, std::string_view text, uint64_t maxWrittenBytes = kDefaultMaxSourceBytes)
      : dialect_(dialect), text_(text), maxWrittenBytes_(maxWrittenBytes) {}

  /// L-Py's `module Name` declarations: names read as one module, not letter by letter.
  std::set<std::string, std::less<>> declaredNames;
  /// L-Py's `module A = F`: A is read as F.
  std::map<std::string, std::string, std::less<>> aliases;
  /// L-Py's helper functions of one expression, `def f(x, y): return EXPR`, and cpfg's
  /// macros with parameters, `#define f(x, y) EXPR`: a call is the expression with its
  /// parameters replaced by the call's arguments.
  struct Function {
    std::vector<std::string> parameters;
    uint32_t begin = 0;  ///< the returned expression, bytes [begin, end) of the file
    uint32_t end = 0;
    /// A macro whose value names constants only: it is written as a #define, and read by
    /// its name where C's replacement reads as its value. Otherwise (`#define L x*2`,
    /// with x a parameter of the productions that use it) every use is the value.
    bool constant = true;
    /// L-Py's function of several lines (ifs, locals, returns), already translated: its
    /// value as a cell-language expression of the parameters, read in place of [begin, end).
    std::optional<std::string> translated;
    /// L-Py's function of several lines the converter cannot translate: the error at its
    /// statement, raised where a production, the axiom or a value calls it (Python runs
    /// no function that nothing calls).
    std::optional<ConvertError> untranslatable;
  };
  std::map<std::string, Function, std::less<>> functions;
  /// cpfg's macros without parameters, `#define X 1+2` (no parameters; the value at
  /// [begin, end)): C replaces the name by the value's text, so where the name stands
  /// among operators (`2*X` is 2*1+2) the value's tokens are put in, not its value.
  std::map<std::string, Function, std::less<>> macros;
  /// cpfg's variables of the blocks around each step (Start:, StartEach:, EndEach:), each
  /// read as a cell-language expression of `time` (the step a production fires at):
  /// a counter `n = n + 1` is its value at that step. `stepEnd`: EndEach: changes it
  /// after each step, so after the last one (where the homomorphism reads it) it is
  /// one step on: `afterStep` is its value there (an EndEach: counter's, of `time`, the
  /// steps made), or empty where the converter cannot write it.
  struct StepVariable {
    std::string value;
    bool stepEnd = false;
    std::string afterStep;
  };
  std::map<std::string, StepVariable, std::less<>> stepVariables;
  /// cpfg's arrays of a `Define:` block, `array c[3] = {1, 3, 2};`: each element a
  /// cell-language expression of constants. `c[i]` reads as a choice among them by the
  /// index made whole, as C's cast does.
  std::map<std::string, std::vector<std::string>, std::less<>> arrays;
  /// L-Py: the objects the editor's INITIALISATION section makes (`path =
  /// pgl.NurbsCurve2D(...)`), by name: their class. A production reading one is refused
  /// at the name.
  std::map<std::string, std::string, std::less<>> editorObjects;
  /// cpfg's functions `func(n, x)` of the view file, in its order (cpfg_function.h).
  std::vector<SampledFunction> splineFunctions;
  /// The section being read is a homomorphism.
  bool inHomomorphism = false;
  /// What L-Py's `getIterationNb()` (the number of the step being derived, from 0) reads
  /// as: `time - 1` in a production, whose `time` is the step it makes (from 1); the hooks
  /// (lpy_hooks.h) set it to `time` for `use group:`, read at the start of the step.
  std::string iterationNumber = "time - 1";
  /// L-Py: where a file shows Python 2 (a print statement, `<>`, `xrange`, ...) and does
  /// not import division from __future__: its `/` floors between integers, which the
  /// converter cannot tell from a quotient, and its round() takes halves away from zero.
  std::optional<uint32_t> python2;
  /// `from __future__ import division`: a Python 2 file whose `/` is Python 3's.
  bool futureDivision = false;
  /// Python's `import random as rd`: rd. is read as random. (and likewise for math).
  std::map<std::string, std::string, std::less<>> moduleAliases;
  /// L-Py: the file's top-level constants whose value is a number, by name (as cellName
  /// spells it): the number and the constants it was computed from (lpy_constants.h).
  struct FileConstant {
    double value = 0;
    std::set<std::string, std::less<>> from;
  };
  std::map<std::string, FileConstant, std::less<>> fileConstants;
  /// L-Py: names the file sets more than once, no constants of one value.
  std::set<std::string, std::less<>> setAgain;
  /// L-Py: the constants fixedNumber() read as their numbers, each at its first use: the
  /// block writes them in place (lpy_constants.h).
  mutable std::map<std::string, SourceRange, std::less<>> fixedConstants;
  /// L-Py: modules whose parameters hold PlantGL vectors, `P(Vector2(0, 1))`, by label
  /// and number of parameters: each parameter's dimension (0: a number). Each vector is
  /// written as its components (foreign_vectors.cpp).
  mutable std::map<std::pair<std::string, size_t>, std::vector<int>> vectorParameters;
  /// L-Py: the vector parameters of the production being read (as cellName spells them),
  /// each with its dimension: `v` is written v_0, v_1, and `v[0]` reads v_0.
  mutable std::map<std::string, int, std::less<>> vectorNames;
  /// L-Py: the globals production bodies set (`global n` and an assignment to n), each
  /// at its first `global` line (lpy_globals.h).
  mutable std::map<std::string, SourceRange, std::less<>> bodyGlobals;
  /// Constructs converted with a loss (a drawing command ontogen's turtle has not), each
  /// label once, at its first place.
  mutable std::vector<ConvertWarning> warnings;

  /// While it lives, `names` are the names in scope that hide the file's globals of the
  /// same name (cpfg's variables, cpfg's arrays, L-Py's lists): a production's parameters,
  /// or an L-Py helper function's parameters, or those and a Python body's locals.
  class Scope {
   public:
    Scope(const ForeignSyntax& syntax, std::set<std::string, std::less<>> names);
    ~Scope() { syntax_.bound_ = std::move(saved_); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    const ForeignSyntax& syntax_;
    std::set<std::string, std::less<>> saved_;
  };

  /// The number of a cell-language expression of written numbers and of the file's
  /// constants (not those a parameter or local of the Scope hides), read at [begin, end)
  /// of the file: the constants it reads are fixed there (lpy_constants.h). nullopt where
  /// it reads anything else.
  std::optional<double> fixedNumber(const std::string& expr, uint32_t begin, uint32_t end) const;
  /// The modules of text [begin, end); `pattern`: a predecessor or context, whose
  /// parameters are names. Throws ConvertError.
  std::vector<ModuleText> modules(uint32_t begin, uint32_t end, bool pattern) const;
  /// An expression of the dialect as a cell-language expression. Throws ConvertError.
  std::string expression(uint32_t begin, uint32_t end) const;
  /// An expression of which only the truth is read (a production's condition, an if's
  /// test): Python's `or` and `and` are the cell language's || and && there.
  std::string condition(uint32_t begin, uint32_t end) const;
  /// The value of `maximum depth: N`: N, or kMaxRewriteDepth (the deepest the cell
  /// language takes) with a warning when N is a number above it; cpfg's files ask for up
  /// to 1000 where their homomorphisms recurse a few levels.
  std::string maximumDepth(uint32_t begin, uint32_t end) const;
  /// The labels of an `ignore:` or `consider:` list.
  std::vector<std::string> symbols(uint32_t begin, uint32_t end) const;
  /// A production of [begin, end), which holds an arrow (`-->` or `->`).
  Statement production(uint32_t begin, uint32_t end) const;

  /// A predecessor the cell language can write: one module of a label, not L-Py's
  /// wildcard `*` or alternatives. Throws ConvertError at [begin, end).
  void checkPredecessor(const ModuleText& predecessor, uint32_t begin, uint32_t end) const;

  /// [begin, end) without the spaces at its ends.
  void trim(uint32_t& begin, uint32_t& end) const;
  /// The first `what` in [begin, end) outside parentheses, or `end`.
  uint32_t find(uint32_t begin, uint32_t end, std::string_view what) const;

  /// Counts `bytes` the converter has written for good: a statement's line of the converted
  /// text, or the value of a local it substitutes. Past `maxWrittenBytes` in all, throws
  /// ConvertedTextTooLarge.
  void written(uint64_t bytes) const;
  /// Throws ConvertedTextTooLarge when a text of `bytes` being built would not fit in what
  /// is left of `maxWrittenBytes`: no expansion grows far past the limit before it stops.
  void fits(uint64_t bytes) const;

  [[noreturn]] void fail(uint32_t begin, uint32_t end, std::string message, bool untranslatable = true) const;

 private:
  uint32_t moduleEnd(uint32_t at, uint32_t end, std::string& label) const;
  void vocabulary(ModuleText& module, uint32_t begin, uint32_t end, bool pattern) const;
  void warnOnce(const std::string& label, uint32_t begin, uint32_t end, std::string message) const;
  /// L-Py's text of a number, the whole parameter [a, b) of a Label: `str(x)`,
  /// `str(round(x, 2))[:5]`, or a call of a helper function of one line returning one:
  /// x as a cell-language expression, with a warning (the word holds the number);
  /// nullopt for any other parameter.
  std::optional<std::string> labelText(const std::string& label, uint32_t a, uint32_t b) const;
  /// 2 or 3 where [a, b) is `Vector2(...)` or `Vector3(...)`.
  std::optional<int> vectorCall(uint32_t a, uint32_t b) const;
  /// The components of the vector parameter [a, b) of `dimension`: a Vector2/3 call's
  /// arguments, or a linear expression of the production's vectors per component.
  std::vector<std::string> vectorComponents(uint32_t a, uint32_t b, int dimension) const;
  /// Throws at [a, b) where the number `value` reads a vector parameter whole.
  void noVectorRead(const std::string& value, uint32_t a, uint32_t b) const;
  /// [x, y) of `str(x)`, `str(x)[...]`, `str(round(x, n))` at [a, b), or nullopt.
  std::optional<std::pair<uint32_t, uint32_t>> textOfNumber(uint32_t a, uint32_t b) const;
  /// One level deeper of conditionals or alternatives; past kMaxNesting an error at
  /// [begin, end), so that no file exhausts the stack.
  struct Nested {
    explicit Nested(const ForeignSyntax& syntax, uint32_t begin, uint32_t end);
    ~Nested() { --depth; }
    Nested(const Nested&) = delete;
    Nested& operator=(const Nested&) = delete;
    int& depth;
  };

  std::optional<std::string> conditional(uint32_t begin, uint32_t end) const;
  /// expression() that gives its tokens unrewritten in `raw` too (nullptr: not wanted).
  std::string expression(uint32_t begin, uint32_t end, std::vector<ExpressionToken>* raw) const;
  /// A macro whose value is one operand wherever its name stands: C's replacement reads
  /// as its value.
  bool plainMacro(const Function& macro, int depth = 0) const;
  /// The character before `at` (after `from`) and from `at` on (before `to`) that is no
  /// space, or '\0'.
  char previous(uint32_t at, uint32_t from) const;
  char following(uint32_t at, uint32_t to) const;
  /// A call to one of cpfg's functions of angles in degrees (sin, cos, tan and their
  /// inverses) as the cell language's, in radians; nullopt for other names.
  std::optional<std::string> degreeCall(const std::string& name, uint32_t at, uint32_t open, uint32_t end,
                                        uint32_t& stop) const;
  /// A call `func(n, x)` of cpfg's functions of the view file, whose name starts at `at`
  /// and whose '(' is at `open`: the value between its samples; in `stop` the offset
  /// after its ')'.
  std::string splineCall(uint32_t at, uint32_t open, uint32_t end, uint32_t& stop) const;
  /// The element `[index]` of a cpfg array whose name starts at `at` and whose '[' is at
  /// `open`; in `stop` the offset after its ']'.
  std::string arrayElement(const std::vector<std::string>& elements, uint32_t at, uint32_t open, uint32_t end,
                           uint32_t& stop) const;
  /// Python's round(x): Python 3 takes halves to the even neighbour.
  std::string pythonRound(uint32_t at, uint32_t open, uint32_t end, uint32_t& stop) const;
  /// The call of a helper function whose name starts at `at` and whose '(' is at `open`,
  /// in the expression [begin, end): its value, and in `stop` the offset after its ')'.
  std::string inlined(const Function& function, uint32_t begin, uint32_t at, uint32_t open, uint32_t end,
                      uint32_t& stop) const;
  /// Counts `bytes` written by inlining a call or a macro at [at, stop); past
  /// kMaxInlinedBytes in all, an error there.
  void countInlined(size_t bytes, uint32_t at, uint32_t stop) const;
  /// Whether [begin, end) is one operand whatever surrounds it: a name, a number, a call
  /// or a parenthesis.
  bool atomic(uint32_t begin, uint32_t end) const;
  std::string substituted(const std::string& expr, const std::vector<std::pair<std::string, std::string>>& locals) const;
  /// Whether the statement of cpfg's file that holds byte `at` is a production with a
  /// parameter `name` in its predecessor or contexts.
  bool bindsParameter(size_t at, std::string_view name) const;
  uint32_t block(uint32_t at, uint32_t end, const Statement& s, uint32_t statementBegin, uint32_t statementEnd,
                 std::vector<std::pair<std::string, std::string>>& locals) const;

  Dialect dialect_;
  std::string_view text_;
  mutable std::set<std::string, std::less<>> warned_;
  mutable int depth_ = 0;
  mutable bool truthNext_ = false;   // the next expression() is a condition()
  mutable size_t inlinedBytes_ = 0;  // written by inlining helper functions and macros
  uint64_t maxWrittenBytes_;
  mutable uint64_t writtenBytes_ = 0;  // counted by written()
  mutable std::set<std::string, std::less<>> bound_;  // the names of the Scope being read
  // L-Py: modules read so far by label and number of parameters (vectorParameters).
  mutable std::set<std::pair<std::string, size_t>> readModules_;
};

/// A name of the other tool's file as the cell language may write it: the names of a
/// cell's internal state (`age`, `time`, `status`, ...), which the cell language reads
/// before a file's own names and refuses as parameters, and of its built-in functions
/// (`step`, `max`, ...), which no #define may take, get a trailing '_'.
std::string cellName(std::string_view name);

/// The parameters a production binds: its predecessor's and contexts' (as cellName
/// spells them).
std::set<std::string, std::less<>> parametersOf(const Statement& production);

/// Whether a production outside the homomorphism (cpfg's decompositions among them) would
/// rewrite the axiom: with `derivation length: 0` it would not run, so the file is refused.
bool rewritesTheAxiom(const LSystemFile& file);

/// Levels of conditionals (`c ? a : b`, `a if c else b`) and of L-Py's `or(...)` the
/// converter reads inside one another. The compiler takes 200 levels of nesting, and each
/// conditional becomes two (a call and its arguments); no model nests a tenth as deep.
inline constexpr int kMaxConvertNesting = 64;
/// Parentheses one expression nests (the compiler takes 200 levels).
inline constexpr int kMaxConvertParentheses = 200;
/// Bytes the calls of helper functions and macros of one file may write in all: calls
/// within calls multiply, and no model writes a thousandth as much.
inline constexpr size_t kMaxInlinedBytes = size_t{4} << 20;


}  // namespace ontogen::convert
