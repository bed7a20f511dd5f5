// Interpretation blocks: `interpret SET { ... }` in a cell, `interpret SET X(a) { ... }`
// in an L-system. Each instruction is checked against the set's commands (when the
// caller gives the sets, CompileOptions::commandSets) and its arguments compiled
// against the master's frame; and each master gets the command it stands for.

#include <map>
#include <optional>
#include <string>

#include "lang/compile_stages.h"
#include "lang/expression_compiler.h"

namespace ontogen::detail {

void compileInterpretation(CompileContext& ctx, const ast::Interpretation& block, int master,
                           const std::vector<std::string>* params, const Scope* scope) {
  InterpretationBlock compiled;
  compiled.setName = block.setName;
  compiled.span = block.span;
  const CommandSetInfo* set = nullptr;
  if (!ctx.options.commandSets.empty()) {
    for (const auto& candidate : ctx.options.commandSets)
      if (candidate.name == block.setName) set = &candidate;
    if (!set) {
      std::string known;
      for (const auto& candidate : ctx.options.commandSets) known += (known.empty() ? "" : ", ") + candidate.name;
      ctx.sink.error(block.span, "unknown interpretation set '" + block.setName + "' (known: " + known + ")");
      return;
    }
  }
  const MasterCell& self = ctx.program->masters[master];
  const Scope& lookupScope = scope ? *scope : ctx.global;
  std::map<std::string, int, std::less<>> slots;
  for (uint32_t i = 0; i < self.stateCount(); ++i)
    slots[params ? (*params)[i] : self.stateNames[i]] = static_cast<int>(i);
  ctx.reader = Reader{master, -1};
  ctx.readsParent = false;
  NameLookup names = ctx.frameLookup(slots, static_cast<int>(self.stateCount()), lookupScope);
  if (set && set->constant) {
    names.constant = [&lookupScope, set](std::string_view name) -> std::optional<double> {
      if (auto value = lookupScope.constants.find(name)) return value;
      return set->constant(name);
    };
  }
  for (const auto& module : block.instructions) {
    Instruction instruction;
    instruction.span = module.span;
    const std::string* equiv = lookupScope.findEquiv(module.label);
    instruction.command = equiv ? *equiv : module.label;
    if (set) {
      const CommandInfo* info = set->find(instruction.command);
      if (!info) {
        ctx.sink.error(module.span, "'" + module.label + "' is not a command of the '" + block.setName + "' set");
        continue;
      }
      int count = static_cast<int>(module.args.size());
      if (count < info->minArity || (info->maxArity >= 0 && count > info->maxArity)) {
        ctx.sink.error(module.span, "'" + module.label + "' takes " + std::to_string(info->minArity) +
                                        (info->maxArity == info->minArity ? ""
                                         : info->maxArity < 0             ? " or more"
                                                                          : " to " + std::to_string(info->maxArity)) +
                                        " arguments, given " + std::to_string(count));
        continue;
      }
      instruction.commandId = info->id;
    }
    for (const auto& arg : module.args) instruction.args.push_back(compileExpression(*arg, names, ctx.sink));
    compiled.instructions.push_back(std::move(instruction));
  }
  if (ctx.readsParent) ctx.program->masters[master].readsParent = true;
  ctx.program->masters[master].interpretations.push_back(std::move(compiled));
}

// `interpret SET X(a) { ... }` in an L-system: the block of the block's own symbol X,
// its parameters named as the pattern names them.
void compileSymbolInterpretations(CompileContext& ctx, const ast::System& system, const Scope& scope, int index) {
  for (const auto& item : system.interpretations) {
    int master = ctx.findMaster(item.symbol, index);
    // Of the block's modules with this label (one per number of parameters), the one
    // with as many parameters as the block names.
    for (size_t m = 0; m < ctx.program->masters.size(); ++m)
      if (ctx.program->masters[m].label == item.symbol && ctx.program->masters[m].scope == index &&
          ctx.program->masters[m].stateCount() == item.params.size())
        master = static_cast<int>(m);
    if (master < 0 || ctx.program->masters[master].scope != index) {
      ctx.sink.error(item.symbolSpan, "'" + item.symbol + "' is not a symbol of L-system '" + system.name + "'");
      continue;
    }
    const MasterCell& target = ctx.program->masters[master];
    if (item.params.size() != target.stateCount()) {
      ctx.sink.error(item.symbolSpan, "'" + item.symbol + "' has " + std::to_string(target.stateCount()) +
                                          " parameter" + (target.stateCount() == 1 ? "" : "s") + ", but " +
                                          std::to_string(item.params.size()) + " are named here");
      continue;
    }
    if (target.interpretation(item.block.setName)) continue;  // the first block counts
    compileInterpretation(ctx, item.block, master, &item.params, &scope);
  }
}

// The instruction each master stands for (its label, or the command an equiv names),
// and the brackets and cuts among them.
// With the sets known, each master's command is resolved in every set once, here.
void resolveCommands(CompileContext& ctx) {
  for (const auto& set : ctx.options.commandSets) ctx.program->commandSets.push_back(set.name);
  for (auto& master : ctx.program->masters) {
    const std::string* equiv = ctx.scopeOf(master).findEquiv(master.label);
    master.command = equiv ? *equiv : master.label;
    if (master.command == "[") master.symbolClass = kSymbolBranchOpen;
    if (master.command == "]") master.symbolClass = kSymbolBranchClose;
    // The cut of cpfg and L-Py acts in the next step: it lives one time unit, like an
    // untimed module, and then removes itself and the rest of its branch.
    if (master.command.size() == 2 && master.command[0] == '?') {
      master.query = master.command[1];
      if (master.stateCount() > 3)
        ctx.sink.error(master.span, "'" + master.label + "' answers 3 values (x, y, z); it takes at most 3 parameters");
      ctx.program->hasQueries = true;
    }
    if (master.command == "%") {
      master.symbolClass = kSymbolCut;
      if (!master.terminalRules.empty())
        ctx.sink.error(master.terminalRules.front().span, "'%' is the cut: it removes the rest of its branch and has no productions");
      master.lifetime = 1;
    }
    const unsigned char first = master.label.empty() ? 0 : static_cast<unsigned char>(master.label[0]);
    master.treeNode = master.symbolClass == kSymbolModule &&
                      ((first >= 'a' && first <= 'z') || (first >= 'A' && first <= 'Z') || first == '_' || first >= 0x80 ||
                       (first >= '0' && first <= '9'));  // digits: ABOP's labels under #letters
    master.commandIds.clear();
    for (const auto& set : ctx.options.commandSets) {
      const CommandInfo* info = set.find(master.command);
      master.commandIds.push_back(!info ? -1 : info->id >= 0 ? info->id : -2);
    }
  }
}

}  // namespace ontogen::detail
