#pragma once
// L-Py's imports at the top level of a file. `import math`, `import random as rd`,
// `from math import *` give the names the converter translates (`rd.uniform` is
// `uniform`); another module's import is read over where the names it binds mean
// nothing to the converter (read later, they are unknown names or attributes, located).
// An import that binds `math` or `random` to another module, a name the converter
// translates from another module, or `from M import *` of a module whose names it cannot
// know is refused at its place.

#include <cstdint>
#include <string_view>

#include "lang/convert/foreign_syntax.h"

namespace ontogen::convert {

/// Whether the line [begin, end) of `text` is an import, read (module aliases recorded in
/// `syntax`). Throws ConvertError at an import it refuses.
bool readImport(ForeignSyntax& syntax, std::string_view text, uint32_t begin, uint32_t end);

}  // namespace ontogen::convert
