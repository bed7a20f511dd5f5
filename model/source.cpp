#include "model/source.h"

#include <algorithm>

#include "model/utf8.h"

namespace ontogen {

SourceFile::SourceFile(std::string name, std::string text)
    : name_(std::move(name)), text_(std::move(text)) {
  // Editors that write a byte-order mark hide it; columns count from after it.
  if (text_.starts_with(kUtf8ByteOrderMark)) text_.erase(0, kUtf8ByteOrderMark.size());
  lineStarts_.push_back(0);
  for (uint32_t i = 0; i < text_.size(); ++i)
    if (text_[i] == '\n') lineStarts_.push_back(i + 1);
}

int SourceFile::lineOf(uint32_t offset) const {
  auto it = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
  return static_cast<int>(it - lineStarts_.begin());
}

int SourceFile::columnOf(uint32_t offset) const {
  int line = lineOf(offset);
  return static_cast<int>(offset - lineStarts_[line - 1]) + 1;
}

std::string_view SourceFile::lineText(int line) const {
  if (line < 1 || line > static_cast<int>(lineStarts_.size())) return {};
  uint32_t begin = lineStarts_[line - 1];
  uint32_t end = line < static_cast<int>(lineStarts_.size()) ? lineStarts_[line] : text_.size();
  std::string_view view(text_.data() + begin, end - begin);
  while (!view.empty() && (view.back() == '\n' || view.back() == '\r')) view.remove_suffix(1);
  return view;
}

SourceSpan SourceSpan::to(const SourceSpan& other) const {
  if (!valid()) return other;
  if (!other.valid()) return *this;
  return {file, std::min(begin, other.begin), std::max(end, other.end)};
}

}  // namespace ontogen
