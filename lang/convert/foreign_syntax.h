#pragma once
// The notation cpfg and L-Py share, read into cell-language text: module strings
// (`F(2)+[A]`, modules written without spaces), the expressions in their parameters and
// conditions (C's in cpfg, Python's in L-Py), and productions
// `left < predecessor > right : condition --> successors : probability`. Every position
// is a byte offset into the whole file, so errors name the file, line and column.

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "lang/convert/lsystem_file.h"

namespace ontogen::convert {

/// Why a file cannot be converted, at bytes [begin, end) of it.
struct ConvertError {
  uint32_t begin = 0;
  uint32_t end = 0;
  std::string message;
  bool untranslatable = true;  ///< true: a construct ontogen cannot express (code); false: malformed text
};

class ForeignSyntax {
 public:
  ForeignSyntax(Dialect dialect, std::string_view text) : dialect_(dialect), text_(text) {}

  /// L-Py's `module Name` declarations: names read as one module, not letter by letter.
  std::set<std::string, std::less<>> declaredNames;

  /// The modules of text [begin, end); `pattern`: a predecessor or context, whose
  /// parameters are names. Throws ConvertError.
  std::vector<ModuleText> modules(uint32_t begin, uint32_t end, bool pattern) const;
  /// An expression of the dialect as a cell-language expression. Throws ConvertError.
  std::string expression(uint32_t begin, uint32_t end) const;
  /// The labels of an `ignore:` or `consider:` list.
  std::vector<std::string> symbols(uint32_t begin, uint32_t end) const;
  /// A production of [begin, end), which holds an arrow (`-->` or `->`).
  Statement production(uint32_t begin, uint32_t end) const;

  /// A predecessor the cell language can write: one module of a label, not L-Py's
  /// wildcard `*` or alternatives. Throws ConvertError at [begin, end).
  void checkPredecessor(const ModuleText& predecessor, uint32_t begin, uint32_t end) const;

  /// [begin, end) without the spaces at its ends.
  void trim(uint32_t& begin, uint32_t& end) const;
  /// The first `what` in [begin, end) outside parentheses, or `end`.
  uint32_t find(uint32_t begin, uint32_t end, std::string_view what) const;

  [[noreturn]] void fail(uint32_t begin, uint32_t end, std::string message, bool untranslatable = true) const;

 private:
  uint32_t moduleEnd(uint32_t at, uint32_t end, std::string& label) const;
  std::optional<std::string> conditional(uint32_t begin, uint32_t end) const;

  Dialect dialect_;
  std::string_view text_;
};

}  // namespace ontogen::convert
