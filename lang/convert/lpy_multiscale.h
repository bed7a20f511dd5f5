#pragma once
// L-Py's multiscale modules for `ontogen convert`: `module A, B : scale = N` declares
// modules and their scale, and the option 'String matching' set to 'As Multiscale
// AxialTree' (3) or 'As Multi-level AxialTree' (2) makes contexts match at those scales
// or levels. The block gets `scale N: A B` or `level N: A B` lines where the file
// matches so; with L-Py's default matching (an axial tree) scales change no match, and
// only the names are declared.

#include <cstdint>
#include <string_view>

#include "lang/convert/foreign_syntax.h"
#include "lang/convert/lsystem_file.h"

namespace ontogen::convert {

/// `module A, B(x) : scale = N`, the text [at, end) after `module` with its colon at
/// `colon`, read from `line`: declares the names and keeps their scale in `file`. Other
/// attributes (`base = A`, a module matching as another) throw ConvertError at their
/// place.
void declareScaled(ForeignSyntax& syntax, std::string_view clean, uint32_t at, uint32_t colon, uint32_t end,
                   SourceRange line, LSystemFile& file);

/// Whether `value`, the digit the option 'String matching' is set to, is 3 (multiscale)
/// or 2 (multi-level): then `file` matches its contexts at the declared scales or levels.
bool readsMultiscale(char value, LSystemFile& file);

}  // namespace ontogen::convert
