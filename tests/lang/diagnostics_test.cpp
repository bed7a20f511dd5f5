#include "lang/diagnostics.h"

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

}  // namespace
}  // namespace ontogen
