#pragma once
// Tokens of the cell language. Keywords are contextual (lexed as identifiers), so that
// words like `cell` or `pool` stay free as module labels where no keyword can stand.

#include <string>
#include <string_view>

#include "model/source.h"

namespace ontogen {

enum class TokenKind {
  EndOfFile,
  Identifier,  // also UTF-8 names such as ρ or β
  Number,
  String,
  Directive,   // `#define`, `#angle`, ...: text holds the name without '#'
  LParen, RParen, LBrace, RBrace, LBracket, RBracket,
  Comma, Semicolon, Colon, Dot,
  Plus, Minus, Star, Slash, Percent, Caret, Backslash,
  Amp, AmpAmp, Pipe, PipePipe, Bang,
  Less, LessEqual, Greater, GreaterEqual, EqualEqual, BangEqual,
  Equal, PlusEqual, MinusEqual, StarEqual, SlashEqual,
  Arrow,       // `->`, `-->` or `→`
  Dollar, Tilde, At,
  EmptySet,    // `∅`: the empty successor
  Error,       // a character the language does not use; text holds it
};

struct Token {
  TokenKind kind = TokenKind::EndOfFile;
  std::string text;  ///< identifier name, number spelling, string contents, directive name
  double number = 0;
  SourceSpan span;
  int line = 0;    ///< 1-based, cached from span for the newline-sensitive statements
  int column = 0;  ///< 1-based byte column
};

/// The spelling of a token kind for messages, e.g. "'->'" or "identifier".
std::string_view tokenKindName(TokenKind kind);

}  // namespace ontogen
