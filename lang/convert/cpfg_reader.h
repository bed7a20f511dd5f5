#pragma once
// cpfg's L-system files (.l), as the Virtual Laboratory writes them: `Lsystem:`,
// `Seed:`, `derivation length:`, `Axiom:`, `#define`, `#ignore` / `ignore:`,
// `#consider` / `consider:`, `decomposition`, `homomorphism`, `maximum depth:`,
// `group`, productions `lc < pred > rc : cond --> succ : prob`, `endlsystem`, and
// `/* */` comments. Modules are one character each. The turn angle lives in the
// view file (.v): `angle increment: D` (degrees) or `angle factor: N` (360 / N), the
// last of them; 45 degrees when it has neither (cpfg's default).

#include <cstdint>
#include <optional>
#include <string_view>

#include "lang/convert/cpfg_function.h"
#include "lang/convert/lsystem_file.h"
#include "lang/source_reader.h"

namespace ontogen::convert {

/// Reads a cpfg file; `view` is the text of its view file, or nothing when there is none:
/// the first turn without an angle then warns that it turns by ontogen's default, where
/// cpfg would have the view file's. `readSideFile` gives
/// the function files the view file names (cpfg_function.h), or is empty. Throws
/// ConvertError (lang/convert/foreign_syntax.h) at the first construct it cannot
/// translate, and ConvertedTextTooLarge as soon as its text passes `maxBytes`.
LSystemFile readCpfg(std::string_view text, std::string_view path, std::optional<std::string_view> view,
                     const SideFileReader& readSideFile = {}, uint64_t maxBytes = kDefaultMaxSourceBytes);

}  // namespace ontogen::convert
