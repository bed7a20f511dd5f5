#pragma once
// The modules cpfg and L-Py predefine, and what each becomes in the cell language: one
// table, read by the converter's module reader for labels, '@' names and their fates.

#include <span>
#include <string_view>

#include "lang/convert/lsystem_file.h"

namespace ontogen::convert {

// What a predefined module of cpfg or L-Py becomes. A turtle command ontogen has is
// translated to it; a drawing command it has not stays a module of a name (the word is the
// other tool's), with a warning that it draws nothing; a query whose parameters ontogen
// would not fill is refused, as the word would differ.
enum class Fate { Translate, Inert, Refuse };
/// One module of the table.
struct Predefined {
  std::string_view name;  ///< as the file writes it
  std::string_view cell;  ///< Translate: the cell-language label; Inert: the module's name
  Fate fate;
  bool lpyOnly = true;    ///< a name of L-Py alone (cpfg's modules are one character or '@' names)
  bool cpfgOnly = false;  ///< a name of cpfg alone
};

/// Whether `p` is a module of `dialect`.
bool inDialect(const Predefined& p, Dialect dialect);
/// The predefined module of `dialect` named `name`, or nullptr.
const Predefined* predefined(std::string_view name, Dialect dialect);
/// The whole table, both dialects' modules.
std::span<const Predefined> predefinedModules();

}  // namespace ontogen::convert
