#pragma once
// Source text and locations. Every token and AST node carries a SourceSpan, so that
// every diagnostic can name file:line:col and underline the offending text.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace ontogen {

/// A program text with its name (a path or "<string>") and an index of line starts. A
/// UTF-8 byte-order mark at the start is dropped: offsets count from after it.
class SourceFile {
 public:
  SourceFile(std::string name, std::string text);

  const std::string& name() const { return name_; }
  const std::string& text() const { return text_; }

  /// 1-based line number of a byte offset.
  int lineOf(uint32_t offset) const;
  /// 1-based column (in bytes) of a byte offset.
  int columnOf(uint32_t offset) const;
  /// The text of a 1-based line, without its line break.
  std::string_view lineText(int line) const;

 private:
  std::string name_;
  std::string text_;
  std::vector<uint32_t> lineStarts_;
};

/// A half-open byte range [begin, end) in one source file.
struct SourceSpan {
  const SourceFile* file = nullptr;
  uint32_t begin = 0;
  uint32_t end = 0;

  bool valid() const { return file != nullptr; }
  int line() const { return file ? file->lineOf(begin) : 0; }
  int column() const { return file ? file->columnOf(begin) : 0; }
  /// The smallest span covering both.
  SourceSpan to(const SourceSpan& other) const;
};

}  // namespace ontogen
