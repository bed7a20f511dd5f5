#include "lang/lexer.h"

#include <gtest/gtest.h>

namespace ontogen {
namespace {

std::vector<Token> lexText(const std::string& text, DiagnosticSink& sink) {
  static std::vector<std::unique_ptr<SourceFile>> keep;  // tokens point into their file
  keep.push_back(std::make_unique<SourceFile>("test.cell", text));
  return lex(*keep.back(), sink);
}

std::vector<TokenKind> kinds(const std::vector<Token>& tokens) {
  std::vector<TokenKind> result;
  for (const auto& token : tokens) result.push_back(token.kind);
  return result;
}

TEST(Lexer, OperatorsAndArrows) {
  DiagnosticSink sink;
  auto tokens = lexText("-> --> → <= ≤ >= ≥ != ≠ == && || & | ^ \\ ∅ += -=", sink);
  using K = TokenKind;
  EXPECT_EQ(kinds(tokens), (std::vector<K>{K::Arrow, K::Arrow, K::Arrow, K::LessEqual, K::LessEqual,
                                           K::GreaterEqual, K::GreaterEqual, K::BangEqual, K::BangEqual,
                                           K::EqualEqual, K::AmpAmp, K::PipePipe, K::Amp, K::Pipe, K::Caret,
                                           K::Backslash, K::EmptySet, K::PlusEqual, K::MinusEqual, K::EndOfFile}));
  EXPECT_FALSE(sink.hasErrors());
}

TEST(Lexer, NumbersKeepTheirValue) {
  DiagnosticSink sink;
  auto tokens = lexText("0.04 3 2.5e-3 .5 7.", sink);
  ASSERT_EQ(tokens.size(), 6u);
  EXPECT_DOUBLE_EQ(tokens[0].number, 0.04);
  EXPECT_DOUBLE_EQ(tokens[1].number, 3);
  EXPECT_DOUBLE_EQ(tokens[2].number, 2.5e-3);
  EXPECT_DOUBLE_EQ(tokens[3].number, 0.5);
  EXPECT_DOUBLE_EQ(tokens[4].number, 7);
}

TEST(Lexer, Utf8Identifiers) {
  DiagnosticSink sink;
  auto tokens = lexText("ρ β_sw τ", sink);
  ASSERT_EQ(tokens.size(), 4u);
  EXPECT_EQ(tokens[0].text, "ρ");
  EXPECT_EQ(tokens[1].text, "β_sw");
  EXPECT_EQ(tokens[2].text, "τ");
}

TEST(Lexer, DirectivesAndComments) {
  DiagnosticSink sink;
  auto tokens = lexText("#define WR 50 // wheel\n/* block\ncomment */ #radians", sink);
  ASSERT_EQ(tokens.size(), 5u);
  EXPECT_EQ(tokens[0].kind, TokenKind::Directive);
  EXPECT_EQ(tokens[0].text, "define");
  EXPECT_EQ(tokens[3].kind, TokenKind::Directive);
  EXPECT_EQ(tokens[3].text, "radians");
  EXPECT_EQ(tokens[3].line, 3);
  EXPECT_EQ(tokens[3].column, 12);
}

// Under #letters a '//' touching the token before it is two rolls (ABOP's ]/////); one
// after a space is still a comment, and the rule ends with the block that says #letters.
TEST(Lexer, UnderLettersTouchingSlashesAreRolls) {
  DiagnosticSink sink;
  auto tokens = lexText("a { #letters\n ]//F // note\n}\nb { ]//F\n}", sink);
  using K = TokenKind;
  EXPECT_EQ(kinds(tokens), (std::vector<K>{K::Identifier, K::LBrace, K::Directive, K::RBracket, K::Slash, K::Slash,
                                           K::Identifier, K::RBrace, K::Identifier, K::LBrace, K::RBracket,
                                           K::RBrace, K::EndOfFile}));
  EXPECT_FALSE(sink.hasErrors());
}

TEST(Lexer, BadCharacterIsReportedAndLexingGoesOn) {
  DiagnosticSink sink;
  auto tokens = lexText("A ? B", sink);
  ASSERT_EQ(sink.errorCount(), 1);
  EXPECT_EQ(sink.diagnostics()[0].message, "unexpected character '?'");
  EXPECT_EQ(sink.diagnostics()[0].span.column(), 3);
  EXPECT_EQ(tokens[2].text, "B");
}

TEST(Lexer, InvalidUtf8IsAnErrorAtItsByteOncePerLine) {
  DiagnosticSink sink;
  // A stray continuation byte, an overlong '/', a surrogate, a truncated sequence.
  lexText("A \x80 B\nC \xC0\xAF \xED\xA0\x80\nok \xCF\x81\nD \xE2\x88", sink);
  ASSERT_EQ(sink.errorCount(), 3) << formatDiagnostics(sink);
  EXPECT_EQ(sink.diagnostics()[0].message,
            "invalid UTF-8: byte 0x80 starts no character (the source must be UTF-8 text)");
  EXPECT_EQ(sink.diagnostics()[0].span.line(), 1);
  EXPECT_EQ(sink.diagnostics()[0].span.column(), 3);
  EXPECT_EQ(sink.diagnostics()[1].span.line(), 2);
  EXPECT_EQ(sink.diagnostics()[1].span.column(), 3);
  EXPECT_EQ(sink.diagnostics()[2].span.line(), 4);
  EXPECT_EQ(sink.diagnostics()[2].span.column(), 3);
}

TEST(Lexer, AByteOrderMarkIsNotPartOfTheFirstName) {
  DiagnosticSink sink;
  auto tokens = lexText("\xEF\xBB\xBFlsystem a", sink);
  EXPECT_FALSE(sink.hasErrors());
  ASSERT_EQ(tokens.size(), 3u);
  EXPECT_EQ(tokens[0].text, "lsystem");
  EXPECT_EQ(tokens[0].column, 1);
}

TEST(Lexer, ControlCharactersAreNamedNotEchoed) {
  DiagnosticSink sink;
  lexText("A \x01 B", sink);
  ASSERT_EQ(sink.errorCount(), 1);
  EXPECT_EQ(sink.diagnostics()[0].message, "unexpected control character 0x01");
}

TEST(Lexer, StopsReadingAtTheErrorLimit) {
  DiagnosticSink sink(20);
  auto tokens = lexText(std::string(100000, '?'), sink);
  EXPECT_EQ(sink.errorCount(), 20);
  EXPECT_LT(tokens.size(), 100u);
  EXPECT_EQ(tokens.back().kind, TokenKind::EndOfFile);
}

}  // namespace
}  // namespace ontogen
