#pragma once
// L-Py's hooks around the derivation, Python functions the L-system calls at its start
// (`Start`), before and after each step (`StartEach`, `EndEach`), at its end (`End`) and
// around the interpretation (`StartInterpretation`, `EndInterpretation`, `PostDraw`),
// read for what the cell language can say of them:
//
//   def Start():                      global values set once: #define
//     global n; n = 3
//   def StartEach():                  the active group of each step: use group:
//     if getIterationNb() % 5 == 0: useGroup(2)
//     else: useGroup(1)
//     global k; k += 1                a counter, or a value of getIterationNb():
//                                     an expression of `time` where it is read
//
// `print`, `pass` and `frameDisplay` change no word and are read over, `assert` with a
// warning at its place (the block does not check it);
// `seed(N)` in `Start` is the block's seed; `backward()` and `forward()` called on every
// step are the direction the block's `>>` or `<<` already gives. Anything else in a hook
// is a located error: state carried from step to step (a value that reads its value of
// the step before, a way that calls no useGroup), the word itself (`lstring`), `return`,
// and Python the bodies of productions do not take either.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lang/convert/foreign_syntax.h"
#include "lang/convert/lsystem_file.h"
#include "lang/convert/python_body.h"

namespace ontogen::convert {

/// One hook of the file: `def NAME(parameters):` at [begin, end) and its body.
struct HookText {
  std::string name;
  uint32_t begin = 0;
  uint32_t end = 0;
  std::vector<std::string> parameters;  ///< `lstring`, `scene`, ...: what the hook must not read
  std::vector<BodyLine> body;
};

/// The names L-Py calls as hooks.
bool isLPyHook(std::string_view name);

/// A global a hook sets, as the block reads it.
struct HookValue {
  std::string value;  ///< a cell-language expression
  SourceRange origin;
};

/// What the hooks give the converted block.
struct HookEffects {
  /// Globals of one value for the whole run (set by Start, or by StartEach to a value of
  /// constants): #defines, in place of the file's own of the same name.
  std::map<std::string, HookValue, std::less<>> defines;
  /// Globals StartEach sets to a value that changes from step to step: expressions of
  /// `time` as a production reads them (its `time` is the step it makes, from 1).
  std::map<std::string, HookValue, std::less<>> stepValues;
  std::optional<HookValue> useGroup;  ///< `use group:`, an expression of `time` (from 0)
  std::optional<HookValue> seed;
  /// backward() (true) or forward() called on every step: the direction, which the block's
  /// productions must agree with.
  std::optional<std::pair<bool, SourceRange>> backward;
};

/// The effects of `hooks`; `initial` holds the file's top-level constants as the block
/// reads them (a counter starts from its value). Throws ConvertError at what a hook does
/// that the block cannot say.
HookEffects translateHooks(ForeignSyntax& syntax, std::string_view text, const std::vector<HookText>& hooks,
                           const std::map<std::string, std::string, std::less<>>& initial);

/// `text` (a cell-language expression) with each name in `values` (as cellName spells
/// it) replaced by its value in parentheses, except the names in `bound` (the
/// production's parameters); `replaced` tells whether any was.
std::string withHookValues(const std::string& text, const std::map<std::string, HookValue, std::less<>>& values,
                           const std::vector<std::string>& bound, bool* replaced = nullptr);

}  // namespace ontogen::convert
