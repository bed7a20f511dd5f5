#include "lang/convert/lpy_globals.h"

#include <algorithm>
#include <string>
#include <string_view>

#include "lang/convert/foreign_text.h"

namespace ontogen::convert {

namespace {

using chars::isNameChar;

// Whether the cell-language text names `name` (a whole name, not a part of one).
bool names(std::string_view text, std::string_view name) {
  for (size_t at = text.find(name); at != std::string_view::npos; at = text.find(name, at + 1)) {
    const size_t after = at + name.size();
    if ((at == 0 || (!isNameChar(text[at - 1]) && text[at - 1] != '.')) &&
        (after == text.size() || !isNameChar(text[after])))
      return true;
  }
  return false;
}

bool anyNames(const std::vector<ModuleText>& word, std::string_view name) {
  for (const ModuleText& m : word)
    for (const std::string& arg : m.args)
      if (names(arg, name)) return true;
  return false;
}

// Whether anything of the converted file but the global's own constants reads `name`.
bool read(const LSystemFile& file, const ForeignSyntax& syntax, std::string_view name) {
  if (anyNames(file.axiom, name)) return true;
  for (const std::optional<std::string>* value : {&file.derivationLength, &file.useGroup, &file.seed, &file.angle})
    if (*value && names(**value, name)) return true;
  for (const Define& d : file.defines)
    if (cellName(d.name) != name && names(d.value, name)) return true;
  for (const auto& [array, elements] : syntax.arrays)
    for (const std::string& element : elements)
      if (names(element, name)) return true;
  for (const Statement& s : file.statements) {
    if (s.kind == StatementKind::MaximumDepth || s.kind == StatementKind::Group) {
      if (names(s.word, name)) return true;
      continue;
    }
    if (s.kind != StatementKind::Production) continue;
    if (names(s.condition, name) || names(s.probability, name) || anyNames(s.successors, name)) return true;
  }
  return false;
}

}  // namespace

void leaveOutUnreadBodyGlobals(const ForeignSyntax& syntax, LSystemFile& file) {
  for (const auto& [global, where] : syntax.bodyGlobals) {
    const std::string name = cellName(global);
    if (read(file, syntax, name))
      syntax.fail(where.begin, where.end,
                  "'" + global +
                      "' declared global and set in a production body, and read by the productions or the "
                      "block's values: state carried from production to production, which the converter does "
                      "not write");
    std::erase_if(file.defines, [&](const Define& d) { return cellName(d.name) == name; });
    syntax.warnings.push_back(
        {where, "'" + global +
                    "' set in a production body is read by nothing the word depends on (L-Py's hooks may assert "
                    "or print it, which the block does not check): the converter leaves it out"});
  }
}

}  // namespace ontogen::convert
