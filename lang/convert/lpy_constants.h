#pragma once
// L-Py's top-level constants read where the converter needs a number to write
// something out (`for i in range(N)`, a choice `randint(1, N)`): the number is written
// out, turn by turn or choice by choice, so the constant may not change apart from it.
// Such a constant is written in place of its name everywhere in the block, with no
// #define (`--define N=...` then says the program has none, where it would have changed
// the other uses and not the turns), and a hook that sets it is a located error.

#include <map>
#include <string>

#include "lang/convert/foreign_syntax.h"
#include "lang/convert/lpy_hooks.h"
#include "lang/convert/lsystem_file.h"

namespace ontogen::convert {

/// Records the top-level constant `name` = `value` (a cell-language expression) among
/// ForeignSyntax::fileConstants where its value is a number of written numbers and
/// constants recorded before; a name set again is no constant of one value.
void recordFileConstant(ForeignSyntax& syntax, const std::string& name, const std::string& value);

/// Python's top-level `NAME = value` for a NAME the file set before (or `NAME op= value`,
/// `op` not '='), `value` a cell-language expression, at `line`: the later value in
/// place of the earlier #define (the productions read it when they run), the earlier
/// value put in where `value` reads NAME. Throws ConvertError at `line` where the file's
/// values, axiom or derivation length read NAME between the two (Python read the earlier
/// value there); false where NAME was not set before.
bool setAgain(ForeignSyntax& syntax, LSystemFile& file, const std::string& name, char op, const std::string& value,
              SourceRange line);

/// Throws ConvertError at the first use of a fixed constant that a hook sets (its value
/// would change where the turns written out do not).
void checkFixedConstantsAgainstHooks(const ForeignSyntax& syntax, const HookEffects& effects);

/// Writes each fixed constant's number in place of its name in `file` (not where a
/// production's parameter of that name hides it) and leaves out its #define.
void writeFixedConstantsInPlace(const ForeignSyntax& syntax, LSystemFile& file);

}  // namespace ontogen::convert
