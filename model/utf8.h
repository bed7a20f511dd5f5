#pragma once
// UTF-8 as the source must be: the lexer reports the first byte of a line that breaks
// it, and diagnostics echo a line one character per column whatever it holds.

#include <cstddef>
#include <string_view>

namespace ontogen {

/// The byte-order mark some editors put at the start of a UTF-8 file.
inline constexpr std::string_view kUtf8ByteOrderMark = "\xEF\xBB\xBF";

/// Bytes of the well-formed UTF-8 sequence starting at `text[at]` (1 to 4), or 0 when
/// none starts there: a stray continuation byte, a truncated sequence, an overlong
/// form, a surrogate or a code point above U+10FFFF (RFC 3629).
size_t utf8SequenceLength(std::string_view text, size_t at);

/// Offset of the first byte from `from` on that starts no well-formed sequence, or
/// text.size() when the rest is valid UTF-8.
size_t findInvalidUtf8(std::string_view text, size_t from = 0);

}  // namespace ontogen
