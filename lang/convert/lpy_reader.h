#pragma once
// The declarative part of L-Py's files (.lpy): `Axiom:`, `derivation length:`,
// `production:`, `decomposition:`, `homomorphism:` (or `interpretation:`),
// `maximum depth:`, `ignore:`, `consider:`, `group N:` / `endgroup`, `module` declarations,
// `#define`, `endlsystem`, productions `pred --> succ` and `pred : cond --> succ`, a
// production whose body is one `produce` line, and top-level constants `NAME = EXPR`.
// Other Python code is an error at its line. The `###### INITIALISATION ######`
// section the L-Py editor writes (materials, panels) ends what is read.

#include <cstdint>
#include <string_view>

#include "lang/convert/lsystem_file.h"
#include "lang/source_reader.h"

namespace ontogen::convert {

/// L-Py's turtle turns by 60 degrees unless told otherwise.
inline constexpr std::string_view kLPyDefaultAngle = "60";

/// Reads an L-Py file. Throws ConvertError (lang/convert/foreign_syntax.h) at the first
/// construct it cannot translate, and ConvertedTextTooLarge as soon as its text passes
/// `maxBytes`.
LSystemFile readLPy(std::string_view text, std::string_view path, uint64_t maxBytes = kDefaultMaxSourceBytes);

}  // namespace ontogen::convert
