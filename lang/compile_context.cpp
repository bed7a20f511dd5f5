#include "lang/compile_context.h"

#include <algorithm>
#include <cmath>

#include "model/builtins.h"

namespace ontogen::detail {

namespace {

bool isTimeName(std::string_view name) {
  return name == "time";
}

}  // namespace

bool isAgeName(std::string_view name) {
  return name == "age" || name == "tau" || name == "τ";
}

bool isTerminalAgeName(std::string_view name) {
  return name == "beta" || name == "β" || name == "lifetime";
}

bool isReadOnlyName(std::string_view name) {
  return isAgeName(name) || isTerminalAgeName(name) || isTimeName(name) || name == "status" || name == "id";
}

int internalSlot(std::string_view name) {
  if (isAgeName(name) || name == "me.age") return FrameSlot::kAge;
  if (isTerminalAgeName(name)) return FrameSlot::kTerminalAge;
  if (isTimeName(name)) return FrameSlot::kTime;
  if (name == "id" || name == "me.id") return FrameSlot::kId;
  if (name == "me.x") return FrameSlot::kX;
  if (name == "me.y") return FrameSlot::kY;
  if (name == "me.z") return FrameSlot::kZ;
  if (name == "me.parent") return FrameSlot::kParent;
  return -1;
}

std::string where(const SourceSpan& span) {
  if (!span.file) return "?";
  const std::string& name = span.file->name();
  return name.substr(name.find_last_of('/') + 1) + ":" + std::to_string(span.line());
}

std::optional<double> ConstantScope::find(std::string_view name) const {
  if (auto it = values.find(name); it != values.end()) return it->second;
  if (outer) return outer->find(name);
  if (name == "π") return M_PI;
  if (const BuiltinConstant* constant = findConstant(name)) return constant->value;
  return std::nullopt;
}

int Scope::findFunction(std::string_view name) const {
  if (auto it = functions.find(name); it != functions.end()) return it->second;
  return outer ? outer->findFunction(name) : -1;
}

const std::string* Scope::findEquiv(std::string_view symbol) const {
  if (auto it = equivs.find(symbol); it != equivs.end()) return &it->second;
  return outer ? outer->findEquiv(symbol) : nullptr;
}

const Scope& CompileContext::scopeOf(const MasterCell& master) const {
  return master.scope >= 0 ? *scopes[master.scope] : global;
}

// ---- name lookups ----

NameLookup CompileContext::constantLookup(const Scope& scope) const {
  NameLookup names;
  names.constant = [&scope](std::string_view name) { return scope.constants.find(name); };
  return names;
}

void CompileContext::addFunctions(NameLookup& names, const Scope& scope) const {
  names.function = [&scope](std::string_view name) { return scope.findFunction(name); };
  names.functionArity = [this](int index) { return program->functions[index].arity; };
}

NameLookup CompileContext::frameLookup(const SlotMap& slots, int stateCount, const Scope& scope) {
  NameLookup names = constantLookup(scope);
  names.slot = [this, &slots, stateCount](std::string_view name) -> int {
    if (auto it = slots.find(name); it != slots.end()) return it->second;
    int internal = internalSlot(name);
    if (internal >= FrameSlot::kX && internal <= FrameSlot::kZ) readsPosition = true;
    if (internal == FrameSlot::kParent) readsParent = true;
    return internal < 0 ? -1 : stateCount + internal;
  };
  addFunctions(names, scope);
  names.ancestor = [this](const std::string& path, SourceSpan span) { return registerAncestor(path, span); };
  names.unknownHint = [](std::string_view) { return std::string(); };
  return names;
}

int CompileContext::registerAncestor(const std::string& path, SourceSpan span) {
  std::vector<std::string> parts;
  for (size_t begin = 0;;) {
    size_t dot = path.find('.', begin);
    parts.push_back(path.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin));
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  AncestorRef ref;
  ref.name = parts.back();
  bool valid = parts.size() >= 2;
  if (parts[0] == "root") {
    ref.level = 0;
    valid = valid && parts.size() == 2;
  } else {
    ref.level = static_cast<int>(parts.size()) - 1;
    for (size_t i = 0; i + 1 < parts.size(); ++i) valid = valid && parts[i] == "parent";
  }
  if (!valid || ref.name == "parent" || ref.name == "root" || ref.name == "me") {
    if (reportedAncestors.insert(span.begin).second)
      sink.error(span, "'" + path + "': read an enclosing system as 'parent.x', 'parent.parent.x' or 'root.x'");
    return 0;
  }
  auto found = std::find(program->ancestorRefs.begin(), program->ancestorRefs.end(), ref);
  const int index = static_cast<int>(found - program->ancestorRefs.begin());
  if (found == program->ancestorRefs.end()) program->ancestorRefs.push_back(ref);
  if (reportedAncestors.insert(span.begin).second) ancestorReads.push_back({reader, ref, path, span});
  return index;
}

// ---- masters ----

int CompileContext::addMaster(std::string label, int scope, SourceSpan span) {
  MasterCell master;
  master.label = std::move(label);
  master.scope = scope;
  master.span = span;
  const int index = static_cast<int>(program->masters.size());
  mastersByLabel[master.label].push_back(index);
  program->masters.push_back(std::move(master));
  arityKnown.push_back(false);
  return index;
}

int CompileContext::findMaster(std::string_view label, int scope) const {
  const auto found = mastersByLabel.find(label);
  if (found == mastersByLabel.end()) return -1;
  int outside = -1;  // the global master of that label, if the scope has none
  for (int i : found->second) {
    if (program->masters[i].scope == scope) return i;
    if (program->masters[i].scope == -1) outside = i;
  }
  return outside;
}

void CompileContext::declareState(const std::vector<ast::Parameter>& state, int index) {
  std::set<std::string> seen;
  for (const auto& param : state) {
    if (!seen.insert(param.name).second) sink.error(param.span, "state variable '" + param.name + "' appears twice");
    if (isReadOnlyName(param.name))
      sink.error(param.span, "'" + param.name + "' is the cell's read-only internal state; choose another name");
    double value = 0;
    if (param.defaultValue) {
      auto constant = evaluateConstant(*param.defaultValue, constantLookup(global), sink, "a default value");
      if (constant) value = *constant;
    }
    program->masters[index].stateNames.push_back(param.name);
    program->masters[index].defaults.push_back(value);
  }
}

// In an lsystem (scope >= 0) a symbol it has not seen becomes its own master, except a
// declared top-level `cell` named in a successor or the axiom: that means the cell, with
// its interpret blocks. A predecessor is always the lsystem's own (its productions must
// not change a cell other systems share); predecessors are resolved first, so a label
// with a production stays local throughout the block.
int CompileContext::resolveModule(const ast::Module& module, int scope, bool predecessor) {
  int count = static_cast<int>(module.args.size());
  int index = findMaster(module.label, scope);
  if (scope >= 0 && index >= 0 && program->masters[index].scope == scope) {
    // In an L-system, as in L-Py, `A`, `A(x)` and `A(x, y)` are modules of their own.
    index = -1;
    for (int i : mastersByLabel.find(module.label)->second) {
      const MasterCell& candidate = program->masters[i];
      if (candidate.scope == scope && (!arityKnown[i] || static_cast<int>(candidate.stateCount()) == count)) {
        index = i;
        break;
      }
    }
    if (index < 0) index = addMaster(module.label, scope, module.span);
  }
  const bool sharedCell = index >= 0 && !predecessor && program->masters[index].declared;
  if (index < 0 || (scope >= 0 && program->masters[index].scope != scope && !sharedCell))
    index = addMaster(module.label, scope, module.span);
  MasterCell& master = program->masters[index];
  if (module.age) master.timedNotation = true;
  if (!arityKnown[index]) {
    arityKnown[index] = true;
    master.span = module.span;
    for (int i = 0; i < count; ++i) {
      std::string name = "p" + std::to_string(i + 1);
      if (module.args[i]->kind == ast::Expr::Kind::Name) name = module.args[i]->name;
      master.stateNames.push_back(name);
      master.defaults.push_back(0);
    }
  } else if (master.declared && master.scope == -1) {
    if (count > static_cast<int>(master.stateCount()))
      sink.error(module.span, "cell '" + master.label + "' has " + std::to_string(master.stateCount()) +
                                  " state variable" + (master.stateCount() == 1 ? "" : "s") + ", given " +
                                  std::to_string(count));
  } else if (count != static_cast<int>(master.stateCount())) {
    sink.error(module.span, "'" + master.label + "' has " + std::to_string(master.stateCount()) + " parameter" +
                                (master.stateCount() == 1 ? "" : "s") + " elsewhere (first at line " +
                                std::to_string(master.span.line()) + "), but " + std::to_string(count) + " here");
  }
  return index;
}

}  // namespace ontogen::detail
