// ABOP prints `F -> FF-[-F+F+F]`; the cell language reads `FF` as one module named FF.
// A successor or axiom module whose multi-letter label nothing defines, while each of its
// letters is a symbol of the block, was most likely meant as that run of letters: warn,
// and say how to write it.

#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "lang/compile_stages.h"

namespace ontogen::detail {

namespace {

// The characters of a label, UTF-8 sequences kept whole.
std::vector<std::string> charactersOf(std::string_view label) {
  std::vector<std::string> characters;
  for (size_t at = 0; at < label.size();) {
    size_t end = at + 1;
    while (end < label.size() && (static_cast<unsigned char>(label[end]) & 0xC0) == 0x80) ++end;
    characters.emplace_back(label.substr(at, end - at));
    at = end;
  }
  return characters;
}

// A set that accepts any name (trace) says nothing about which names are commands.
bool isCommand(const CompileContext& ctx, const std::string& label) {
  for (const auto& set : ctx.options.commandSets)
    if (set.find("\x01") == nullptr && set.find(label) != nullptr) return true;
  return false;
}

void warnInSystem(CompileContext& ctx, const ast::System& system) {
  std::set<std::string> defined;  // labels something gives meaning to
  std::set<std::string> letters;  // one-character symbols of the block
  auto note = [&](const ast::Module& module) {
    if (charactersOf(module.label).size() == 1) letters.insert(module.label);
  };
  for (const auto& rule : system.productions) {
    defined.insert(rule.predecessor.label);
    note(rule.predecessor);
    for (const auto& side : {&rule.left, &rule.right})
      for (const auto& module : *side) note(module);
    for (const auto& module : rule.successors) note(module);
  }
  for (const auto& module : system.axiom) note(module);
  for (const auto& function : system.functions) defined.insert(function.name);
  for (const auto& interpretation : system.interpretations) defined.insert(interpretation.symbol);
  for (const auto& equiv : system.equivs) defined.insert(equiv.symbol);
  for (const auto& equiv : ctx.tree.equivs) defined.insert(equiv.symbol);
  for (const auto& cell : ctx.tree.cells) defined.insert(cell.name);
  for (const auto& other : ctx.tree.systems) defined.insert(other.name);

  auto check = [&](const ast::Module& module) {
    const std::vector<std::string> characters = charactersOf(module.label);
    if (characters.size() < 2 || defined.count(module.label) || isCommand(ctx, module.label)) return;
    for (const auto& character : characters)
      if (!letters.count(character) && !isCommand(ctx, character)) return;
    std::string spaced;
    for (const auto& character : characters) spaced += (spaced.empty() ? "" : " ") + character;
    ctx.sink.warning(module.span, "'" + module.label + "' is one module named " + module.label +
                                      ", which nothing defines; for the symbols " + spaced + " write '" + spaced +
                                      "', or put #letters in the block to read every letter as a module");
  };
  for (const auto& rule : system.productions)
    for (const auto& module : rule.successors) check(module);
  for (const auto& module : system.axiom) check(module);
}

}  // namespace

void warnLetterRuns(CompileContext& ctx) {
  for (const auto& system : ctx.tree.systems)
    if (system.isLSystem) warnInSystem(ctx, system);
}

}  // namespace ontogen::detail
