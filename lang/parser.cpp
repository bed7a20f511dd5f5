#include "lang/parser.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <climits>
#include <cmath>
#include <functional>
#include <optional>

#include "lang/directives.h"
#include "lang/lexer.h"

namespace ontogen {
namespace {

using namespace ast;
using ast::Program;  // not ontogen::Program, which lang/directives.h declares

// Thrown to unwind to the enclosing statement after an error was reported (or, while
// speculating, instead of reporting it).
struct SyntaxError {};
// Thrown past every recovery point when the sink's error limit is reached: the rest of
// the file is not read.
struct ErrorLimitReached {};

bool isSymbolToken(TokenKind kind) {
  switch (kind) {
    case TokenKind::Plus: case TokenKind::Minus: case TokenKind::Caret: case TokenKind::Amp:
    case TokenKind::Slash: case TokenKind::Backslash: case TokenKind::Pipe: case TokenKind::Bang:
    case TokenKind::Less: case TokenKind::Greater: case TokenKind::LBracket: case TokenKind::RBracket:
    case TokenKind::Dollar: case TokenKind::Tilde: case TokenKind::At: case TokenKind::Percent:
      return true;
    default:
      return false;
  }
}

std::string symbolSpelling(const Token& token) {
  if (token.kind == TokenKind::Identifier) return token.text;
  std::string_view name = tokenKindName(token.kind);  // "'+'"
  return std::string(name.substr(1, name.size() - 2));
}

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
  Parser(const SourceFile& file, DiagnosticSink& sink) : sink_(sink) {
    // #letters splits tokens in place (splitLetterRun); with room for every character
    // the buffer never reallocates, so references to tokens already read stay valid.
    std::vector<Token> tokens = lex(file, sink);
    const size_t room = file.text().find("#letters") != std::string::npos ? file.text().size() : 0;
    tokens_ = TokenBuffer(std::move(tokens), room);
  }

  Program run() {
    Program program;
    try {
      while (!check(TokenKind::EndOfFile)) {
        size_t before = pos_;
        try {
          topLevel(program);
        } catch (const SyntaxError&) {
          synchronize();
        }
        if (pos_ == before) advance();  // never loop on a token nobody consumes
      }
    } catch (const ErrorLimitReached&) {
    }
    return program;
  }

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

  [[noreturn]] void fail(const SourceSpan& span, std::string message) {
    if (speculating_ == 0) {
      // An Error token was already reported by the lexer: stay silent on it.
      if (peek().kind != TokenKind::Error) sink_.error(span, std::move(message));
      if (sink_.limitReached()) throw ErrorLimitReached{};
    }
    throw SyntaxError{};
  }
  [[noreturn]] void failHere(std::string expected) {
    const Token& token = peek();
    // A line-based statement that stops short is reported where its line ends, not on
    // the line after it, which is another statement.
    if (atLineEnd()) {
      const SourceSpan& last = previous().span;
      fail(SourceSpan{last.file, last.end, last.end}, "expected " + expected + ", found the end of the line");
    }
    std::string found = token.kind == TokenKind::Identifier ? "'" + token.text + "'"
                        : token.kind == TokenKind::Number   ? "number '" + token.text + "'"
                                                            : std::string(tokenKindName(token.kind));
    fail(token.span, "expected " + expected + ", found " + found);
  }
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

  bool atStatementEnd() const {
    const Token& token = peek();
    if (token.kind == TokenKind::Semicolon || token.kind == TokenKind::RBrace || token.kind == TokenKind::EndOfFile)
      return true;
    return atLineEnd();
  }

  // The next token starts a new line-based statement: its line begins at or left of the
  // column the current statement began in.
  bool atLineEnd() const {
    if (!statement_.lineBased || depth_ > 0 || pos_ <= statement_.firstToken) return false;
    const Token& token = peek();
    if (token.kind == TokenKind::RBrace || token.kind == TokenKind::EndOfFile) return false;
    return token.line > previous().line && token.column <= statement_.startColumn;
  }

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

  void endStatement() {
    if (match(TokenKind::Semicolon)) return;
    if (check(TokenKind::RBrace) || check(TokenKind::EndOfFile)) return;
    if (statement_.lineBased && atStatementEnd()) return;
    failHere("';' or the end of the statement");
  }

  // Whether an arrow comes before the end of the current line-based statement.
  bool arrowInStatement() const {
    int parens = 0;
    for (size_t i = pos_; i < tokens_.size(); ++i) {
      const Token& token = tokens_[i];
      if (token.kind == TokenKind::Semicolon || token.kind == TokenKind::RBrace || token.kind == TokenKind::EndOfFile)
        return false;
      if (i > pos_ && parens == 0 && token.line > tokens_[i - 1].line && token.column <= statement_.startColumn)
        return false;
      if (token.kind == TokenKind::LParen) ++parens;
      if (token.kind == TokenKind::RParen && parens > 0) --parens;
      if (token.kind == TokenKind::Arrow && parens == 0) return true;
    }
    return false;
  }

  // Skips to a point where a new statement can start.
  void synchronize() {
    int braces = 0;
    int line = peek().line;
    while (!check(TokenKind::EndOfFile)) {
      const Token& token = peek();
      if (statement_.lineBased && braces == 0 && token.line > line && token.column <= statement_.startColumn) return;
      if (token.kind == TokenKind::Semicolon && braces == 0) {
        advance();
        return;
      }
      if (token.kind == TokenKind::LBrace) ++braces;
      if (token.kind == TokenKind::RBrace) {
        if (braces == 0) return;
        --braces;
        if (braces == 0 && !statement_.lineBased) {
          advance();
          return;
        }
      }
      line = token.line;
      advance();
    }
  }

  // ---- top level ----
  void topLevel(Program& program) {
    Statement top{};
    statement_ = top;
    depth_ = 0;  // an error inside parentheses leaves them counted
    if (check(TokenKind::Directive)) return directive(program.defines, program.settings);
    if (checkWord("equiv")) return program.equivs.push_back(equiv(Statement{true, peek().column}));
    if (checkWord("import")) return program.imports.push_back(importStatement());
    if (checkWord("cell")) return program.cells.push_back(cell());
    if (checkWord("system")) return program.systems.push_back(system());
    if (checkWord("lsystem")) return program.systems.push_back(lsystem());
    if ((checkWord("g") || checkWord("develop")) && peek(1).kind == TokenKind::Identifier)
      return program.functions.push_back(inStatement(Statement{true, peek().column}, [&] { return function(); }));
    failHere("'cell', 'system', 'lsystem', 'equiv', 'import', 'g' or a directive such as '#define'");
  }

  Import importStatement() {
    const Token& keyword = advance();
    const Token& path = expect(TokenKind::String, " (the file to import, in double quotes: import \"lib.cell\";)");
    Import result{keyword.span.to(path.span), path.text};
    match(TokenKind::Semicolon);
    return result;
  }

  void directive(std::vector<Define>& defines, std::vector<Setting>& settings) {
    const Token& hash = advance();
    try {
      directiveBody(hash, defines, settings);
    } catch (const SyntaxError&) {
      // A directive is one line: recover at the next one.
      while (!check(TokenKind::EndOfFile) && peek().line == hash.line) advance();
    }
  }

  // What follows a directive's name depends on its kind (lang/directives.h).
  void directiveBody(const Token& hash, std::vector<Define>& defines, std::vector<Setting>& settings) {
    inStatement(Statement{true, INT_MAX}, [&] {
      statement_.firstToken = pos_ - 1;  // the statement began at the '#name' already read
      const Directive* directive = findDirective(hash.text);
      if (!directive) fail(hash.span, unknownDirectiveMessage(hash.text));
      if (directive->owner == DirectiveOwner::Notation) notation();
      switch (directive->kind) {
        case DirectiveKind::Define: defines.push_back(defineStatement(hash)); break;
        case DirectiveKind::Number:
        case DirectiveKind::Integer: settings.push_back(numberSetting(hash, *directive)); break;
        case DirectiveKind::Flag: settings.push_back(Setting{hash.span, directive}); break;
        case DirectiveKind::Word: settings.push_back(wordSetting(hash, *directive)); break;
        case DirectiveKind::TimeSignature: settings.push_back(timeSignature(hash, *directive)); break;
        case DirectiveKind::NumberedFile: settings.push_back(numberedFile(hash, *directive)); break;
        case DirectiveKind::NumberedName: settings.push_back(numberedName(hash, *directive)); break;
        case DirectiveKind::Range: settings.push_back(rangeSetting(hash, *directive)); break;
      }
      if (match(TokenKind::Semicolon)) return;
      if (!atStatementEnd()) failHere("the end of the line after the directive");
    });
  }

  Define defineStatement(const Token& hash) {
    Define define;
    const Token& name = peek();
    if (name.kind != TokenKind::Identifier) failHere("a name after #define");
    advance();
    define.name = name.text;
    if (atStatementEnd()) fail(name.span, "expected a value after '#define " + name.text + "'");
    define.value = expression();
    define.span = hash.span.to(previous().span);
    return define;
  }

  Setting numberSetting(const Token& hash, const Directive& directive) {
    Setting setting{hash.span, &directive};
    if (atStatementEnd()) fail(hash.span, "expected a value after '#" + hash.text + "'");
    setting.value = expression();
    setting.span = hash.span.to(previous().span);
    return setting;
  }

  // `#range NAME LOW HIGH`: numbers as written, each optionally signed, so that the
  // variation operators (lang/variation.h) read them from the tokens as the parser does.
  Setting rangeSetting(const Token& hash, const Directive& directive) {
    const Token& name = peek();
    if (name.kind != TokenKind::Identifier) failHere("the name of a #define after #" + hash.text);
    advance();
    Setting setting{hash.span, &directive, nullptr, name.text};
    auto bound = [&](const char* which) {
      const bool negative = match(TokenKind::Minus);
      if (!check(TokenKind::Number) || peek().line != hash.line)
        failHere(std::string("the ") + which + " value of " + name.text + " after '#" + hash.text + " " + name.text +
                 "', a number as in #range " + name.text + " 1 10");
      const double value = advance().number;
      return negative ? -value : value;
    };
    setting.low = bound("lowest");
    setting.high = bound("highest");
    setting.span = hash.span.to(previous().span);
    return setting;
  }

  Setting wordSetting(const Token& hash, const Directive& directive) {
    const Token& word = peek();
    if (word.kind != TokenKind::Identifier ||
        std::find(directive.words.begin(), directive.words.end(), word.text) == directive.words.end())
      failHere(wordChoices(directive) + " after #" + hash.text);
    advance();
    return Setting{hash.span.to(word.span), &directive, nullptr, word.text};
  }

  // Written as musicians write it, 6/8: two whole numbers, not a division.
  Setting timeSignature(const Token& hash, const Directive& directive) {
    const Token& top = peek();
    if (top.kind != TokenKind::Number || !directive.accepts(top.number))
      failHere("a time signature such as 3/4 after #" + hash.text + " (beats per bar " +
               describeRange(directive.range) + ")");
    advance();
    if (!match(TokenKind::Slash)) failHere("'/' in the time signature, as in #" + hash.text + " 3/4");
    const Token& bottom = peek();
    // Bounded before the conversion: 3/1e999 is infinite, which no int holds.
    int d = bottom.kind == TokenKind::Number && bottom.number == std::floor(bottom.number) && bottom.number >= 1 &&
                    bottom.number <= 1024
                ? static_cast<int>(bottom.number)
                : 0;
    if (!isNoteValue(d)) failHere("a note value " + noteValueChoices() + " below the '/' of #" + hash.text);
    advance();
    return Setting{hash.span.to(bottom.span), &directive, nullptr, "", static_cast<int>(top.number), d};
  }

  // `#track 1 "Bass"`: a number, then a name on the same line.
  Setting numberedName(const Token& hash, const Directive& directive) {
    Setting setting{hash.span, &directive};
    const std::string example = "as in " + std::string(directive.syntax);
    if (atStatementEnd()) fail(hash.span, "expected a number and a name after '#" + hash.text + "', " + example);
    setting.value = expression();
    if (!check(TokenKind::String) || peek().line != hash.line)
      fail(hash.span.to(previous().span), "expected the name in double quotes after the number, " + example);
    const Token& name = advance();
    setting.word = name.text;
    setting.span = hash.span.to(name.span);
    return setting;
  }

  // #surface, the one directive of this kind, names its number and file in its messages.
  Setting numberedFile(const Token& hash, const Directive& directive) {
    Setting setting{hash.span, &directive};
    if (atStatementEnd())
      fail(hash.span, "expected a surface number and an OBJ file after '#" + hash.text +
                          "', as in #surface 1 \"bud.obj\"");
    setting.value = expression();
    if (!check(TokenKind::String) || peek().line != hash.line)
      fail(hash.span.to(previous().span),
           "expected the OBJ file in double quotes after the surface number, as in #surface 1 \"bud.obj\"");
    const Token& path = advance();
    setting.word = path.text;
    setting.span = hash.span.to(path.span);
    return setting;
  }

  Equiv equiv(Statement statement) {
    return inStatement(statement, [&] {
      Equiv result;
      const Token& keyword = advance();
      const Token& command = peek();
      if (command.kind != TokenKind::Identifier && !isSymbolToken(command.kind))
        failHere("a command after 'equiv' (as in 'equiv f mov')");
      advance();
      const Token& symbol = peek();
      if (symbol.kind != TokenKind::Identifier && !isSymbolToken(symbol.kind))
        failHere("the symbol that stands for '" + symbolSpelling(command) + "' (as in 'equiv f mov')");
      advance();
      result.command = symbolSpelling(command);
      result.symbol = symbolSpelling(symbol);
      result.span = keyword.span.to(symbol.span);
      endStatement();
      return result;
    });
  }

  // ---- cells ----
  Cell cell() {
    Cell result;
    const Token& keyword = advance();
    const Token& name = expect(TokenKind::Identifier, " (the cell's label)");
    result.name = name.text;
    result.nameSpan = name.span;
    if (check(TokenKind::LParen)) result.state = parameters();
    expect(TokenKind::LBrace, " to open the cell's body");
    while (!check(TokenKind::RBrace) && !check(TokenKind::EndOfFile)) {
      size_t before = pos_;
      try {
        cellItem(result);
      } catch (const SyntaxError&) {
        synchronize();
      }
      if (pos_ == before) advance();
    }
    const Token& close = expect(TokenKind::RBrace, " to close the cell");
    result.span = keyword.span.to(close.span);
    return result;
  }

  void cellItem(Cell& cell) {
    statement_ = Statement{};
    depth_ = 0;
    if (checkWord("rules")) {
      advance();
      expect(TokenKind::LBrace, " after 'rules'");
      while (!check(TokenKind::RBrace) && !check(TokenKind::EndOfFile)) {
        size_t before = pos_;
        try {
          depth_ = 0;
          cell.rules.push_back(cellRule());
        } catch (const SyntaxError&) {
          synchronize();
        }
        if (pos_ == before) advance();
      }
      expect(TokenKind::RBrace, " to close 'rules'");
      return;
    }
    if (checkWord("interpret")) {
      const Token& keyword = advance();
      const Token& name = expect(TokenKind::Identifier, " (the interpretation set, e.g. 'geometry')");
      cell.interpretations.push_back(interpretationBlock(keyword, name.text));
      return;
    }
    if (checkWord("lifetime")) {
      const Token& keyword = advance();
      cell.lifetime = expression();
      cell.lifetimeSpan = keyword.span.to(previous().span);
      endStatement();
      return;
    }
    failHere("'rules', 'interpret', 'lifetime' or '}' in the cell");
  }

  // `{ instruction ... }` after `interpret SET` (and the symbol, in an L-system).
  Interpretation interpretationBlock(const Token& keyword, const std::string& setName) {
    {
      Interpretation interpretation;
      interpretation.setName = setName;
      expect(TokenKind::LBrace, " to open the interpretation block");
      try {
        while (!check(TokenKind::RBrace) && !check(TokenKind::EndOfFile)) {
          if (match(TokenKind::Semicolon)) continue;
          if (!canStartModule()) failHere("an instruction such as 'F(1)' or '}'");
          interpretation.instructions.push_back(module(ModuleUse::Instruction));
        }
      } catch (const SyntaxError&) {
        // Skip to the block's own '}' so that the cell goes on.
        int parens = 0;
        while (!check(TokenKind::EndOfFile) && !(parens == 0 && check(TokenKind::RBrace))) {
          if (check(TokenKind::LParen)) ++parens;
          if (check(TokenKind::RParen) && parens > 0) --parens;
          if (check(TokenKind::LBrace)) break;
          advance();
        }
      }
      const Token& close = expect(TokenKind::RBrace, " to close the interpretation block");
      interpretation.span = keyword.span.to(close.span);
      return interpretation;
    }
  }

  // `interpret SET X(a, b) { ... }` in an L-system.
  void symbolInterpretation(System& system) {
    SymbolInterpretation result;
    const Token& keyword = advance();
    const Token& set = expect(TokenKind::Identifier, " (the interpretation set, e.g. 'music')");
    const Token& symbol = peek();
    if (symbol.kind != TokenKind::Identifier && !isSymbolToken(symbol.kind))
      failHere("the symbol to interpret after 'interpret " + set.text + "', as in 'interpret music F { note }'");
    advance();
    result.symbol = symbolSpelling(symbol);
    result.symbolSpan = symbol.span;
    if (check(TokenKind::LParen))
      for (const auto& param : parameters()) {
        if (param.defaultValue) fail(param.span, "the parameters of an interpreted symbol take no default values");
        result.params.push_back(param.name);
      }
    result.block = interpretationBlock(keyword, set.text);
    system.interpretations.push_back(std::move(result));
    endStatement();
  }

  std::vector<Parameter> parameters() {
    std::vector<Parameter> result;
    expect(TokenKind::LParen, "");
    ++depth_;
    if (!check(TokenKind::RParen)) {
      do {
        Parameter parameter;
        const Token& name = expect(TokenKind::Identifier, " (a parameter name)");
        parameter.name = name.text;
        parameter.span = name.span;
        if (match(TokenKind::Equal)) {
          parameter.defaultValue = expression();
          parameter.span = name.span.to(previous().span);
        }
        result.push_back(std::move(parameter));
      } while (match(TokenKind::Comma));
    }
    --depth_;
    expect(TokenKind::RParen, " to close the parameter list");
    return result;
  }

  // Colons at nesting depth 0 before the arrow divide a cell rule into
  // {context} : predicate : body.
  Rule cellRule() {
    Rule rule;
    const Token& first = peek();
    if (checkWord("terminal") && peek(1).kind == TokenKind::Colon) {
      advance();
      advance();
      rule.terminal = true;
    }
    int colons = 0;
    bool contextFirst = false;
    {
      int depth = 0;
      bool seenColon = false;
      for (size_t i = pos_; i < tokens_.size(); ++i) {
        const Token& token = tokens_[i];
        if (token.kind == TokenKind::LParen) ++depth;
        if (token.kind == TokenKind::RParen) --depth;
        if (depth > 0) continue;
        if (token.kind == TokenKind::Semicolon || token.kind == TokenKind::RBrace ||
            token.kind == TokenKind::EndOfFile || token.kind == TokenKind::Arrow)
          break;
        if (token.kind == TokenKind::Colon) {
          ++colons;
          seenColon = true;
        }
        if (!seenColon && token.kind == TokenKind::Identifier && token.text == "me") contextFirst = true;
      }
      // A context of several dimensions opens with '(' and holds 'me' inside parentheses.
      if (check(TokenKind::LParen))
        for (size_t i = pos_; i < tokens_.size(); ++i) {
          const Token& token = tokens_[i];
          if (token.kind == TokenKind::Colon || token.kind == TokenKind::Semicolon || token.kind == TokenKind::Arrow ||
              token.kind == TokenKind::RBrace || token.kind == TokenKind::EndOfFile)
            break;
          if (token.kind == TokenKind::Identifier && token.text == "me") contextFirst = true;
        }
    }
    if (colons > 2)
      fail(peek().span, "a rule has at most three parts ({context} : predicate : body), found " +
                            std::to_string(colons + 1));
    if (colons >= 1 && (contextFirst || colons == 2)) {
      context(rule, /*lsystem=*/false);
      expect(TokenKind::Colon, " after the context");
      --colons;
    }
    if (colons == 1) {
      rule.predicate = expression();
      expect(TokenKind::Colon, " after the predicate");
    }
    ruleBody(rule);
    rule.span = first.span.to(previous().span);
    endStatement();
    return rule;
  }

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

  ContextGroup contextGroup() {
    ContextGroup group;
    Nested nested = nest(peek().span, "context");
    const Token& open = expect(TokenKind::LParen, "");
    ++depth_;
    if (check(TokenKind::LParen)) {
      group.isRow = false;
      while (check(TokenKind::LParen)) group.groups.push_back(contextGroup());
      for (const ContextGroup& inner : group.groups)
        if (inner.dimensions() != group.groups.front().dimensions())
          fail(inner.span, "the parts of a context have the same number of dimensions (parentheses)");
    } else {
      while (!check(TokenKind::RParen) && !atStatementEnd()) {
        if (match(TokenKind::Star)) {
          group.items.emplace_back();
          continue;
        }
        if (!canStartModule()) failHere("a module, 'me' or '*' in the context row");
        group.items.emplace_back(module(ModuleUse::Pattern));
      }
    }
    --depth_;
    const Token& close = expect(TokenKind::RParen, " to close the context's parenthesis");
    group.span = open.span.to(close.span);
    return group;
  }

  // Gives every module of a group its offset along `axis` and the axes below it.
  void placeContext(ContextGroup& group, int axis, std::array<int, 3> base, Rule& rule) {
    const size_t n = group.isRow ? group.items.size() : group.groups.size();
    int first = 0;
    if (group.holdsMe()) {
      for (size_t k = 0; k < n; ++k)
        if (group.isRow ? (group.items[k] && group.items[k]->isMe) : group.groups[k].holdsMe()) first = -static_cast<int>(k);
    } else {
      if (n % 2 == 0)
        fail(group.span, "a part of the context without 'me' is centred on it, so it needs an odd number of " +
                             std::string(group.isRow ? "items" : "parts") + " (use '*' to hold a place)");
      first = -static_cast<int>(n / 2);
    }
    for (size_t k = 0; k < n; ++k) {
      std::array<int, 3> at = base;
      at[axis] += first + static_cast<int>(k);
      if (!group.isRow) {
        placeContext(group.groups[k], axis - 1, at, rule);
        continue;
      }
      if (!group.items[k]) continue;  // `*`
      if (group.items[k]->isMe) {
        if (at != std::array<int, 3>{0, 0, 0}) fail(group.items[k]->span, "'me' appears twice in the context");
        rule.predecessor = std::move(*group.items[k]);
        continue;
      }
      rule.right.push_back(std::move(*group.items[k]));
      rule.offsets.push_back(at);
    }
  }

  void gridContext(Rule& rule) {
    ContextGroup top;
    top.isRow = false;
    const Token& start = peek();
    while (check(TokenKind::LParen)) top.groups.push_back(contextGroup());
    top.span = start.span.to(previous().span);
    for (const ContextGroup& inner : top.groups)
      if (inner.dimensions() != top.groups.front().dimensions())
        fail(inner.span, "the parts of a context have the same number of dimensions (parentheses)");
    rule.contextDimensions = top.dimensions();
    if (rule.contextDimensions > 3) fail(top.span, "a context has at most 3 dimensions");
    int mes = 0;
    std::function<void(const ContextGroup&)> countMe = [&](const ContextGroup& g) {
      for (const auto& item : g.items) mes += item && item->isMe;
      for (const auto& inner : g.groups) countMe(inner);
    };
    countMe(top);
    if (mes != 1)
      fail(top.span, mes == 0 ? "a context names the current cell with 'me', as in '(A) (B me C) (D)'"
                              : "'me' appears twice in the context");
    placeContext(top, rule.contextDimensions - 1, {0, 0, 0}, rule);
  }

  // A cell's context: modules around exactly one `me`.
  void context(Rule& rule, bool lsystem) {
    (void)lsystem;
    rule.hasContext = true;
    if (check(TokenKind::LParen)) return gridContext(rule);
    bool seenMe = false;
    while (canStartModule() || check(TokenKind::Star)) {
      Module item = check(TokenKind::Star) ? contextModule(/*lsystem=*/false) : module(ModuleUse::Pattern);
      if (item.isMe) {
        if (seenMe) fail(item.span, "'me' appears twice in the context");
        seenMe = true;
        rule.predecessor = std::move(item);
      } else if (seenMe) {
        rule.right.push_back(std::move(item));
      } else {
        rule.left.push_back(std::move(item));
      }
    }
    if (!seenMe) fail(peek().span, "a context names the current cell with 'me', as in 'A(y) me B(z)'");
  }

  void ruleBody(Rule& rule) {
    while (!check(TokenKind::Arrow) && !atStatementEnd() && !check(TokenKind::Colon)) {
      rule.calculations.push_back(assignment());
      if (!match(TokenKind::Comma)) break;
    }
    if (match(TokenKind::Arrow)) {
      rule.hasAction = true;
      successors(rule);
    }
  }

  Assignment assignment() {
    Assignment result;
    const Token& first = peek();
    if (checkWord("rate") && peek(1).kind == TokenKind::LParen) {
      advance();
      advance();
      const Token& target = expect(TokenKind::Identifier, " (the state variable of 'rate')");
      expect(TokenKind::RParen, " after the variable of 'rate'");
      result.isRate = true;
      result.target = target.text;
      result.targetSpan = target.span;
    } else {
      if (!check(TokenKind::Identifier)) failHere("a state calculation such as 'x = x + 1' or '->'");
      const Token& target = advance();
      result.target = target.text;
      result.targetSpan = target.span;
      if (check(TokenKind::Dot) && (target.text == "parent" || target.text == "root" || target.text == "me")) {
        std::string path = target.text;
        SourceSpan span = target.span;
        while (match(TokenKind::Dot) && check(TokenKind::Identifier)) {
          path += "." + peek().text;
          span = span.to(advance().span);
        }
        fail(span, target.text == "me" ? "'" + path + "' is the cell's read-only internal state; it cannot be assigned"
                                       : "'" + path + "' is an enclosing system's state: cells read it, never write it");
      }
    }
    switch (peek().kind) {
      case TokenKind::Equal: case TokenKind::PlusEqual: case TokenKind::MinusEqual:
      case TokenKind::StarEqual: case TokenKind::SlashEqual:
        result.op = advance().kind;
        break;
      default:
        failHere("'=' in the state calculation of '" + result.target + "'");
    }
    if (result.isRate && result.op != TokenKind::Equal) fail(previous().span, "'rate(x)' is set with '='");
    result.value = expression();
    result.span = first.span.to(previous().span);
    return result;
  }

  void successors(Rule& rule) {
    if (match(TokenKind::EmptySet)) {
    } else {
      while (!atStatementEnd() && (canStartModule() || check(TokenKind::Equal)))
        rule.successors.push_back(module(ModuleUse::Successor));
      if (!atStatementEnd()) failOnDigitModule();
    }
    if (match(TokenKind::Colon)) rule.probability = expression();
  }

  // ---- modules ----
  enum class ModuleUse { Pattern, Successor, Axiom, Instruction, Predecessor };

  bool canStartModule() const {
    const Token& token = peek();
    if (token.kind == TokenKind::Identifier || token.kind == TokenKind::LParen) return true;
    if (letters_ &&
        (token.kind == TokenKind::Number || token.kind == TokenKind::AmpAmp || token.kind == TokenKind::PipePipe))
      return true;
    return isSymbolToken(token.kind);
  }

  // ---- #letters: ABOP's strings as printed ----
  // `#letters` at the top level holds for the lsystem blocks after it, in a block for the
  // rest of the block. Under it a run of letters and digits where a module stands is one
  // module per character, so `FF-[-F+F+F]` and ABOP's `0 -> 1[0]0` read as printed.
  void notation() {
    if (inLSystem_)
      letters_ = true;
    else
      lettersEverywhere_ = true;
  }

  static size_t codePoints(std::string_view text) {
    size_t count = 0;
    for (unsigned char c : text) count += (c & 0xC0) != 0x80;
    return count;
  }

  // Replaces the token at pos_ by one token per character when it is a run of several
  // (`FF`, `01`), and `&&`, `||` by two symbols. A parameter list stays on the last one,
  // since its '(' touches the last character.
  void splitLetterRun() {
    const Token token = peek();
    std::vector<Token> pieces;
    // The pieces copy the token but for its text, which may be long (a run of 32,000
    // letters copied into each of its pieces took 1 GB).
    const Token shape{token.kind, {}, token.number, token.span, token.line, token.column};
    auto piece = [&](uint32_t begin, uint32_t end, TokenKind kind) {
      Token part = shape;
      part.kind = kind;
      part.text = kind == TokenKind::Identifier ? token.span.file->text().substr(begin, end - begin) : std::string();
      part.span.begin = begin;
      part.span.end = end;
      part.column = token.column + static_cast<int>(begin - token.span.begin);
      pieces.push_back(std::move(part));
    };
    if (token.kind == TokenKind::AmpAmp || token.kind == TokenKind::PipePipe) {
      const TokenKind one = token.kind == TokenKind::AmpAmp ? TokenKind::Amp : TokenKind::Pipe;
      piece(token.span.begin, token.span.begin + 1, one);
      piece(token.span.begin + 1, token.span.end, one);
    } else if ((token.kind == TokenKind::Identifier && codePoints(token.text) > 1) || token.kind == TokenKind::Number) {
      const std::string& text = token.span.file->text();
      for (uint32_t at = token.span.begin; at < token.span.end;) {
        uint32_t end = at + 1;
        while (end < token.span.end && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) ++end;
        const unsigned char c = static_cast<unsigned char>(text[at]);
        if (!std::isalnum(c) && c != '_' && c < 0x80)
          fail(token.span, "under #letters every digit is a module, so '" + token.text +
                               "' cannot stand here; write a number inside a module's parentheses, as in F(" +
                               token.text + ")");
        piece(at, end, TokenKind::Identifier);
        at = end;
      }
      if (pieces.size() == 1 && token.kind == TokenKind::Identifier) return;
    } else {
      return;
    }
    tokens_.split(pos_, pieces);
  }

  // A number where a module could stand: ABOP's digit labels (`0 -> 1[0]0`).
  void failOnDigitModule() {
    if (!inLSystem_ || !check(TokenKind::Number)) return;
    const Token& number = peek();
    fail(number.span, "'" + number.text + "' is a number, not a module: a label starts with a letter (write 'A" +
                          number.text +
                          "'), or put #letters in the block, under which every letter and digit is a module, as in "
                          "ABOP's 0 -> 1[0]0");
  }


  // `X`, `X(args)` (the '(' must touch the label), `(X(args), age)` or `me`.
  // A successor may be written `=X` (or `=(X, age)`, `(=X, age)`): it keeps its
  // predecessor's identity.
  Module module(ModuleUse use) {
    const Token& equal = peek();
    if (use == ModuleUse::Successor && match(TokenKind::Equal)) {
      Module kept = module(use);
      if (kept.keepsIdentity) fail(equal.span, "one '=' keeps the identity");
      if (kept.isMe) fail(equal.span, "'me' keeps its identity already; write 'me'");
      kept.keepsIdentity = true;
      kept.span = equal.span.to(kept.span);
      return kept;
    }
    const Token& first = peek();
    if (check(TokenKind::LParen)) {
      advance();
      ++depth_;
      const bool keeps = use == ModuleUse::Successor && match(TokenKind::Equal);
      Module inner = bareModule(use);
      inner.keepsIdentity = keeps;
      if (use == ModuleUse::Instruction || use == ModuleUse::Pattern)
        fail(first.span, "a timed module '(X, age)' cannot stand here");
      if (inner.isMe) fail(first.span, "'me' keeps its own age; it takes no birth age");
      expect(TokenKind::Comma, " and an age, as in '(A(x), 0.5)'");
      inner.age = expression();
      --depth_;
      const Token& close = expect(TokenKind::RParen, " to close the timed module");
      inner.span = first.span.to(close.span);
      return inner;
    }
    return bareModule(use);
  }

  Module bareModule(ModuleUse use) {
    Module result;
    if (letters_ && use != ModuleUse::Instruction) splitLetterRun();
    const Token& label = peek();
    if (label.kind != TokenKind::Identifier && !isSymbolToken(label.kind)) failHere("a module such as 'A' or 'F(1)'");
    advance();
    result.label = symbolSpelling(label);
    result.span = label.span;
    if (label.kind == TokenKind::Identifier && label.text == "me") {
      if (use == ModuleUse::Axiom || use == ModuleUse::Instruction || use == ModuleUse::Predecessor)
        fail(label.span, "'me' names the current cell and can only stand in a rule");
      result.isMe = true;
    }
    if (check(TokenKind::LParen) && peek().span.begin == label.span.end) {
      patternArguments(result, use);
      result.span = label.span.to(previous().span);
    }
    return result;
  }

  // `(a, b)` after a label: names or value patterns in patterns, expressions elsewhere.
  void patternArguments(Module& result, ModuleUse use) {
    advance();
    ++depth_;
    result.hasArgs = true;
    if (!check(TokenKind::RParen)) {
      do {
        if ((use == ModuleUse::Pattern || use == ModuleUse::Predecessor) &&
            (check(TokenKind::Number) || (check(TokenKind::Minus) && peek(1).kind == TokenKind::Number))) {
          // A value pattern, `A(3)`: the module matches only with that value there.
          const Token& sign = peek();
          const bool negative = match(TokenKind::Minus);
          const Token& value = advance();
          auto expr = std::make_unique<Expr>();
          expr->kind = Expr::Kind::Number;
          expr->number = negative ? -value.number : value.number;
          expr->span = sign.span.to(value.span);
          result.args.push_back(std::move(expr));
        } else if (use == ModuleUse::Pattern || use == ModuleUse::Predecessor) {
          const Token& name = peek();
          if (name.kind != TokenKind::Identifier)
            failHere("a parameter name or a number (patterns bind names, as in 'A(x)', or test values, as in 'A(3)')");
          advance();
          auto expr = std::make_unique<Expr>();
          expr->kind = Expr::Kind::Name;
          expr->name = name.text;
          expr->span = name.span;
          result.args.push_back(std::move(expr));
        } else {
          result.args.push_back(expression());
        }
      } while (match(TokenKind::Comma));
    }
    --depth_;
    expect(TokenKind::RParen, " to close the arguments of '" + result.label + "'");
  }

  // ---- systems ----
  System system() {
    System result;
    const Token& keyword = advance();
    const Token& name = expect(TokenKind::Identifier, " (the system's name)");
    result.name = name.text;
    result.nameSpan = name.span;
    if (check(TokenKind::LParen)) result.state = parameters();
    expect(TokenKind::LBrace, " to open the system");
    while (!check(TokenKind::RBrace) && !check(TokenKind::EndOfFile)) {
      size_t before = pos_;
      try {
        statement_ = Statement{};
        depth_ = 0;
        systemItem(result);
      } catch (const SyntaxError&) {
        synchronize();
      }
      if (pos_ == before) advance();
    }
    const Token& close = expect(TokenKind::RBrace, " to close the system");
    result.span = keyword.span.to(close.span);
    return result;
  }

  void systemItem(System& system) {
    if (match(TokenKind::Semicolon)) return;
    if (check(TokenKind::Directive) && peek().text == "letters")
      fail(peek().span, "#letters reads ABOP's strings in lsystem blocks; a system's cells keep their names");
    if (check(TokenKind::Directive)) return directive(system.defines, system.settings);
    if (checkWord("equiv")) return system.equivs.push_back(equiv(Statement{}));
    if (checkWord("pool")) {
      const Token& keyword = advance();
      const Token& kind = expect(TokenKind::Identifier, " (the pool kind: linear, grid or spatial)");
      system.poolKind = kind.text;
      // `pool grid(64, 64) wrap moore;`: sizes or a radius, then option words.
      if (check(TokenKind::LParen) && peek().span.begin == kind.span.end) {
        advance();
        ++depth_;
        if (!check(TokenKind::RParen)) {
          do system.poolArgs.push_back(expression());
          while (match(TokenKind::Comma));
        }
        --depth_;
        expect(TokenKind::RParen, " to close the pool's arguments");
      }
      while (check(TokenKind::Identifier) && !atStatementEnd()) system.poolOptions.push_back(advance().text);
      system.poolSpan = keyword.span.to(previous().span);
      endStatement();
      return;
    }
    if (checkWord("axiom")) return axiom(system);
    if (checkWord("fill") || (checkWord("at") && peek(1).kind == TokenKind::LParen)) return placement(system);
    if (checkWord("ignore") || checkWord("consider")) return symbolList(system);
    failHere("'pool', 'axiom', 'fill', 'at', 'ignore', 'consider', 'equiv', a directive or '}' in the system");
  }

  // `fill A(e)` and `at(x, y) A(1)`: cells of a grid system.
  void placement(System& system) {
    Placement result;
    const Token& keyword = advance();
    result.fill = keyword.text == "fill";
    if (!result.fill) {
      expect(TokenKind::LParen, " after 'at'");
      ++depth_;
      do result.at.push_back(expression());
      while (match(TokenKind::Comma));
      --depth_;
      expect(TokenKind::RParen, " to close the site's coordinates");
    }
    if (!canStartModule()) failHere("a cell, as in '" + std::string(result.fill ? "fill A(0)" : "at(1, 2) A(0)") + "'");
    result.module = module(ModuleUse::Axiom);
    result.span = keyword.span.to(previous().span);
    system.placements.push_back(std::move(result));
    endStatement();
  }

  void axiom(System& system) {
    const Token& keyword = advance();
    match(TokenKind::Colon);
    if (!system.axiom.empty()) fail(keyword.span, "the system already has an axiom");
    while (!atStatementEnd() && canStartModule()) system.axiom.push_back(module(ModuleUse::Axiom));
    if (!atStatementEnd()) failOnDigitModule();
    system.axiomSpan = keyword.span.to(previous().span);
    if (system.axiom.empty()) fail(keyword.span, "the axiom is empty: give at least one cell, as in 'axiom A(1)'");
    endStatement();
  }

  void symbolList(System& system) {
    const Token& keyword = advance();
    match(TokenKind::Colon);
    SymbolList list;
    while (!atStatementEnd()) {
      if (letters_) splitLetterRun();  // only within the statement: the next line's keyword stays whole
      if (!check(TokenKind::Identifier) && !isSymbolToken(peek().kind)) break;
      if (check(TokenKind::LBracket) || check(TokenKind::RBracket))
        fail(peek().span, "brackets delimit branches and cannot be ignored");
      list.symbols.push_back(symbolSpelling(advance()));
    }
    list.span = keyword.span.to(previous().span);
    list.consider = keyword.text == "consider";
    if (system.isLSystem) {
      filter_ = static_cast<int>(system.filters.size());
      system.filters.push_back(list);
    }
    (keyword.text == "ignore" ? system.ignore : system.consider).push_back(std::move(list));
    endStatement();
  }

  // ---- L-systems (paper 000 notation, line-based) ----
  System lsystem() {
    System result;
    result.isLSystem = true;
    section_ = RuleKind::Production;
    group_ = 0;
    filter_ = -1;
    const Token& keyword = advance();
    const Token& name = expect(TokenKind::Identifier, " (the L-system's name)");
    result.name = name.text;
    result.nameSpan = name.span;
    expect(TokenKind::LBrace, " to open the L-system");
    inLSystem_ = true;
    letters_ = lettersEverywhere_;
    while (!check(TokenKind::RBrace) && !check(TokenKind::EndOfFile)) {
      size_t before = pos_;
      Statement line{true, peek().column};
      statement_ = line;
      try {
        inStatement(line, [&] { lsystemItem(result); });
      } catch (const SyntaxError&) {
        // Line-based recovery: the statement ends at the next line that starts at or
        // left of its first column, even if an open '(' swallowed line breaks.
        pos_ = before;
        int startLine = peek().line;
        advance();
        while (!check(TokenKind::EndOfFile) && !check(TokenKind::RBrace) &&
               !(peek().line > startLine && peek().column <= line.startColumn)) {
          if (advance().kind == TokenKind::Semicolon) break;
        }
      }
      if (pos_ == before) advance();
    }
    inLSystem_ = letters_ = false;
    const Token& close = expect(TokenKind::RBrace, " to close the L-system");
    result.span = keyword.span.to(close.span);
    if (!result.axiomSpan.valid() && !sink_.limitReached())
      sink_.error(name.span, "L-system '" + name.text + "' has no axiom: give it one, as in 'axiom A'");
    return result;
  }

  void lsystemItem(System& system) {
    if (match(TokenKind::Semicolon)) return;
    if (check(TokenKind::Directive)) return directive(system.defines, system.settings);
    if (checkWord("equiv")) return system.equivs.push_back(equiv(statement_));
    if (checkWord("interpret") && peek(1).kind == TokenKind::Identifier && peek(1).line == peek().line)
      return symbolInterpretation(system);
    if (checkWord("axiom") && (peek(1).kind == TokenKind::Colon || peek(1).line == peek().line) &&
        peek(1).kind != TokenKind::Arrow && peek(1).kind != TokenKind::Less && peek(1).kind != TokenKind::Greater) {
      system.axiomSpan = peek().span;  // an axiom was written, even if it fails to parse
      return axiom(system);
    }
    if ((checkWord("ignore") || checkWord("consider")) && peek(1).kind == TokenKind::Colon) return symbolList(system);
    if ((checkWord("ignore") || checkWord("consider")) && !arrowInStatement()) {
      const std::string word = peek().text;
      fail(peek().span, "'" + word + "' needs a colon in an L-system, as in '" + word + ": F'");
    }
    if ((checkWord("g") || checkWord("develop")) &&
        (peek(1).kind == TokenKind::Identifier || isSymbolToken(peek(1).kind)) && peek(2).kind == TokenKind::LParen)
      return system.functions.push_back(function());
    if (sectionLine()) return section(system);
    if (checkWord("group") && peek(1).kind == TokenKind::Number && peek(2).kind == TokenKind::Colon) return group();
    if (checkWord("use") && peek(1).kind == TokenKind::Identifier && peek(1).text == "group" &&
        peek(2).kind == TokenKind::Colon)
      return useGroup(system);
    if (checkWord("maximum") && peek(1).kind == TokenKind::Identifier && peek(1).text == "depth" &&
        peek(2).kind == TokenKind::Colon)
      return maximumDepth(system);
    system.productions.push_back(production());
    system.productions.back().kind = section_;
    system.productions.back().group = group_;
    system.productions.back().filter = filter_;
  }

  // `group N:` (L-Py): the rules that follow belong to group N; `group 0:` is the default.
  void group() {
    advance();
    const Token& number = advance();
    advance();
    if (!(number.number >= 0) || number.number != std::floor(number.number) || number.number > 1e6)
      fail(number.span, "a group is a whole number from 0, as in 'group 1:'");
    group_ = static_cast<int>(number.number);
    endStatement();
  }

  // `use group: EXPR`: the active group, evaluated at the start of every step.
  void useGroup(System& system) {
    const Token& first = advance();
    advance();
    advance();
    if (system.useGroup) fail(first.span, "the L-system already says which group it uses");
    system.useGroup = expression();
    endStatement();
  }

  // `production:`, `decomposition:`, `homomorphism:` (or `interpretation:`) alone on
  // their line switch the kind of the rules that follow (L-Py's sections).
  bool sectionLine() const {
    if (!(checkWord("production") || checkWord("decomposition") || checkWord("homomorphism") ||
          checkWord("interpretation")))
      return false;
    if (peek(1).kind != TokenKind::Colon) return false;
    const Token& after = peek(2);
    return after.kind == TokenKind::Semicolon || after.kind == TokenKind::RBrace ||
           after.kind == TokenKind::EndOfFile || after.line > peek(1).line;
  }

  void section(System& system) {
    (void)system;
    const std::string& word = advance().text;
    advance();
    section_ = word == "production"      ? RuleKind::Production
               : word == "decomposition" ? RuleKind::Decomposition
                                         : RuleKind::Homomorphism;
    endStatement();
  }

  // `maximum depth: N` after `decomposition:` or `homomorphism:`.
  void maximumDepth(System& system) {
    const Token& first = peek();
    advance();
    advance();
    advance();
    if (section_ == RuleKind::Production)
      fail(first.span, "'maximum depth' belongs to a 'decomposition:' or 'homomorphism:' section; write it after one");
    ExprPtr& depth = section_ == RuleKind::Decomposition ? system.decompositionDepth : system.homomorphismDepth;
    if (depth)
      fail(first.span, std::string("the ") + (section_ == RuleKind::Decomposition ? "decomposition" : "homomorphism") +
                           "'s maximum depth is given twice");
    depth = expression();
    endStatement();
  }

  DevelopmentFunction function() {
    DevelopmentFunction result;
    const Token& keyword = advance();
    const Token& name = advance();
    result.name = symbolSpelling(name);
    result.params = parameters();
    for (const auto& param : result.params)
      if (param.defaultValue) fail(param.span, "a development function's parameters take no default values");
    expect(TokenKind::Equal, " after the development function's parameters");
    result.body = expression();
    result.span = keyword.span.to(previous().span);
    endStatement();
    return result;
  }

  // [label ':'] [left '<'] predecessor ['>' right] [':' condition] '->' successors [':' probability]
  Rule production() {
    const Token& first = peek();
    // Under #letters a single letter before ':' is a predecessor (`A : x > 1 -> B`).
    if (check(TokenKind::Identifier) && peek(1).kind == TokenKind::Colon &&
        !(letters_ && codePoints(peek().text) == 1)) {
      // `p1: A -> B` or `A : cond -> B`: try the label first, then fall back.
      // Backtracking restores everything the attempt changed: the position and the
      // parentheses it left open, which would otherwise hide the line breaks after it.
      const size_t savedPos = pos_;
      const int savedDepth = depth_, savedNesting = nesting_;
      ++speculating_;
      try {
        std::string name = advance().text;
        advance();
        Rule rule = productionAfterLabel(first);
        --speculating_;
        rule.name = name;
        return rule;
      } catch (const SyntaxError&) {
        --speculating_;
        pos_ = savedPos;
        depth_ = savedDepth;
        nesting_ = savedNesting;
      }
    }
    return productionAfterLabel(first);
  }

  // A module of a context: a pattern, or `*`, which matches any module. In an L-system
  // also `*(x, y)` (any module with that many parameters, binding them), `∅` (nothing:
  // the start of the word, the end of a branch) and `(B C | D)` (alternatives).
  Module contextModule(bool lsystem = true) {
    if (check(TokenKind::Star)) {
      Module any;
      any.label = "*";
      any.span = advance().span;
      if (check(TokenKind::LParen) && peek().span.begin == any.span.end) {
        if (!lsystem)
          fail(peek().span,
               "the wildcard '*' of a cell's context matches any module and binds nothing; write it "
               "without parameters");
        patternArguments(any, ModuleUse::Pattern);
        any.span = any.span.to(previous().span);
      }
      return any;
    }
    if (lsystem && check(TokenKind::EmptySet)) {
      Module none;
      none.label = "∅";
      none.span = advance().span;
      return none;
    }
    if (lsystem && check(TokenKind::LParen)) return alternativesOrTimed();
    return module(ModuleUse::Predecessor);
  }

  // `(B C | D)`: alternatives; or `(A(x), 3)`, a timed predecessor.
  Module alternativesOrTimed() {
    const Token& open = advance();
    Nested nested = nest(open.span, "context");
    ++depth_;
    Module group;
    group.label = "(|)";
    group.alternatives.emplace_back();
    for (;;) {
      auto& sequence = group.alternatives.back();
      while (!check(TokenKind::Pipe) && !check(TokenKind::RParen) && !check(TokenKind::Comma) &&
             (canStartModule() || check(TokenKind::Star) || check(TokenKind::EmptySet)))
        sequence.push_back(contextModule());
      if (check(TokenKind::Comma) && group.alternatives.size() == 1 && sequence.size() == 1 &&
          sequence.front().alternatives.empty()) {
        advance();
        Module timed = std::move(sequence.front());
        timed.age = expression();
        --depth_;
        const Token& close = expect(TokenKind::RParen, " to close the timed module");
        timed.span = open.span.to(close.span);
        return timed;
      }
      if (!match(TokenKind::Pipe)) break;
      group.alternatives.emplace_back();
    }
    --depth_;
    const Token& close =
        expect(TokenKind::RParen, " to close the alternatives, as in '(B | C D)', or ', age' after a timed module");
    group.span = open.span.to(close.span);
    return group;
  }

  // `<<` and `>>`: two touching '<' or '>'.
  bool atDouble(TokenKind kind) const {
    return check(kind) && peek(1).kind == kind && peek(1).span.begin == peek().span.end;
  }

  std::vector<Module> contextItems() {
    std::vector<Module> items;
    // A new line at or left of the statement's column ends it (docs/LANGUAGE.md 3.9).
    while (!atStatementEnd() && (canStartModule() || check(TokenKind::Star) || check(TokenKind::EmptySet)) &&
           !check(TokenKind::Less) && !check(TokenKind::Greater))
      items.push_back(contextModule());
    return items;
  }

  // [left '<'] [new-left '<<'] predecessor ['>' right]
  Rule productionAfterLabel(const Token& first) {
    Rule rule;
    rule.terminal = true;
    std::vector<Module> items = contextItems();
    auto newLeftContext = [&] {
      advance();
      advance();
      rule.hasContext = true;
      rule.newLeft = std::move(items);
      if (rule.newLeft.empty()) failHere("a new left context before '<<'");
      items = contextItems();
    };
    if (atDouble(TokenKind::Less)) {
      newLeftContext();
    } else if (match(TokenKind::Less)) {
      rule.hasContext = true;
      rule.left = std::move(items);
      items = contextItems();
      if (atDouble(TokenKind::Less)) newLeftContext();
      if (items.empty()) failHere("the predecessor after '<'");
    }
    if (items.size() != 1) {
      failOnDigitModule();
      if (items.empty()) failHere("a production such as 'A(x) -> B(x + 1)'");
      fail(items[1].span, "a production has one predecessor module; put context before '<' or after '>'");
    }
    rule.predecessor = std::move(items.front());
    if (rule.predecessor.label == "*")
      fail(rule.predecessor.span,
           "the wildcard '*' stands in contexts, not as the predecessor: a production "
           "belongs to the module it rewrites; write one per label");
    if (rule.predecessor.label == "∅")
      fail(rule.predecessor.span, "'∅' (nothing) stands in contexts, not as the predecessor");
    if (!rule.predecessor.alternatives.empty())
      fail(rule.predecessor.span,
           "alternatives stand in contexts; the predecessor is one module (write one "
           "production per alternative)");
    if (atDouble(TokenKind::Greater)) {
      rule.newRightSpan = peek().span.to(peek(1).span);
      advance();
      advance();
      rule.hasContext = true;
      while (!atStatementEnd() && (canStartModule() || check(TokenKind::Star) || check(TokenKind::EmptySet)) &&
             !check(TokenKind::Greater))
        rule.newRight.push_back(contextModule());
      if (rule.newRight.empty()) failHere("a new right context after '>>'");
    }
    if (match(TokenKind::Greater)) {
      rule.hasContext = true;
      while (!atStatementEnd() && (canStartModule() || check(TokenKind::Star) || check(TokenKind::EmptySet)))
        rule.right.push_back(contextModule());
      if (rule.right.empty()) failHere("a right context after '>'");
    }
    std::function<void(const std::vector<Module>&)> untimed = [&](const std::vector<Module>& side) {
      for (const Module& item : side) {
        if (item.age) fail(item.span, "a context module has no terminal age; write it without '(..., age)'");
        for (const auto& alternative : item.alternatives) untimed(alternative);
      }
    };
    for (const auto* side : {&rule.left, &rule.right, &rule.newLeft, &rule.newRight}) untimed(*side);
    if (match(TokenKind::Colon)) rule.predicate = expression();
    if (!match(TokenKind::Arrow)) failHere("'->' in the production");
    rule.hasAction = true;
    successors(rule);
    rule.span = first.span.to(previous().span);
    endStatement();
    return rule;
  }

  // ---- expressions, C precedence; '^' is power and binds tighter than unary minus ----
  // Deeper nesting than this is no program a person writes; it would only exhaust the stack.
  static constexpr int kMaxNesting = 200;

  // One level deeper for as long as it lives; past kMaxNesting an error, so that no
  // input, however deep, recurses further than that.
  struct Nested {
    int& nesting;
    ~Nested() { --nesting; }
  };
  [[nodiscard]] Nested nest(const SourceSpan& at, std::string_view what) {
    if (nesting_ >= kMaxNesting)
      fail(at, std::string(what) + " nested too deeply (more than " + std::to_string(kMaxNesting) + " levels)");
    ++nesting_;
    return Nested{nesting_};
  }

  ExprPtr expression() {
    Nested nested = nest(peek().span, "expression");
    return logicalOr();
  }

  // A chain `a + b + c ...` grows the tree without the parser recursing, so the tree's
  // height has a bound of its own, looser than the nesting: long sums are plausible.
  static constexpr int kMaxHeight = 1000;

  // Sets a node's height from its operands' and checks it.
  ExprPtr measured(ExprPtr node) {
    for (const ExprPtr& arg : node->args) node->height = std::max(node->height, arg->height + 1);
    if (node->height > kMaxHeight)
      fail(node->span, "expression too deep: more than " + std::to_string(kMaxHeight) +
                           " operators inside each other (split it with #define or a function)");
    return node;
  }

  ExprPtr binary(TokenKind op, ExprPtr left, ExprPtr right) {
    auto node = std::make_unique<Expr>();
    node->kind = Expr::Kind::Binary;
    node->op = op;
    node->span = left->span.to(right->span);
    node->args.push_back(std::move(left));
    node->args.push_back(std::move(right));
    return measured(std::move(node));
  }

  bool operatorAhead(std::initializer_list<TokenKind> kinds) const {
    if (atStatementEnd()) return false;
    for (TokenKind kind : kinds)
      if (check(kind)) return true;
    return false;
  }

  ExprPtr logicalOr() {
    ExprPtr left = logicalAnd();
    while (operatorAhead({TokenKind::PipePipe, TokenKind::Pipe})) {
      advance();
      left = binary(TokenKind::PipePipe, std::move(left), logicalAnd());
    }
    return left;
  }
  ExprPtr logicalAnd() {
    ExprPtr left = equality();
    while (operatorAhead({TokenKind::AmpAmp, TokenKind::Amp})) {
      advance();
      left = binary(TokenKind::AmpAmp, std::move(left), equality());
    }
    return left;
  }
  ExprPtr equality() {
    ExprPtr left = relational();
    for (;;) {
      if (operatorAhead({TokenKind::EqualEqual, TokenKind::BangEqual})) {
        TokenKind op = advance().kind;
        left = binary(op, std::move(left), relational());
      } else if (depth_ > 0 && check(TokenKind::Equal)) {
        fail(peek().span, "'=' assigns; compare with '=='");
      } else {
        return left;
      }
    }
  }
  ExprPtr relational() {
    ExprPtr left = additive();
    while (operatorAhead({TokenKind::Less, TokenKind::LessEqual, TokenKind::Greater, TokenKind::GreaterEqual})) {
      TokenKind op = advance().kind;
      left = binary(op, std::move(left), additive());
    }
    return left;
  }
  ExprPtr additive() {
    ExprPtr left = multiplicative();
    while (operatorAhead({TokenKind::Plus, TokenKind::Minus})) {
      TokenKind op = advance().kind;
      left = binary(op, std::move(left), multiplicative());
    }
    return left;
  }
  ExprPtr multiplicative() {
    ExprPtr left = unary();
    while (operatorAhead({TokenKind::Star, TokenKind::Slash, TokenKind::Percent})) {
      TokenKind op = advance().kind;
      left = binary(op, std::move(left), unary());
    }
    return left;
  }
  ExprPtr unary() {
    if (check(TokenKind::Minus) || check(TokenKind::Plus) || check(TokenKind::Bang)) {
      const Token& op = advance();
      Nested nested = nest(op.span, "expression");
      ExprPtr operand = unary();
      if (op.kind == TokenKind::Plus) return operand;
      auto node = std::make_unique<Expr>();
      node->kind = Expr::Kind::Unary;
      node->op = op.kind;
      node->span = op.span.to(operand->span);
      node->args.push_back(std::move(operand));
      return measured(std::move(node));
    }
    return power();
  }
  ExprPtr power() {
    ExprPtr base = postfix();
    if (operatorAhead({TokenKind::Caret})) {
      Nested nested = nest(advance().span, "expression");
      ExprPtr exponent = unary();  // right-associative; allows 2^-1
      return binary(TokenKind::Caret, std::move(base), std::move(exponent));
    }
    return base;
  }
  ExprPtr postfix() {
    ExprPtr node = primary();
    while (check(TokenKind::Dot) && !atStatementEnd()) {
      advance();
      const Token& field = expect(TokenKind::Identifier, " (a state variable after '.')");
      auto member = std::make_unique<Expr>();
      member->kind = Expr::Kind::Member;
      member->name = field.text;
      member->span = node->span.to(field.span);
      member->args.push_back(std::move(node));
      node = measured(std::move(member));
    }
    return node;
  }
  ExprPtr primary() {
    const Token& token = peek();
    if (token.kind == TokenKind::Number) {
      advance();
      auto node = std::make_unique<Expr>();
      node->kind = Expr::Kind::Number;
      node->number = token.number;
      node->span = token.span;
      return node;
    }
    if (token.kind == TokenKind::Identifier) {
      advance();
      auto node = std::make_unique<Expr>();
      node->name = token.text;
      node->span = token.span;
      if (check(TokenKind::LParen)) {
        advance();
        ++depth_;
        node->kind = Expr::Kind::Call;
        if (!check(TokenKind::RParen)) {
          do node->args.push_back(expression());
          while (match(TokenKind::Comma));
        }
        --depth_;
        const Token& close = expect(TokenKind::RParen, " to close the call of '" + token.text + "'");
        node->span = token.span.to(close.span);
        return measured(std::move(node));
      }
      node->kind = Expr::Kind::Name;
      return node;
    }
    if (token.kind == TokenKind::LParen) {
      advance();
      ++depth_;
      ExprPtr inner = expression();
      --depth_;
      expect(TokenKind::RParen, " to close the parenthesis");
      return inner;
    }
    failHere("an expression");
  }

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

}  // namespace

ast::Program parse(const SourceFile& file, DiagnosticSink& sink) { return Parser(file, sink).run(); }

}  // namespace ontogen
