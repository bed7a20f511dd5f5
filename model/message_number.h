#pragma once
// How a message writes a number: every diagnostic, run-time error and warning formats its
// numbers here, so that none prints printf's `-nan` (a NaN's sign bit, which means
// nothing to a reader) or another spelling of an infinity. Non-finite values read as the
// language writes them: `inf`, `-inf` and `NaN` (docs/LANGUAGE.md 7).

#include <string>

namespace ontogen {

/// Significant digits of a number in a message, as printf's %g gives them.
inline constexpr int kMessageDigits = 6;
/// Asks messageNumber for the fewest digits that read back as the same double.
inline constexpr int kShortestDigits = 0;

/// `value` as a message writes it: `inf`, `-inf` or `NaN` when it is not finite, else in
/// `significantDigits` significant digits as printf's %g writes them (`1e+302`, `0.5`), or
/// the shortest text that reads back as `value` for kShortestDigits.
std::string messageNumber(double value, int significantDigits = kMessageDigits);

}  // namespace ontogen
