#pragma once
// The parser's class (lang/parser.h), private to the files that define its members: the
// tokens, errors and recovery, the top level and directives (lang/parser.cpp), cells and
// their rules (lang/parser_cells.cpp), systems and L-systems (lang/parser_systems.cpp),
// expressions (lang/parser_expressions.cpp).

#include <algorithm>
#include <array>
#include <cctype>
#include <climits>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lang/ast.h"
#include "model/diagnostics.h"
#include "lang/directives.h"
#include "lang/lexer.h"
#include "model/source.h"

namespace ontogen::detail {

using namespace ast;
using ast::Program;  // not ontogen::Program, which lang/directives.h declares

// Thrown to unwind to the enclosing statement after an error was reported (or, while
// speculating, instead of reporting it).
struct SyntaxError {};
// Thrown past every recovery point when the sink's error limit is reached: the rest of
// the file is not read.
struct ErrorLimitReached {};

/// Whether a token of this kind may stand for a symbol ('+', '[', ...) where a name may.
bool isSymbolToken(TokenKind kind);
/// The symbol a token stands for, as written.
std::string symbolSpelling(const Token& token);

// The tokens of a file, which #letters splits in place where the parser stands (one
// token per character of `FF-[-F]`): a gap buffer whose gap follows the parser, so that
// splitting every run of a file costs time linear in its tokens (a vector's insert moved
// every token after the split: 32,000 runs of two letters, 10 s). Tokens 0 .. front_.size()
// - 1 are in front_, the rest in back_, last first. Both are reserved to their most, so
// a token read (before the parser's position, in front_) never moves.
class TokenBuffer {
 public:
  TokenBuffer() = default;
  /// `room`: how many tokens splits may add at most (0: the file has no #letters).
  TokenBuffer(std::vector<Token> tokens, size_t room) : front_(std::move(tokens)) {
    if (room == 0) return;
    front_.reserve(front_.size() + room);
    back_.reserve(front_.size());
  }
  size_t size() const { return front_.size() + back_.size(); }
  const Token& operator[](size_t i) const {
    return i < front_.size() ? front_[i] : back_[back_.size() - 1 - (i - front_.size())];
  }
  /// Keeps tokens 0 .. i in front_ (the parser stands at i).
  void reach(size_t i) {
    while (front_.size() <= i && !back_.empty()) take();
  }
  /// Replaces token `at` by `pieces`.
  void split(size_t at, std::vector<Token>& pieces) {
    while (front_.size() > at) {
      back_.push_back(std::move(front_.back()));
      front_.pop_back();
    }
    while (front_.size() < at) take();
    back_.pop_back();  // token `at`, first of back_ now
    for (Token& piece : pieces) front_.push_back(std::move(piece));
  }

 private:
  void take() {
    front_.push_back(std::move(back_.back()));
    back_.pop_back();
  }
  std::vector<Token> front_;
  std::vector<Token> back_;
};

class Parser {
 public:
  Parser(const SourceFile& file, DiagnosticSink& sink);

  Program run();

 private:
  // ---- token access ----
  const Token& peek(size_t ahead = 0) const {
    size_t index = std::min(pos_ + ahead, tokens_.size() - 1);
    return tokens_[index];
  }
  const Token& previous() const { return tokens_[pos_ == 0 ? 0 : pos_ - 1]; }
  bool check(TokenKind kind) const { return peek().kind == kind; }
  bool checkWord(std::string_view word) const { return check(TokenKind::Identifier) && peek().text == word; }
  const Token& advance() {
    const Token& token = tokens_[pos_];
    if (pos_ + 1 < tokens_.size()) tokens_.reach(++pos_);
    return token;
  }
  bool match(TokenKind kind) {
    if (!check(kind)) return false;
    advance();
    return true;
  }

  [[noreturn]] void fail(const SourceSpan& span, std::string message);
  [[noreturn]] void failHere(std::string expected);
  const Token& expect(TokenKind kind, std::string_view what) {
    if (!check(kind)) failHere(std::string(tokenKindName(kind)) + std::string(what));
    return advance();
  }

  // ---- statement ends ----
  // Cells and systems separate statements with ';'. L-system blocks and directives are
  // line-based: a statement ends where a later line starts at or left of the column the
  // statement started in (so indented lines continue it), or at ';' or '}'.
  struct Statement {
    bool lineBased = false;
    int startColumn = INT_MAX;
    size_t firstToken = 0;  // set by inStatement; the first token never ends its statement
  };

  bool atStatementEnd() const;

  // The next token starts a new line-based statement: its line begins at or left of the
  // column the current statement began in.
  bool atLineEnd() const;

  template <typename F>
  auto inStatement(Statement statement, F&& body) {
    Statement saved = statement_;
    int savedDepth = depth_;
    statement_ = statement;
    statement_.firstToken = pos_;
    depth_ = 0;
    struct Restore {
      Parser* parser;
      Statement statement;
      int depth;
      ~Restore() {
        parser->statement_ = statement;
        parser->depth_ = depth;
      }
    } restore{this, saved, savedDepth};
    return body();
  }

  void endStatement();

  // Whether an arrow comes before the end of the current line-based statement.
  bool arrowInStatement() const;

  // Skips to a point where a new statement can start.
  void synchronize();

  // ---- top level ----
  void topLevel(Program& program);

  Import importStatement();

  void directive(std::vector<Define>& defines, std::vector<Setting>& settings);

  // What follows a directive's name depends on its kind (lang/directives.h).
  void directiveBody(const Token& hash, std::vector<Define>& defines, std::vector<Setting>& settings);

  Define defineStatement(const Token& hash);

  Setting numberSetting(const Token& hash, const Directive& directive);

  // `#range NAME LOW HIGH`: numbers as written, each optionally signed, so that the
  // variation operators (lang/variation.h) read them from the tokens as the parser does.
  Setting rangeSetting(const Token& hash, const Directive& directive);

  Setting wordSetting(const Token& hash, const Directive& directive);

  // Written as musicians write it, 6/8: two whole numbers, not a division.
  Setting timeSignature(const Token& hash, const Directive& directive);

  // `#track 1 "Bass"`: a number, then a name on the same line.
  Setting numberedName(const Token& hash, const Directive& directive);

  // #surface, the one directive of this kind, names its number and file in its messages.
  Setting numberedFile(const Token& hash, const Directive& directive);

  Equiv equiv(Statement statement);

  // ---- cells ----
  Cell cell();

  void cellItem(Cell& cell);

  // `{ instruction ... }` after `interpret SET` (and the symbol, in an L-system).
  Interpretation interpretationBlock(const Token& keyword, const std::string& setName);

  // `interpret SET X(a, b) { ... }` in an L-system.
  void symbolInterpretation(System& system);

  std::vector<Parameter> parameters();

  // Colons at nesting depth 0 before the arrow divide a cell rule into
  // {context} : predicate : body.
  Rule cellRule();

  // A context of 2 or 3 dimensions (paper 002, Fig. 3): parentheses mark dimensions.
  // `(A) (B me C) (D)` is a 2-D context: rows from y - 1 to y + 1, each row's modules
  // from left to right; `((..) (..)) ((..) (B me C)) ((..))` is 3-D, blocks from z - 1.
  // `*` holds a place and matches anything, an empty site too. The row, block ... that
  // holds `me` is aligned on it; the others are centred on it, so they need an odd
  // number of items.
  struct ContextGroup {
    SourceSpan span;
    bool isRow = true;
    std::vector<std::optional<Module>> items;  ///< rows: modules, `me`, or empty for `*`
    std::vector<ContextGroup> groups;          ///< otherwise
    int dimensions() const { return isRow ? 1 : 1 + groups.front().dimensions(); }
    bool holdsMe() const {
      if (isRow)
        return std::any_of(items.begin(), items.end(), [](const auto& item) { return item && item->isMe; });
      return std::any_of(groups.begin(), groups.end(), [](const ContextGroup& g) { return g.holdsMe(); });
    }
  };

  ContextGroup contextGroup();

  // Gives every module of a group its offset along `axis` and the axes below it.
  void placeContext(ContextGroup& group, int axis, std::array<int, 3> base, Rule& rule);

  void gridContext(Rule& rule);

  // A cell's context: modules around exactly one `me`.
  void context(Rule& rule, bool lsystem);

  void ruleBody(Rule& rule);

  Assignment assignment();

  void successors(Rule& rule);

  // ---- modules ----
  enum class ModuleUse { Pattern, Successor, Axiom, Instruction, Predecessor };

  bool canStartModule() const;

  // ---- #letters: ABOP's strings as printed ----
  // `#letters` at the top level holds for the lsystem blocks after it, in a block for the
  // rest of the block. Under it a run of letters and digits where a module stands is one
  // module per character, so `FF-[-F+F+F]` and ABOP's `0 -> 1[0]0` read as printed.
  void notation();

  static size_t codePoints(std::string_view text) {
    size_t count = 0;
    for (unsigned char c : text) count += (c & 0xC0) != 0x80;
    return count;
  }

  // Replaces the token at pos_ by one token per character when it is a run of several
  // (`FF`, `01`), and `&&`, `||` by two symbols. A parameter list stays on the last one,
  // since its '(' touches the last character.
  void splitLetterRun();

  // A number where a module could stand: ABOP's digit labels (`0 -> 1[0]0`).
  void failOnDigitModule();


  // `X`, `X(args)` (the '(' must touch the label), `(X(args), age)` or `me`.
  // A successor may be written `=X` (or `=(X, age)`, `(=X, age)`): it keeps its
  // predecessor's identity.
  Module module(ModuleUse use);

  Module bareModule(ModuleUse use);

  // `(a, b)` after a label: names or value patterns in patterns, expressions elsewhere.
  void patternArguments(Module& result, ModuleUse use);

  // ---- systems ----
  System system();

  void systemItem(System& system);

  // `fill A(e)` and `at(x, y) A(1)`: cells of a grid system.
  void placement(System& system);

  void axiom(System& system);

  void symbolList(System& system);

  // ---- L-systems (paper 000 notation, line-based) ----
  System lsystem();

  void lsystemItem(System& system);

  // `group N:` (L-Py): the rules that follow belong to group N; `group 0:` is the default.
  void group();
  void scaleLine(System& system);

  // `use group: EXPR`: the active group, evaluated at the start of every step.
  void useGroup(System& system);

  // `production:`, `decomposition:`, `homomorphism:` (or `interpretation:`) alone on
  // their line switch the kind of the rules that follow (L-Py's sections).
  bool sectionLine() const;

  void section(System& system);

  // `maximum depth: N` after `decomposition:` or `homomorphism:`.
  void maximumDepth(System& system);

  DevelopmentFunction function();

  // [label ':'] [left '<'] predecessor ['>' right] [':' condition] '->' successors [':' probability]
  Rule production();

  // A module of a context: a pattern, or `*`, which matches any module. In an L-system
  // also `*(x, y)` (any module with that many parameters, binding them), `∅` (nothing:
  // the start of the word, the end of a branch) and `(B C | D)` (alternatives).
  Module contextModule(bool lsystem = true);

  // `(B C | D)`: alternatives; or `(A(x), 3)`, a timed predecessor.
  Module alternativesOrTimed();

  // `<<` and `>>`: two touching '<' or '>'.
  bool atDouble(TokenKind kind) const {
    return check(kind) && peek(1).kind == kind && peek(1).span.begin == peek().span.end;
  }

  std::vector<Module> contextItems();

  // [left '<'] [new-left '<<'] predecessor ['>' right]
  Rule productionAfterLabel(const Token& first);

  // ---- expressions, C precedence; '^' is power and binds tighter than unary minus ----
  // Deeper nesting than this is no program a person writes; it would only exhaust the stack.
  static constexpr int kMaxNesting = 200;

  // One level deeper for as long as it lives; past kMaxNesting an error, so that no
  // input, however deep, recurses further than that.
  struct Nested {
    int& nesting;
    ~Nested() { --nesting; }
  };
  [[nodiscard]] Nested nest(const SourceSpan& at, std::string_view what);

  ExprPtr expression() {
    Nested nested = nest(peek().span, "expression");
    return logicalOr();
  }

  // A chain `a + b + c ...` grows the tree without the parser recursing, so the tree's
  // height has a bound of its own, looser than the nesting: long sums are plausible.
  static constexpr int kMaxHeight = 1000;

  // Sets a node's height from its operands' and checks it.
  ExprPtr measured(ExprPtr node);

  ExprPtr binary(TokenKind op, ExprPtr left, ExprPtr right);

  bool operatorAhead(std::initializer_list<TokenKind> kinds) const;

  ExprPtr logicalOr();
  ExprPtr logicalAnd();
  ExprPtr equality();
  ExprPtr relational();
  ExprPtr additive();
  ExprPtr multiplicative();
  ExprPtr unary();
  ExprPtr power();
  ExprPtr postfix();
  ExprPtr primary();

  DiagnosticSink& sink_;
  TokenBuffer tokens_;
  size_t pos_ = 0;
  Statement statement_;
  int depth_ = 0;        // parentheses open in the current statement
  int speculating_ = 0;  // > 0: errors unwind without being reported
  int nesting_ = 0;      // expressions being parsed inside each other
  RuleKind section_ = RuleKind::Production;  // the L-system section being read
  int group_ = 0;                            // the L-system rule group being read
  int filter_ = -1;                          // the L-system's last ignore:/consider: line
  // #letters (notation()): inside an lsystem block, whether it holds there, and a
  // top-level one that holds in every block after it.
  bool inLSystem_ = false;
  bool letters_ = false;
  bool lettersEverywhere_ = false;
};

}  // namespace ontogen::detail
