#include "lang/lexer.h"

#include <cctype>
#include <cstdlib>
#include <cstring>

#include "model/utf8.h"

namespace ontogen {

std::string_view tokenKindName(TokenKind kind) {
  switch (kind) {
    case TokenKind::EndOfFile: return "end of file";
    case TokenKind::Identifier: return "identifier";
    case TokenKind::Number: return "number";
    case TokenKind::String: return "string";
    case TokenKind::Directive: return "directive";
    case TokenKind::LParen: return "'('";
    case TokenKind::RParen: return "')'";
    case TokenKind::LBrace: return "'{'";
    case TokenKind::RBrace: return "'}'";
    case TokenKind::LBracket: return "'['";
    case TokenKind::RBracket: return "']'";
    case TokenKind::Comma: return "','";
    case TokenKind::Semicolon: return "';'";
    case TokenKind::Colon: return "':'";
    case TokenKind::Dot: return "'.'";
    case TokenKind::Plus: return "'+'";
    case TokenKind::Minus: return "'-'";
    case TokenKind::Star: return "'*'";
    case TokenKind::Slash: return "'/'";
    case TokenKind::Percent: return "'%'";
    case TokenKind::Caret: return "'^'";
    case TokenKind::Backslash: return "'\\'";
    case TokenKind::Amp: return "'&'";
    case TokenKind::AmpAmp: return "'&&'";
    case TokenKind::Pipe: return "'|'";
    case TokenKind::PipePipe: return "'||'";
    case TokenKind::Bang: return "'!'";
    case TokenKind::Less: return "'<'";
    case TokenKind::LessEqual: return "'<='";
    case TokenKind::Greater: return "'>'";
    case TokenKind::GreaterEqual: return "'>='";
    case TokenKind::EqualEqual: return "'=='";
    case TokenKind::BangEqual: return "'!='";
    case TokenKind::Equal: return "'='";
    case TokenKind::PlusEqual: return "'+='";
    case TokenKind::MinusEqual: return "'-='";
    case TokenKind::StarEqual: return "'*='";
    case TokenKind::SlashEqual: return "'/='";
    case TokenKind::Arrow: return "'->'";
    case TokenKind::Dollar: return "'$'";
    case TokenKind::Tilde: return "'~'";
    case TokenKind::At: return "'@'";
    case TokenKind::EmptySet: return "'∅'";
    case TokenKind::Error: return "invalid character";
  }
  return "token";
}

namespace {

bool isIdentStart(unsigned char c) { return std::isalpha(c) || c == '_' || c >= 0x80; }
bool isIdentChar(unsigned char c) { return std::isalnum(c) || c == '_' || c >= 0x80; }

// Multi-byte UTF-8 operators the papers print; they lex as their ASCII equivalents.
struct Utf8Operator {
  const char* bytes;
  TokenKind kind;
};
constexpr Utf8Operator kUtf8Operators[] = {
    {"\xE2\x86\x92", TokenKind::Arrow},         // →
    {"\xE2\x89\xA4", TokenKind::LessEqual},     // ≤
    {"\xE2\x89\xA5", TokenKind::GreaterEqual},  // ≥
    {"\xE2\x89\xA0", TokenKind::BangEqual},     // ≠
    {"\xE2\x88\x85", TokenKind::EmptySet},      // ∅
};

class Lexer {
 public:
  Lexer(const SourceFile& file, DiagnosticSink& sink) : file_(file), text_(file.text()), sink_(sink) {}

  std::vector<Token> run() {
    reportInvalidUtf8();
    std::vector<Token> tokens;
    for (;;) {
      skipSpaceAndComments();
      // Past the sink's error limit the rest of the text is not read.
      if (sink_.limitReached()) pos_ = text_.size();
      Token token = next();
      followNotation(token);
      bool done = token.kind == TokenKind::EndOfFile;
      tokens.push_back(std::move(token));
      if (done) break;
    }
    return tokens;
  }

 private:
  // The source is UTF-8: the first byte of each line that breaks it is an error, so a
  // file of binary noise gives one error a line, not one a byte.
  void reportInvalidUtf8() {
    int reportedLine = 0;
    for (size_t at = findInvalidUtf8(text_); at < text_.size(); at = findInvalidUtf8(text_, at + 1)) {
      const int line = file_.lineOf(static_cast<uint32_t>(at));
      if (line == reportedLine) continue;
      reportedLine = line;
      sink_.error(span(at, at + 1), "invalid UTF-8: byte " + hexByte(text_[at]) + " starts no character (the source must be UTF-8 text)");
      if (sink_.limitReached()) return;
    }
  }

  static std::string hexByte(char c) {
    static constexpr char kDigits[] = "0123456789ABCDEF";
    const auto byte = static_cast<unsigned char>(c);
    return std::string("0x") + kDigits[byte >> 4] + kDigits[byte & 15];
  }

  bool atUtf8Operator() const {
    for (const auto& op : kUtf8Operators)
      if (text_.compare(pos_, std::strlen(op.bytes), op.bytes) == 0) return true;
    return false;
  }

  char peek(size_t ahead = 0) const { return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0'; }

  // Under #letters (lang/parser_cells.cpp), ABOP's `]/////` is five rolls: a `//` that touches
  // the token before it is no comment. The lexer follows where #letters holds: after a
  // top-level one, or to the end of the block that holds it.
  void followNotation(const Token& token) {
    if (token.kind == TokenKind::LBrace) ++braces_;
    if (token.kind == TokenKind::RBrace && braces_ > 0 && --braces_ < lettersBraces_) lettersBraces_ = 0;
    if (token.kind == TokenKind::Directive && token.text == "letters") {
      if (braces_ == 0)
        lettersEverywhere_ = true;
      else if (lettersBraces_ == 0)
        lettersBraces_ = braces_;
    }
  }
  bool lettersHold() const { return lettersEverywhere_ || lettersBraces_ > 0; }

  void skipSpaceAndComments() {
    for (;;) {
      while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
      if (peek() == '/' && peek(1) == '/' && lettersHold() && pos_ > 0 &&
          !std::isspace(static_cast<unsigned char>(text_[pos_ - 1])))
        return;
      if (peek() == '/' && peek(1) == '/') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else if (peek() == '/' && peek(1) == '*') {
        size_t start = pos_;
        size_t close = text_.find("*/", pos_ + 2);
        if (close == std::string::npos) {
          sink_.error(span(start, start + 2), "unterminated comment: '/*' has no matching '*/'");
          pos_ = text_.size();
        } else {
          pos_ = close + 2;
        }
      } else {
        return;
      }
    }
  }

  SourceSpan span(size_t begin, size_t end) const {
    return {&file_, static_cast<uint32_t>(begin), static_cast<uint32_t>(end)};
  }

  Token make(TokenKind kind, size_t begin, std::string text = {}) {
    Token token;
    token.kind = kind;
    token.text = std::move(text);
    token.span = span(begin, pos_);
    token.line = file_.lineOf(static_cast<uint32_t>(begin));
    token.column = file_.columnOf(static_cast<uint32_t>(begin));
    return token;
  }

  Token number(size_t begin) {
    while (std::isdigit(static_cast<unsigned char>(peek()))) ++pos_;
    if (peek() == '.' && std::isdigit(static_cast<unsigned char>(peek(1)))) {
      ++pos_;
      while (std::isdigit(static_cast<unsigned char>(peek()))) ++pos_;
    } else if (peek() == '.' && !isIdentStart(static_cast<unsigned char>(peek(1)))) {
      ++pos_;  // "3." is a number; "3.x" is not
    }
    if ((peek() == 'e' || peek() == 'E') &&
        (std::isdigit(static_cast<unsigned char>(peek(1))) ||
         ((peek(1) == '+' || peek(1) == '-') && std::isdigit(static_cast<unsigned char>(peek(2)))))) {
      pos_ += 2;
      while (std::isdigit(static_cast<unsigned char>(peek()))) ++pos_;
    }
    std::string spelling = text_.substr(begin, pos_ - begin);
    Token token = make(TokenKind::Number, begin, spelling);
    token.number = std::strtod(spelling.c_str(), nullptr);
    return token;
  }

  Token next() {
    size_t begin = pos_;
    if (pos_ >= text_.size()) return make(TokenKind::EndOfFile, begin);
    unsigned char c = static_cast<unsigned char>(text_[pos_]);

    for (const auto& op : kUtf8Operators) {
      size_t length = std::strlen(op.bytes);
      if (text_.compare(pos_, length, op.bytes) == 0) {
        pos_ += length;
        return make(op.kind, begin);
      }
    }
    if (std::isdigit(c) || (c == '.' && std::isdigit(static_cast<unsigned char>(peek(1))))) return number(begin);
    if (isIdentStart(c)) {
      // UTF-8 letters continue a name, but the UTF-8 operators end it: `x≤1` is three tokens.
      while (pos_ < text_.size() && isIdentChar(static_cast<unsigned char>(text_[pos_])) && !atUtf8Operator()) ++pos_;
      return make(TokenKind::Identifier, begin, text_.substr(begin, pos_ - begin));
    }
    if (c == '#') {
      ++pos_;
      size_t nameBegin = pos_;
      while (pos_ < text_.size() && isIdentChar(static_cast<unsigned char>(text_[pos_]))) ++pos_;
      if (pos_ == nameBegin) {
        sink_.error(span(begin, pos_), "expected a directive name after '#' (such as #define)");
        return make(TokenKind::Error, begin, "#");
      }
      return make(TokenKind::Directive, begin, text_.substr(nameBegin, pos_ - nameBegin));
    }
    if (c == '"') {
      ++pos_;
      std::string value;
      while (pos_ < text_.size() && text_[pos_] != '"' && text_[pos_] != '\n') value += text_[pos_++];
      if (peek() != '"') {
        sink_.error(span(begin, pos_), "unterminated string: expected '\"' before the end of the line");
        return make(TokenKind::String, begin, value);
      }
      ++pos_;
      return make(TokenKind::String, begin, value);
    }

    ++pos_;
    auto two = [&](char second, TokenKind ifTwo, TokenKind ifOne) {
      if (peek() == second) {
        ++pos_;
        return make(ifTwo, begin);
      }
      return make(ifOne, begin);
    };
    switch (c) {
      case '(': return make(TokenKind::LParen, begin);
      case ')': return make(TokenKind::RParen, begin);
      case '{': return make(TokenKind::LBrace, begin);
      case '}': return make(TokenKind::RBrace, begin);
      case '[': return make(TokenKind::LBracket, begin);
      case ']': return make(TokenKind::RBracket, begin);
      case ',': return make(TokenKind::Comma, begin);
      case ';': return make(TokenKind::Semicolon, begin);
      case ':': return make(TokenKind::Colon, begin);
      case '.': return make(TokenKind::Dot, begin);
      case '+': return two('=', TokenKind::PlusEqual, TokenKind::Plus);
      case '-':
        if (peek() == '>') {
          ++pos_;
          return make(TokenKind::Arrow, begin);
        }
        if (peek() == '-' && peek(1) == '>') {
          pos_ += 2;
          return make(TokenKind::Arrow, begin);
        }
        return two('=', TokenKind::MinusEqual, TokenKind::Minus);
      case '*': return two('=', TokenKind::StarEqual, TokenKind::Star);
      case '/': return two('=', TokenKind::SlashEqual, TokenKind::Slash);
      case '%': return make(TokenKind::Percent, begin);
      case '^': return make(TokenKind::Caret, begin);
      case '\\': return make(TokenKind::Backslash, begin);
      case '&': return two('&', TokenKind::AmpAmp, TokenKind::Amp);
      case '|': return two('|', TokenKind::PipePipe, TokenKind::Pipe);
      case '!': return two('=', TokenKind::BangEqual, TokenKind::Bang);
      case '<': return two('=', TokenKind::LessEqual, TokenKind::Less);
      case '>': return two('=', TokenKind::GreaterEqual, TokenKind::Greater);
      case '=': return two('=', TokenKind::EqualEqual, TokenKind::Equal);
      case '$': return make(TokenKind::Dollar, begin);
      case '~': return make(TokenKind::Tilde, begin);
      case '@': return make(TokenKind::At, begin);
      case '?':
        // cpfg's query modules ?P ?H ?L ?U (ABOP 1.10), and the physics set's ?F ?M ?D,
        // are labels.
        if (pos_ < text_.size() && std::strchr("PHLUFMD", text_[pos_]) && text_[pos_] != '\0' &&
            !(pos_ + 1 < text_.size() && isIdentChar(static_cast<unsigned char>(text_[pos_ + 1])))) {
          ++pos_;
          return make(TokenKind::Identifier, begin, text_.substr(begin, 2));
        }
        break;
      default: break;
    }
    // Control bytes are named, not echoed: the terminal would act on them.
    const bool printable = c >= 0x20 && c < 0x7F;
    std::string shown(1, static_cast<char>(c));
    sink_.error(span(begin, pos_), printable ? "unexpected character '" + shown + "'"
                                             : "unexpected control character " + hexByte(static_cast<char>(c)));
    return make(TokenKind::Error, begin, shown);
  }

  const SourceFile& file_;
  const std::string& text_;
  DiagnosticSink& sink_;
  size_t pos_ = 0;
  int braces_ = 0;                  // '{' open
  int lettersBraces_ = 0;           // > 0: #letters holds while this many '{' are open
  bool lettersEverywhere_ = false;  // a top-level #letters: to the end of the file
};

}  // namespace

std::vector<Token> lex(const SourceFile& file, DiagnosticSink& sink) { return Lexer(file, sink).run(); }

}  // namespace ontogen
