#include "model/diagnostics.h"

#include <gtest/gtest.h>

namespace ontogen {
namespace {

TEST(Diagnostics, FormatLikeClangWithCaretUnderTheSpan) {
  SourceFile file("model.cell", "lsystem a {\n  A(x) -> A(y + 1)\n}\n");
  Diagnostic d{Severity::Error, SourceSpan{&file, 24, 25}, "unknown name 'y'"};
  EXPECT_EQ(formatDiagnostic(d),
            "model.cell:2:13: error: unknown name 'y'\n"
            "  A(x) -> A(y + 1)\n"
            "            ^\n");
  Diagnostic wide{Severity::Warning, SourceSpan{&file, 10, 18}, "w"};
  EXPECT_EQ(formatDiagnostic(wide), "model.cell:1:11: warning: w\nlsystem a {\n          ^\n");
}

TEST(Diagnostics, SinkCountsErrorsOnly) {
  DiagnosticSink sink;
  sink.warning({}, "a");
  sink.note({}, "b");
  EXPECT_FALSE(sink.hasErrors());
  sink.error({}, "c");
  EXPECT_EQ(sink.errorCount(), 1);
  EXPECT_EQ(formatDiagnostic(sink.diagnostics()[2]), "ontogen: error: c\n");
}

TEST(SourceFile, LinesAndColumns) {
  SourceFile file("f", "ab\ncd\n\nx");
  EXPECT_EQ(file.lineOf(0), 1);
  EXPECT_EQ(file.lineOf(3), 2);
  EXPECT_EQ(file.columnOf(4), 2);
  EXPECT_EQ(file.lineOf(7), 4);
  EXPECT_EQ(file.lineText(2), "cd");
  EXPECT_EQ(file.lineText(3), "");
}

TEST(Diagnostics, LongLinesAreEchoedAsAWindowAroundTheCaret) {
  // 100,000 columns, the mistake at column 50,001: the echo is 80 characters and the
  // caret still sits under it.
  std::string text = std::string(50000, 'a') + "?" + std::string(49999, 'b');
  SourceFile file("long.cell", text);
  Diagnostic d{Severity::Error, SourceSpan{&file, 50000, 50001}, "unexpected character '?'"};
  EXPECT_EQ(formatDiagnostic(d), "long.cell:1:50001: error: unexpected character '?'\n"
                                 "…" + std::string(40, 'a') + "?" + std::string(39, 'b') + "…\n"
                                 " " + std::string(40, ' ') + "^\n");
  // At the start of the line the window is cut on the right only.
  Diagnostic atStart{Severity::Error, SourceSpan{&file, 0, 3}, "x"};
  EXPECT_EQ(formatDiagnostic(atStart), "long.cell:1:1: error: x\n" + std::string(80, 'a') + "…\n^~~\n");
  // At the end, on the left only.
  Diagnostic atEnd{Severity::Error, SourceSpan{&file, 100000, 100000}, "x"};
  EXPECT_EQ(formatDiagnostic(atEnd), "long.cell:1:100001: error: x\n…" + std::string(80, 'b') + "\n " +
                                         std::string(80, ' ') + "^\n");
}

TEST(Diagnostics, InvalidBytesAndControlCharactersAreEchoedAsQuestionMarks) {
  SourceFile file("bad.cell", "A\xFF\x01 \xCF\x81 B");
  Diagnostic d{Severity::Error, SourceSpan{&file, 7, 8}, "x"};
  EXPECT_EQ(formatDiagnostic(d), "bad.cell:1:8: error: x\nA?? \xCF\x81 B\n      ^\n");
}

TEST(Diagnostics, SinkStopsKeepingAtItsErrorLimit) {
  DiagnosticSink sink(3);
  for (int i = 0; i < 100000; ++i) sink.error({}, "e" + std::to_string(i));
  EXPECT_EQ(sink.errorCount(), 3);
  EXPECT_TRUE(sink.limitReached());
  EXPECT_EQ(sink.diagnostics().size(), 3u);
  EXPECT_EQ(sink.droppedCount(), 99997);
  EXPECT_EQ(sink.diagnostics()[2].message, "e2");
  EXPECT_EQ(sink.errorsReported(), 100000);  // dropped ones too: a step that failed says so
  DiagnosticSink unlimited(0);
  for (int i = 0; i < 1000; ++i) unlimited.error({}, "e");
  EXPECT_EQ(unlimited.errorCount(), 1000);
  EXPECT_FALSE(unlimited.limitReached());
  EXPECT_EQ(DiagnosticSink().maxErrors(), kDefaultMaxErrors);
}

TEST(Diagnostics, SinkStreamsEachKeptDiagnosticAsItComes) {
  DiagnosticSink sink(2);
  std::vector<std::string> seen;
  sink.streamTo([&](const Diagnostic& d) { seen.push_back(d.message); });
  sink.error({}, "a");
  EXPECT_EQ(seen, std::vector<std::string>{"a"});
  sink.note({}, "b");
  sink.error({}, "c");
  sink.error({}, "dropped");
  EXPECT_EQ(seen, (std::vector<std::string>{"a", "b", "c"}));
}

TEST(SourceFile, AByteOrderMarkAtTheStartIsDropped) {
  SourceFile file("f", "\xEF\xBB\xBFlsystem a");
  EXPECT_EQ(file.text(), "lsystem a");
  EXPECT_EQ(file.columnOf(0), 1);
}

}  // namespace
}  // namespace ontogen
