#pragma once
// The syntax tree the parser builds. It mirrors the text closely (cells, systems and
// L-system blocks as written); lang/compiler.h checks it and lowers everything,
// L-systems included, into the one cell model of model/program.h.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "model/source.h"
#include "lang/token.h"

namespace ontogen {
struct Directive;  // lang/directives.h
}  // namespace ontogen

namespace ontogen::ast {

struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

struct Expr {
  enum class Kind { Number, Name, Unary, Binary, Call, Member };
  Kind kind = Kind::Number;
  SourceSpan span;
  double number = 0;          ///< Number
  std::string name;           ///< Name, Call (function), Member (field: `parent.x`)
  TokenKind op = TokenKind::EndOfFile;  ///< Unary, Binary
  std::vector<ExprPtr> args;  ///< operands or call arguments; Member: the object
  /// Levels of the tree from this node down (1: a leaf). The parser bounds it, so that
  /// the compiler's recursive walks (and the destructor's) cannot exhaust the stack.
  int height = 1;
};

/// `X`, `X(a, b)`, `(X(a, b), age)` or `me`: a module in an axiom, a successor, a context
/// pattern or an interpretation block.
struct Module {
  SourceSpan span;
  std::string label;  ///< "me" for the current cell
  bool isMe = false;
  bool keepsIdentity = false;  ///< a successor written `=X`: it keeps its predecessor's id
  bool hasArgs = false;       ///< `X()` and `X` differ only here
  std::vector<ExprPtr> args;  ///< patterns: Name expressions (formal parameters)
  ExprPtr age;                ///< birth age (successor) or terminal age (predecessor), may be null
  /// L-system contexts: `(B C | D)`, alternatives each a sequence of patterns (label
  /// "(|)"); empty for any other module. The compiler makes one rule per combination.
  std::vector<std::vector<Module>> alternatives;
};

/// `x = e`, `x += e` ..., `rate(x) = e`.
struct Assignment {
  SourceSpan span;
  std::string target;
  SourceSpan targetSpan;
  TokenKind op = TokenKind::Equal;
  bool isRate = false;
  ExprPtr value;
};

/// What an L-system rule does (L-Py's sections): a production rewrites the developing
/// word; a decomposition rule rewrites a module right after the production step that
/// made it, recursively; a homomorphism (interpretation) rule rewrites only the image
/// the interpretation sets read.
enum class RuleKind { Production, Decomposition, Homomorphism };

/// A rule of a cell or a production of an L-system, in one shape:
/// {left} predecessor {right} : predicate : calculations -> successors : probability.
struct Rule {
  SourceSpan span;
  std::string name;            ///< `p1` in `p1: ...`, may be empty
  bool terminal = false;       ///< fires when the cell reaches its terminal age
  RuleKind kind = RuleKind::Production;  ///< L-systems: the section it stands in
  int group = 0;                         ///< L-systems: the `group N:` it stands in
  int filter = -1;  ///< L-systems: the `ignore:` / `consider:` line above it (System::filters), -1: none
  bool hasContext = false;
  std::vector<Module> left;    ///< nearest last
  Module predecessor;          ///< L-systems: the strict predecessor; cells: `me`
  std::vector<Module> right;   ///< nearest first
  /// L-systems: L-Py's new left context `<<`, matched against what the step has already
  /// produced to the left; nearest last.
  std::vector<Module> newLeft;
  /// L-systems: L-Py's new right context `>>`, matched against what the step has already
  /// produced to the right (the block then derives right to left); nearest first.
  std::vector<Module> newRight;
  SourceSpan newRightSpan;  ///< the `>>`
  /// A 2-D or 3-D context (paper 002, Fig. 3: `(A) (B me C) (D)`): its modules are in
  /// `right`, each at the offset from `me` given here (x, y, z).
  int contextDimensions = 1;
  std::vector<std::array<int, 3>> offsets;
  ExprPtr predicate;           ///< may be null
  std::vector<Assignment> calculations;
  bool hasAction = false;      ///< `->` present
  std::vector<Module> successors;  ///< empty with hasAction: delete
  ExprPtr probability;         ///< stochastic productions, may be null
};

struct Define {
  SourceSpan span;
  std::string name;
  ExprPtr value;
};

/// `equiv f mov`: the user symbol `mov` is interpreted as the command `f`.
struct Equiv {
  SourceSpan span;
  std::string command;
  std::string symbol;
};

/// `#angle 90`, `#radians`, `#timesig 3/4` ...: a directive other than #define, with its
/// value as written; its row of the directive table says what the value is.
struct Setting {
  SourceSpan span;
  const Directive* directive = nullptr;  ///< never null in a parsed program
  ExprPtr value = nullptr;               ///< Number, Integer, NumberedFile, NumberedName: the value's expression
  std::string word = {};                 ///< Word: the word; NumberedFile: the file path; NumberedName: the name
  int numerator = 0;                     ///< TimeSignature N/D
  int denominator = 0;
  double low = 0;                        ///< Range: the lowest and highest value (word: the #define's name)
  double high = 0;
};

struct Parameter {
  SourceSpan span;
  std::string name;
  ExprPtr defaultValue;  ///< may be null
};

struct Interpretation {
  SourceSpan span;
  std::string setName;
  std::vector<Module> instructions;
};

/// `interpret music mov(x) { ... }` in an L-system: how one of its symbols is realised,
/// its parameters named as in the pattern.
struct SymbolInterpretation {
  SourceSpan symbolSpan;
  std::string symbol;
  std::vector<std::string> params;
  Interpretation block;
};

/// `g mov(tau, beta) = 1 - cos(2 * pi * tau / beta)`.
struct DevelopmentFunction {
  SourceSpan span;
  std::string name;
  std::vector<Parameter> params;
  ExprPtr body;
};

struct Cell {
  SourceSpan span;
  SourceSpan nameSpan;
  std::string name;
  std::vector<Parameter> state;
  ExprPtr lifetime;  ///< terminal age, may be null (lives for ever)
  SourceSpan lifetimeSpan;
  std::vector<Rule> rules;
  std::vector<Interpretation> interpretations;
};

/// A symbol list after `ignore:` or `consider:`.
struct SymbolList {
  SourceSpan span;
  std::vector<std::string> symbols;
  bool consider = false;  ///< `consider:`: only these take part; `ignore:`: these do not
};

/// `fill A(e)` or `at(x, y) A(1)` in a grid system.
struct Placement {
  SourceSpan span;
  bool fill = false;
  std::vector<ExprPtr> at;  ///< coordinates of `at`
  Module module;
};

/// L-systems: `scale N: A B`, the scale of the modules labelled A and B (L-Py's
/// `module A, B : scale = N`); a block with such lines matches contexts as a multiscale
/// tree (docs/LANGUAGE.md 4.8).
struct ScaleLine {
  SourceSpan span;
  int scale = 0;
  bool levels = false;  ///< `level N:` (L-Py's multi-level matching)
  std::vector<std::string> symbols;
  std::vector<SourceSpan> symbolSpans;
};

struct System {
  SourceSpan span;
  SourceSpan nameSpan;
  std::string name;
  std::vector<Parameter> state;  ///< `system branch(length = 1)`: a system cell's state
  bool isLSystem = false;
  std::string poolKind = "linear";
  std::vector<ExprPtr> poolArgs;          ///< `grid(64, 64)`: sizes; `spatial(2.5)`: radius
  std::vector<std::string> poolOptions;   ///< `wrap`, `moore`, ...
  SourceSpan poolSpan;
  std::vector<Module> axiom;
  SourceSpan axiomSpan;
  std::vector<Placement> placements;    ///< grid pools
  std::vector<Define> defines;          ///< scoped to the block
  std::vector<Equiv> equivs;            ///< scoped to the block
  std::vector<Setting> settings;        ///< scoped to the block
  std::vector<Rule> productions;        ///< L-systems: every rule, each of its kind
  /// `maximum depth: N` after `decomposition:` and after `homomorphism:`; may be null.
  ExprPtr decompositionDepth;
  ExprPtr homomorphismDepth;
  ExprPtr useGroup;  ///< `use group: EXPR`, may be null (group 0)
  std::vector<SymbolInterpretation> interpretations;  ///< L-systems: `interpret SET X(a) { ... }`
  std::vector<DevelopmentFunction> functions;
  std::vector<SymbolList> ignore;
  std::vector<SymbolList> consider;
  /// L-systems: every `ignore:` and `consider:` line in order; each applies to the
  /// productions after it, up to the next one.
  std::vector<SymbolList> filters;
  std::vector<ScaleLine> scales;  ///< L-systems: `scale N:` lines, in order
};

/// `import "lib.cell";`: a file whose declarations join the program's.
struct Import {
  SourceSpan span;
  std::string path;  ///< as written, relative to the importing file
};

struct Program {
  std::vector<Import> imports;
  std::vector<Define> defines;
  std::vector<Equiv> equivs;
  std::vector<Setting> settings;
  std::vector<DevelopmentFunction> functions;
  std::vector<Cell> cells;
  std::vector<System> systems;
};

}  // namespace ontogen::ast
