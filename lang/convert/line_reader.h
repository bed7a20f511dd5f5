#pragma once
// cpfg's and L-Py's files are read line by line: a line's keyword (`Axiom:`,
// `derivation length:`), matched without regard to case, and the rest of the line.

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace ontogen::convert {

/// One line of a file: bytes [begin, end) without the line break.
struct Line {
  uint32_t begin = 0;
  uint32_t end = 0;
};

/// The lines of a text.
std::vector<Line> splitLines(std::string_view text);

/// When line (from its first non-space character) starts with `keyword`, ignoring case,
/// the offset just after it; otherwise nothing. A keyword that ends in a letter must not
/// run on into a name: `group` does not start `groups`.
std::optional<uint32_t> afterKeyword(std::string_view text, Line line, std::string_view keyword);

/// Like afterKeyword for a keyword written before a colon, `Axiom:` or `Axiom :` (the
/// tools allow spaces before it): the offset just after the colon.
std::optional<uint32_t> afterLabel(std::string_view text, Line line, std::string_view keyword);

/// The offset of the line's first non-space character (its end for a blank line).
uint32_t firstNonSpace(std::string_view text, Line line);

}  // namespace ontogen::convert
