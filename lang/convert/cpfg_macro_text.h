#pragma once
// cpfg reads its files through the C preprocessor, which replaces a macro's call by its
// value as text: `#define rot(x) 3000*func(5,x)*dx` makes `phi+rot(x)` the text
// `phi+3000*func(5,x)*dx`. The converter puts a call in as its parenthesised value; the
// two read alike where the operators around the call bind more loosely than the value's
// loosest (C's operators of one level group from the left, so one of that level after
// the call reads alike too). This says where.

#include <functional>
#include <string_view>

namespace ontogen::convert {

/// Whether C's text `before value after` reads as `before (value) after`: `before` is
/// the text of the expression before the call, `after` the text after it. A value with
/// `?:`, or naming a macro whose own value is no single operand (`isCompound`), is
/// never taken to.
bool replacementReadsAsParenthesised(std::string_view value, std::string_view before, std::string_view after,
                                     const std::function<bool(std::string_view name)>& isCompound);

}  // namespace ontogen::convert
