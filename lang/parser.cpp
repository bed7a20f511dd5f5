// The cell language's parser (lang/parser.h): tokens, errors and recovery, the top
// level, directives and equiv lines. The class is in lang/parser_internal.h; cells, systems
// and expressions are parsed in lang/parser_cells.cpp, lang/parser_systems.cpp and
// lang/parser_expressions.cpp.

#include "lang/parser.h"

#include <algorithm>
#include <string>

#include "lang/parser_internal.h"

namespace ontogen {

namespace detail {

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

Parser::Parser(const SourceFile& file, DiagnosticSink& sink) : sink_(sink) {
  // #letters splits tokens in place (splitLetterRun); with room for every character
  // the buffer never reallocates, so references to tokens already read stay valid.
  std::vector<Token> tokens = lex(file, sink);
  const size_t room = file.text().find("#letters") != std::string::npos ? file.text().size() : 0;
  tokens_ = TokenBuffer(std::move(tokens), room);
}

Program Parser::run() {
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

[[noreturn]] void Parser::fail(const SourceSpan& span, std::string message) {
  if (speculating_ == 0) {
    // An Error token was already reported by the lexer: stay silent on it.
    if (peek().kind != TokenKind::Error) sink_.error(span, std::move(message));
    if (sink_.limitReached()) throw ErrorLimitReached{};
  }
  throw SyntaxError{};
}

[[noreturn]] void Parser::failHere(std::string expected) {
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

bool Parser::atStatementEnd() const {
  const Token& token = peek();
  if (token.kind == TokenKind::Semicolon || token.kind == TokenKind::RBrace || token.kind == TokenKind::EndOfFile)
    return true;
  return atLineEnd();
}

bool Parser::atLineEnd() const {
  if (!statement_.lineBased || depth_ > 0 || pos_ <= statement_.firstToken) return false;
  const Token& token = peek();
  if (token.kind == TokenKind::RBrace || token.kind == TokenKind::EndOfFile) return false;
  return token.line > previous().line && token.column <= statement_.startColumn;
}

void Parser::endStatement() {
  if (match(TokenKind::Semicolon)) return;
  if (check(TokenKind::RBrace) || check(TokenKind::EndOfFile)) return;
  if (statement_.lineBased && atStatementEnd()) return;
  failHere("';' or the end of the statement");
}

bool Parser::arrowInStatement() const {
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

void Parser::synchronize() {
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

void Parser::topLevel(Program& program) {
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

Import Parser::importStatement() {
  const Token& keyword = advance();
  const Token& path = expect(TokenKind::String, " (the file to import, in double quotes: import \"lib.cell\";)");
  Import result{keyword.span.to(path.span), path.text};
  match(TokenKind::Semicolon);
  return result;
}

void Parser::directive(std::vector<Define>& defines, std::vector<Setting>& settings) {
  const Token& hash = advance();
  try {
    directiveBody(hash, defines, settings);
  } catch (const SyntaxError&) {
    // A directive is one line: recover at the next one.
    while (!check(TokenKind::EndOfFile) && peek().line == hash.line) advance();
  }
}

void Parser::directiveBody(const Token& hash, std::vector<Define>& defines, std::vector<Setting>& settings) {
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

Define Parser::defineStatement(const Token& hash) {
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

Setting Parser::numberSetting(const Token& hash, const Directive& directive) {
  Setting setting{hash.span, &directive};
  if (atStatementEnd()) fail(hash.span, "expected a value after '#" + hash.text + "'");
  setting.value = expression();
  setting.span = hash.span.to(previous().span);
  return setting;
}

Setting Parser::rangeSetting(const Token& hash, const Directive& directive) {
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

Setting Parser::wordSetting(const Token& hash, const Directive& directive) {
  const Token& word = peek();
  if (word.kind != TokenKind::Identifier ||
      std::find(directive.words.begin(), directive.words.end(), word.text) == directive.words.end())
    failHere(wordChoices(directive) + " after #" + hash.text);
  advance();
  return Setting{hash.span.to(word.span), &directive, nullptr, word.text};
}

Setting Parser::timeSignature(const Token& hash, const Directive& directive) {
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

Setting Parser::numberedName(const Token& hash, const Directive& directive) {
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

Setting Parser::numberedFile(const Token& hash, const Directive& directive) {
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

Equiv Parser::equiv(Statement statement) {
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

}  // namespace detail

ast::Program parse(const SourceFile& file, DiagnosticSink& sink) { return detail::Parser(file, sink).run(); }

}  // namespace ontogen
