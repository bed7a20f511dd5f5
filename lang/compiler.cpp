#include "lang/compiler.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>

#include "lang/expression_compiler.h"
#include "lang/imports.h"
#include "lang/parser.h"
#include "lang/system_tree.h"

namespace ontogen {

int Program::findMaster(std::string_view label, int scope) const {
  int global = -1;
  for (size_t i = 0; i < masters.size(); ++i) {
    if (masters[i].label != label) continue;
    if (masters[i].scope == scope) return static_cast<int>(i);
    if (masters[i].scope == -1) global = static_cast<int>(i);
  }
  return global;
}

namespace {

// Names that read a cell's internal, read-only state.
bool isAgeName(std::string_view name) {
  return name == "age" || name == "tau" || name == "τ";
}
bool isTerminalAgeName(std::string_view name) {
  return name == "beta" || name == "β" || name == "lifetime";
}
bool isTimeName(std::string_view name) {
  return name == "time";
}
bool isReadOnlyName(std::string_view name) {
  return isAgeName(name) || isTerminalAgeName(name) || isTimeName(name) || name == "status" || name == "id";
}

// The slot of internal state a name reads, after the state values, or -1.
int internalSlot(std::string_view name) {
  if (isAgeName(name) || name == "me.age") return FrameSlot::kAge;
  if (isTerminalAgeName(name)) return FrameSlot::kTerminalAge;
  if (isTimeName(name)) return FrameSlot::kTime;
  if (name == "id" || name == "me.id") return FrameSlot::kId;
  if (name == "me.x") return FrameSlot::kX;
  if (name == "me.y") return FrameSlot::kY;
  if (name == "me.z") return FrameSlot::kZ;
  return -1;
}

/// Constants visible in a scope: the block's #defines, then the program's, then built-ins.
struct ConstantScope {
  std::map<std::string, double, std::less<>> values;
  const ConstantScope* outer = nullptr;

  std::optional<double> find(std::string_view name) const {
    if (auto it = values.find(name); it != values.end()) return it->second;
    if (outer) return outer->find(name);
    if (name == "π") return M_PI;
    if (const BuiltinConstant* constant = findConstant(name)) return constant->value;
    return std::nullopt;
  }
};

/// Everything a system block sees: constants, equivs, functions, its index.
struct Scope {
  int system = -1;  // -1: the program's top level
  ConstantScope constants;
  std::map<std::string, std::string, std::less<>> equivs;  // symbol -> command
  std::map<std::string, int, std::less<>> functions;       // name -> index
  const Scope* outer = nullptr;

  int findFunction(std::string_view name) const {
    if (auto it = functions.find(name); it != functions.end()) return it->second;
    return outer ? outer->findFunction(name) : -1;
  }
  const std::string* findEquiv(std::string_view symbol) const {
    if (auto it = equivs.find(symbol); it != equivs.end()) return &it->second;
    return outer ? outer->findEquiv(symbol) : nullptr;
  }
};

class Compiler {
 public:
  Compiler(const ast::Program& tree, DiagnosticSink& sink, const CompileOptions& options)
      : tree_(tree), sink_(sink), options_(options) {}

  std::unique_ptr<Program> run(std::vector<std::shared_ptr<const SourceFile>> sources) {
    program_ = std::make_unique<Program>();
    for (auto& source : sources) {
      sink_.retain(source);
      program_->sources.push_back(std::move(source));
    }
    global_.system = -1;
    takeOverrides();
    defines(tree_.defines, global_, -1);
    equivs(tree_.equivs, global_);
    settings(tree_.settings, globalSettings_, &global_);
    functions(tree_.functions, global_);
    declareCells();
    declareSystemCells();
    for (size_t i = 0; i < tree_.systems.size(); ++i) declareSystem(tree_.systems[i], static_cast<int>(i));
    checkOverrides();
    compileCells();
    for (size_t i = 0; i < tree_.systems.size(); ++i) compileSystem(tree_.systems[i], static_cast<int>(i));
    attachDevelopmentFunctions();
    finishMasters();
    if (!sink_.hasErrors()) {
      SystemTree tree(*program_);
      if (checkCycles(tree)) {
        for (size_t s = 0; s < program_->systems.size(); ++s)
          if (!tree.containers(static_cast<int>(s)).empty()) program_->hasSystemCells = true;
        chooseRoot(tree);
        checkAncestorReads(tree);
      }
    } else {
      chooseRoot(SystemTree(*program_));
    }
    if (sink_.hasErrors()) return nullptr;
    return std::move(program_);
  }

 private:
  // "file:line" of a declaration (the file's name without its folders), for messages
  // that name two places.
  static std::string where(const SourceSpan& span) {
    if (!span.file) return "?";
    const std::string& name = span.file->name();
    return name.substr(name.find_last_of('/') + 1) + ":" + std::to_string(span.line());
  }

  // ---- constants, equivs, settings, functions ----
  NameLookup constantLookup(const Scope& scope) {
    NameLookup names;
    names.constant = [&scope](std::string_view name) { return scope.constants.find(name); };
    return names;
  }

  // `system`: index of the block holding the list, -1 for the top level.
  void defines(const std::vector<ast::Define>& list, Scope& scope, int system) {
    for (const auto& define : list) {
      auto given = overrides_.find(define.name);
      if (given != overrides_.end()) overridden_.insert(define.name);
      if (scope.constants.values.count(define.name)) {
        sink_.error(define.span, "'" + define.name + "' is defined twice");
        continue;
      }
      if (findConstant(define.name) || findBuiltin(define.name)) {
        sink_.error(define.span, "'" + define.name + "' is a built-in name and cannot be redefined");
        continue;
      }
      // A value from outside replaces the text's, which is then not evaluated at all.
      std::optional<double> value;
      if (given != overrides_.end())
        value = given->second;
      else
        value = evaluateConstant(*define.value, constantLookup(scope), sink_, "the value of #define");
      if (!value) continue;
      scope.constants.values[define.name] = *value;
      program_->defines.push_back({define.name, *value, system, given != overrides_.end(), define.span});
    }
  }

  // The values given from outside, the last of each name (as later flags win on a
  // command line). A value that is not finite is reported and left out, so the text's
  // value stands and no error follows from it.
  void takeOverrides() {
    for (const DefineOverride& define : options_.defines) overrides_[define.name] = define.value;
    for (auto it = overrides_.begin(); it != overrides_.end();) {
      if (std::isfinite(it->second)) {
        ++it;
        continue;
      }
      sink_.error(SourceSpan{}, "cannot set '" + it->first + "' to " + std::to_string(it->second) +
                                    ": a value for a #define must be a finite number");
      it = overrides_.erase(it);
    }
  }

  // Every value given from outside must name a #define of the program.
  void checkOverrides() {
    std::string known;
    std::set<std::string_view> listed;
    for (const ProgramDefine& define : program_->defines)
      if (listed.insert(define.name).second) known += (known.empty() ? "" : ", ") + define.name;
    std::set<std::string_view> reported;
    for (const DefineOverride& given : options_.defines) {
      const std::string& name = given.name;
      if (!overrides_.count(name) || overridden_.count(name) || !reported.insert(name).second) continue;
      sink_.error(SourceSpan{}, "cannot set '" + name + "': the program has no #define " + name +
                                    (known.empty() ? " (it has no #define)" : " (it defines " + known + ")"));
    }
  }

  void equivs(const std::vector<ast::Equiv>& list, Scope& scope) {
    for (const auto& equiv : list) {
      if (scope.equivs.count(equiv.symbol)) {
        sink_.error(equiv.span, "'" + equiv.symbol + "' already has an equiv");
        continue;
      }
      scope.equivs[equiv.symbol] = equiv.command;
    }
  }

  void settings(const std::vector<ast::Setting>& list, InterpretSettings& target, const Scope* scope) {
    for (const auto& setting : list) {
      if (setting.name == "radians") {
        target.radians = true;
        continue;
      }
      if (setting.name == "degrees") {
        target.radians = false;
        continue;
      }
      if (setting.name == "music") {
        target.music.time = setting.word == "developmental" ? MusicTime::Developmental : MusicTime::Sequential;
        continue;
      }
      if (setting.name == "timesig") {
        target.music.timeSignatureNumerator = setting.numerator;
        target.music.timeSignatureDenominator = setting.denominator;
        continue;
      }
      auto value = evaluateConstant(*setting.value, constantLookup(*scope), sink_, "#" + setting.name);
      if (!value) continue;
      if (setting.name == "surface") {
        if (*value < 0 || *value > 1023 || *value != std::floor(*value)) {
          sink_.error(setting.span, "#surface takes a whole number 0 to 1023 before the file, as in #surface 1 \"bud.obj\"");
          continue;
        }
        SurfaceFile file{static_cast<int>(*value), setting.word, ""};
        if (setting.span.valid()) {
          const std::filesystem::path base = std::filesystem::path(setting.span.file->name()).parent_path();
          if (std::filesystem::path(file.path).is_relative()) file.path = (base / file.path).lexically_normal().string();
          file.location = setting.span.file->name() + ":" + std::to_string(setting.span.line()) + ":" +
                          std::to_string(setting.span.column());
        }
        target.surfaces.push_back(std::move(file));
        continue;
      }
      if (setting.name == "angle") {
        target.angle = *value;
        target.yawAngle = *value;
      } else if (setting.name == "yawangle") {
        target.yawAngle = *value;
      } else if (setting.name == "length") {
        target.step = *value;
      } else if (setting.name == "until") {
        if (!(*value > 0))
          sink_.error(setting.span, "#until must be greater than 0");
        else
          program_->until = *value;
      } else if (setting.name == "dt") {
        if (!(*value > 0))
          sink_.error(setting.span, "#dt must be greater than 0");
        else
          program_->dt = *value;
      } else if (setting.name == "tolerance") {
        if (!(*value > 0) || *value >= 1)
          sink_.error(setting.span, "#tolerance is between 0 and 1, as in 1e-6");
        else
          program_->rateTolerance = *value;
      } else if (setting.name == "tempo") {
        if (!(*value > 0) || *value > 1000)
          sink_.error(setting.span, "#tempo is in quarter notes per minute, above 0 and at most 1000");
        else
          target.music.tempo = *value;
      } else if (setting.name == "ppq") {
        if (*value < 1 || *value > 32767 || *value != std::floor(*value))
          sink_.error(setting.span, "#ppq must be a whole number of ticks per quarter note, 1 to 32767");
        else
          target.music.ppq = static_cast<int>(*value);
      } else if (setting.name == "midiformat") {
        if (*value != 0 && *value != 1)
          sink_.error(setting.span, "#midiformat must be 0 (one track) or 1 (a track per channel)");
        else
          target.music.format = static_cast<int>(*value);
      } else if (setting.name == "radius") {
        target.radius = *value;
      } else if (setting.name == "seed") {
        if (*value < 0 || *value != std::floor(*value)) {
          sink_.error(setting.span, "#seed must be a whole number ≥ 0");
          continue;
        }
        program_->seed = static_cast<uint64_t>(*value);
        program_->hasSeed = true;
      }
    }
  }

  void functions(const std::vector<ast::DevelopmentFunction>& list, Scope& scope) {
    // Declare first so that functions can call each other in any order.
    std::vector<int> indices;
    for (const auto& function : list) {
      if (scope.functions.count(function.name)) {
        sink_.error(function.span, "development function '" + function.name + "' is defined twice");
        indices.push_back(-1);
        continue;
      }
      if (findBuiltin(function.name)) {
        sink_.error(function.span, "'" + function.name + "' is a built-in function and cannot be redefined");
        indices.push_back(-1);
        continue;
      }
      DevelopmentFunction definition;
      definition.name = function.name;
      definition.arity = static_cast<int>(function.params.size());
      definition.span = function.span;
      int moduleParam = 0;
      for (const auto& param : function.params) {
        if (isAgeName(param.name))
          definition.sources.push_back(DevelopmentFunction::kFromAge);
        else if (isTerminalAgeName(param.name))
          definition.sources.push_back(DevelopmentFunction::kFromTerminalAge);
        else
          definition.sources.push_back(moduleParam++);
      }
      int index = static_cast<int>(program_->functions.size());
      program_->functions.push_back(std::move(definition));
      program_->functionBodies.emplace_back();
      scope.functions[function.name] = index;
      indices.push_back(index);
    }
    for (size_t i = 0; i < list.size(); ++i) {
      if (indices[i] < 0) continue;
      const auto& function = list[i];
      std::map<std::string, int, std::less<>> slots;
      for (size_t p = 0; p < function.params.size(); ++p) {
        if (slots.count(function.params[p].name))
          sink_.error(function.params[p].span, "parameter '" + function.params[p].name + "' appears twice");
        slots[function.params[p].name] = static_cast<int>(p);
      }
      NameLookup names = constantLookup(scope);
      names.slot = [&slots](std::string_view name) {
        auto it = slots.find(name);
        return it == slots.end() ? -1 : it->second;
      };
      addFunctions(names, scope);
      names.unknownHint = [](std::string_view name) -> std::string {
        if (isAgeName(name) || isTerminalAgeName(name))
          return "list it among the function's parameters, as in 'g mov(tau, beta) = ...'";
        return {};
      };
      program_->functionBodies[indices[i]] = compileExpression(*function.body, names, sink_);
    }
    checkRecursion();
  }

  void addFunctions(NameLookup& names, const Scope& scope) {
    names.function = [&scope](std::string_view name) { return scope.findFunction(name); };
    names.functionArity = [this](int index) { return program_->functions[index].arity; };
  }

  // A development function that calls itself, directly or not, would never return.
  void checkRecursion() {
    size_t count = program_->functions.size();
    std::vector<int> state(count, 0);  // 0 new, 1 on the path, 2 done
    std::function<bool(size_t)> visit = [&](size_t f) -> bool {
      if (state[f] == 1) return true;
      if (state[f] == 2) return false;
      state[f] = 1;
      for (int call : program_->functionBodies[f].calledFunctions())
        if (visit(static_cast<size_t>(call))) {
          if (state[f] == 1 && !reportedRecursion_.count(f)) {
            reportedRecursion_.insert(f);
            sink_.error(program_->functions[f].span,
                        "development function '" + program_->functions[f].name + "' calls itself; it would never end");
          }
          state[f] = 2;
          return true;
        }
      state[f] = 2;
      return false;
    };
    for (size_t f = 0; f < count; ++f) visit(f);
  }

  // ---- masters ----
  int addMaster(std::string label, int scope, SourceSpan span) {
    MasterCell master;
    master.label = std::move(label);
    master.scope = scope;
    master.span = span;
    program_->masters.push_back(std::move(master));
    arityKnown_.push_back(false);
    return static_cast<int>(program_->masters.size() - 1);
  }

  // A cell's or a system's state variables and their constant defaults.
  void declareState(const std::vector<ast::Parameter>& state, int index) {
    std::set<std::string> seen;
    for (const auto& param : state) {
      if (!seen.insert(param.name).second) sink_.error(param.span, "state variable '" + param.name + "' appears twice");
      if (isReadOnlyName(param.name))
        sink_.error(param.span, "'" + param.name + "' is the cell's read-only internal state; choose another name");
      double value = 0;
      if (param.defaultValue) {
        auto constant = evaluateConstant(*param.defaultValue, constantLookup(global_), sink_, "a default value");
        if (constant) value = *constant;
      }
      program_->masters[index].stateNames.push_back(param.name);
      program_->masters[index].defaults.push_back(value);
    }
  }

  void declareCells() {
    for (const auto& cell : tree_.cells) {
      if (program_->findMaster(cell.name, -1) >= 0) {
        sink_.error(cell.nameSpan, "cell '" + cell.name + "' is defined twice (also at " +
                                       where(program_->masters[program_->findMaster(cell.name, -1)].span) + ")");
        continue;
      }
      int index = addMaster(cell.name, -1, cell.nameSpan);
      program_->masters[index].declared = true;
      arityKnown_[index] = true;
      declareState(cell.state, index);
      if (cell.lifetime) {
        auto value = evaluateConstant(*cell.lifetime, constantLookup(global_), sink_, "the lifetime");
        if (value) {
          if (!(*value > 0))
            sink_.error(cell.lifetimeSpan, "the lifetime must be greater than 0");
          else
            program_->masters[index].lifetime = *value;
          program_->masters[index].timedNotation = true;
        }
      }
      cellMaster_[&cell] = index;
    }
  }

  // A system (not an L-system) is also a cell: its label and state stand for it in the
  // pools of the systems that contain it (paper 002, section 2.2). It has no rules.
  void declareSystemCells() {
    for (size_t i = 0; i < tree_.systems.size(); ++i) {
      const ast::System& system = tree_.systems[i];
      if (system.isLSystem) {
        if (!system.state.empty())
          sink_.error(system.state.front().span, "an lsystem has no state; write 'system' to give it some");
        continue;
      }
      if (int other = program_->findMaster(system.name, -1); other >= 0) {
        sink_.error(system.nameSpan, "'" + system.name + "' is already a cell (at " +
                                         where(program_->masters[other].span) +
                                         "); a system's name labels its cell, so the two need different names");
        continue;
      }
      int index = addMaster(system.name, -1, system.nameSpan);
      program_->masters[index].declared = true;
      program_->masters[index].system = static_cast<int>(i);
      arityKnown_[index] = true;
      declareState(system.state, index);
      systemMaster_[i] = index;
    }
  }

  // Finds or creates the master a module label refers to in a scope, and checks that
  // every use gives it the same number of parameters.
  // In an lsystem (scope >= 0) a symbol it has not seen becomes its own master, except
  // a declared top-level `cell` named in a successor or the axiom: that means the cell,
  // with its interpret blocks. A predecessor is always the lsystem's own (its
  // productions must not change a cell other systems share); predecessors are resolved
  // first, so a label with a production stays local throughout the block.
  int resolveModule(const ast::Module& module, int scope, bool predecessor = false) {
    int index = program_->findMaster(module.label, scope);
    const bool sharedCell = index >= 0 && !predecessor && program_->masters[index].declared;
    if (index < 0 || (scope >= 0 && program_->masters[index].scope != scope && !sharedCell))
      index = addMaster(module.label, scope, module.span);
    MasterCell& master = program_->masters[index];
    if (module.age) master.timedNotation = true;
    int count = static_cast<int>(module.args.size());
    if (!arityKnown_[index]) {
      arityKnown_[index] = true;
      master.span = module.span;
      for (int i = 0; i < count; ++i) {
        std::string name = "p" + std::to_string(i + 1);
        if (module.args[i]->kind == ast::Expr::Kind::Name) name = module.args[i]->name;
        master.stateNames.push_back(name);
        master.defaults.push_back(0);
      }
    } else if (master.declared && master.scope == -1) {
      if (count > static_cast<int>(master.stateCount()))
        sink_.error(module.span, "cell '" + master.label + "' has " + std::to_string(master.stateCount()) +
                                     " state variable" + (master.stateCount() == 1 ? "" : "s") + ", given " +
                                     std::to_string(count));
    } else if (count != static_cast<int>(master.stateCount())) {
      sink_.error(module.span, "'" + master.label + "' has " + std::to_string(master.stateCount()) + " parameter" +
                                   (master.stateCount() == 1 ? "" : "s") + " elsewhere (first at line " +
                                   std::to_string(master.span.line()) + "), but " + std::to_string(count) + " here");
    }
    return index;
  }

  // ---- systems ----
  void declareSystem(const ast::System& system, int index) {
    SystemDefinition definition;
    definition.name = system.name;
    definition.span = system.nameSpan;
    definition.isLSystem = system.isLSystem;
    if (auto it = systemMaster_.find(static_cast<size_t>(index)); it != systemMaster_.end())
      definition.master = it->second;
    for (const auto& other : program_->systems)
      if (other.name == system.name)
        sink_.error(system.nameSpan, "system '" + system.name + "' is defined twice (also at " + where(other.span) + ")");
    if (system.poolKind == "linear") {
      definition.poolKind = PoolKind::Linear;
      if (!system.poolArgs.empty() || !system.poolOptions.empty())
        sink_.error(system.poolSpan, "the linear pool takes no arguments or options");
    } else if (system.poolKind == "grid") {
      definition.poolKind = PoolKind::Grid;
    } else if (system.poolKind == "spatial") {
      definition.poolKind = PoolKind::Spatial;
    } else {
      sink_.error(system.poolSpan, "unknown pool kind '" + system.poolKind + "' (expected linear, grid or spatial)");
    }
    auto scope = std::make_unique<Scope>();
    scope->system = system.isLSystem ? index : -1;
    scope->outer = &global_;
    scope->constants.outer = &global_.constants;
    definition.settings = globalSettings_;
    program_->systems.push_back(std::move(definition));
    defines(system.defines, *scope, index);
    if (!system.isLSystem && !system.equivs.empty())
      sink_.error(system.equivs.front().span,
                  "cells are shared by every system, so their equivs are too: write 'equiv' at the top level");
    equivs(system.equivs, *scope);
    settings(system.settings, program_->systems.back().settings, scope.get());
    if (system.isLSystem) functions(system.functions, *scope);
    if (program_->systems.back().poolKind == PoolKind::Grid) gridShape(system, *scope, program_->systems.back());
    if (program_->systems.back().poolKind == PoolKind::Spatial)
      spatialRadius(system, *scope, program_->systems.back());
    scopes_.push_back(std::move(scope));
  }

  // `pool grid(nx [, ny [, nz]]) [wrap | clamp | closed] [vonneumann | moore]`
  void gridShape(const ast::System& system, const Scope& scope, SystemDefinition& definition) {
    GridShape& shape = definition.grid;
    if (system.poolArgs.empty() || system.poolArgs.size() > 3) {
      sink_.error(system.poolSpan, "a grid has 1 to 3 sizes, as in 'pool grid(64, 64)'");
      return;
    }
    shape.dimensions = static_cast<int>(system.poolArgs.size());
    uint64_t sites = 1;
    for (size_t axis = 0; axis < system.poolArgs.size(); ++axis) {
      auto value = evaluateConstant(*system.poolArgs[axis], constantLookup(scope), sink_, "a grid size");
      if (!value) return;
      if (!(*value >= 1) || *value != std::floor(*value) || *value > 1e9) {
        sink_.error(system.poolArgs[axis]->span, "a grid size is a whole number ≥ 1, not " + formatNumber(*value));
        return;
      }
      shape.size[axis] = static_cast<uint32_t>(*value);
      sites *= shape.size[axis];
    }
    if (sites >= GridPool::kEmpty) {
      sink_.error(system.poolSpan, "a grid has fewer than 4294967295 sites; this one has " + std::to_string(sites));
      return;
    }
    bool boundarySet = false, neighbourhoodSet = false;
    for (const auto& option : system.poolOptions) {
      bool* set = nullptr;
      if (option == "wrap" || option == "clamp" || option == "closed") {
        set = &boundarySet;
        shape.boundary = option == "wrap"    ? GridBoundary::Wrap
                         : option == "clamp" ? GridBoundary::Clamp
                                             : GridBoundary::Closed;
      } else if (option == "moore" || option == "vonneumann") {
        set = &neighbourhoodSet;
        shape.neighbourhood = option == "moore" ? GridNeighbourhood::Moore : GridNeighbourhood::VonNeumann;
      } else {
        sink_.error(system.poolSpan,
                    "unknown grid option '" + option + "' (expected wrap, clamp or closed, and vonneumann or moore)");
        continue;
      }
      if (*set)
        sink_.error(system.poolSpan, "the grid's " + std::string(set == &boundarySet ? "boundary" : "neighbourhood") +
                                         " is given twice");
      *set = true;
    }
  }

  // `pool spatial(radius)`: cells within the radius are neighbours.
  void spatialRadius(const ast::System& system, const Scope& scope, SystemDefinition& definition) {
    if (system.poolArgs.size() != 1 || !system.poolOptions.empty()) {
      sink_.error(system.poolSpan, "a spatial pool takes its neighbourhood radius, as in 'pool spatial(1.5)'");
      return;
    }
    auto value = evaluateConstant(*system.poolArgs[0], constantLookup(scope), sink_, "the radius");
    if (!value) return;
    if (!(*value > 0) || !std::isfinite(*value)) {
      sink_.error(system.poolArgs[0]->span, "the radius must be greater than 0");
      return;
    }
    definition.spatialRadius = *value;
  }

  // `fill A(e)` and `at(x, y) A(1)`. Values are compiled against a frame of internal
  // state only, so they may read the site's me.x, me.y, me.z (and draw random numbers).
  void compilePlacements(const ast::System& system, Scope& scope, SystemDefinition& definition) {
    if (system.placements.empty()) return;
    if (definition.poolKind != PoolKind::Grid) {
      sink_.error(system.placements.front().span, "'fill' and 'at' place cells in a grid pool; this system's pool is " +
                                                      std::string(poolKindName(definition.poolKind)));
      return;
    }
    std::map<std::string, int, std::less<>> none;
    reader_ = Reader{-1, static_cast<int>(&definition - program_->systems.data())};
    NameLookup names = ruleLookup(none, 0, scope);
    for (const auto& placement : system.placements) {
      GridPlacement compiled;
      compiled.fill = placement.fill;
      compiled.span = placement.span;
      if (placement.module.isMe) {
        sink_.error(placement.module.span, "'me' is not a cell to place; name a cell");
        continue;
      }
      if (!placement.fill) {
        if (static_cast<int>(placement.at.size()) != definition.grid.dimensions) {
          sink_.error(placement.span, "the grid has " + std::to_string(definition.grid.dimensions) + " dimension" +
                                          (definition.grid.dimensions == 1 ? "" : "s") + ", so 'at' takes " +
                                          std::to_string(definition.grid.dimensions) + " coordinate" +
                                          (definition.grid.dimensions == 1 ? "" : "s"));
          continue;
        }
        bool ok = true;
        for (size_t axis = 0; axis < placement.at.size(); ++axis) {
          auto value = evaluateConstant(*placement.at[axis], constantLookup(scope), sink_, "a site coordinate");
          if (!value) {
            ok = false;
            continue;
          }
          if (!(*value >= 0) || *value != std::floor(*value) || *value >= definition.grid.size[axis]) {
            sink_.error(placement.at[axis]->span, "coordinate " + formatNumber(*value) + " is outside the grid (0 to " +
                                                      std::to_string(definition.grid.size[axis] - 1) + ")");
            ok = false;
            continue;
          }
          compiled.at[axis] = static_cast<int64_t>(*value);
        }
        if (!ok) continue;
      }
      int master = resolveModule(placement.module, -1);
      compiled.master = static_cast<MasterId>(master);
      const MasterCell& target = program_->masters[master];
      if (placement.module.age) sink_.error(placement.module.age->span, "cells placed in a grid start with age 0");
      for (uint32_t i = 0; i < target.stateCount(); ++i) {
        if (i < placement.module.args.size())
          compiled.values.push_back(compileExpression(*placement.module.args[i], names, sink_));
        else
          compiled.values.push_back(CompiledExpression::constant(target.defaults[i]));
      }
      definition.placements.push_back(std::move(compiled));
    }
  }

  void compileSystem(const ast::System& system, int index) {
    Scope& scope = *scopes_[index];
    int moduleScope = system.isLSystem ? index : -1;
    if (system.isLSystem) compileProductions(system, scope, index);
    // Axiom: values are compiled now and evaluated when a world is made.
    std::vector<AxiomCell> axiom;
    for (const auto& module : system.axiom) {
      if (module.isMe) continue;
      int master = resolveModule(module, moduleScope);
      AxiomCell cell;
      cell.master = master;
      const MasterCell& definition = program_->masters[master];
      NameLookup names = constantLookup(scope);
      addFunctions(names, scope);
      // Values may read the system's own state and those above it (parent.x, root.x).
      reader_ = Reader{-1, index};
      NameLookup withSystems = names;
      withSystems.ancestor = [this](const std::string& path, SourceSpan span) {
        ++ancestorUses_;
        return registerAncestor(path, span);
      };
      for (uint32_t i = 0; i < definition.stateCount(); ++i) {
        if (i < module.args.size()) {
          const int usesBefore = ancestorUses_;
          const int errorsBefore = sink_.errorCount();
          CompiledExpression compiled = compileExpression(*module.args[i], withSystems, sink_);
          if (ancestorUses_ != usesBefore && sink_.errorCount() == errorsBefore && !compiled.isStochastic()) {
            cell.fromSystems.resize(definition.stateCount());
            cell.fromSystems[i] = std::move(compiled);
            cell.values.push_back(0);
            continue;
          }
          if (sink_.errorCount() != errorsBefore) {
            cell.values.push_back(0);
            continue;
          }
          auto value = evaluateConstant(*module.args[i], names, sink_, "an axiom value");
          cell.values.push_back(value.value_or(0));
        } else {
          cell.values.push_back(definition.defaults[i]);
        }
      }
      if (module.age) {
        cell.age = evaluateConstant(*module.age, names, sink_, "an axiom age").value_or(0);
        const MasterCell& target = program_->masters[master];
        if (cell.age < 0 || cell.age >= target.lifetime)
          sink_.error(
              module.age->span,
              "'" + module.label + "' cannot start with age " + formatNumber(cell.age) +
                  (cell.age < 0 ? "; ages are ≥ 0" : ", not below its terminal age " + formatNumber(target.lifetime)));
      }
      axiom.push_back(std::move(cell));
    }
    program_->systems[index].axiom = std::move(axiom);
    if (system.isLSystem) compileSymbolInterpretations(system, scope, index);
    compilePlacements(system, scope, program_->systems[index]);
    if (program_->systems[index].poolKind == PoolKind::Grid &&
        program_->systems[index].axiom.size() > program_->systems[index].grid.siteCount())
      sink_.error(system.axiomSpan, "the axiom has " + std::to_string(program_->systems[index].axiom.size()) +
                                        " cells, more than the grid's " +
                                        std::to_string(program_->systems[index].grid.siteCount()) + " sites");
    ignoreLists_.push_back({index, &system});
  }

  void compileProductions(const ast::System& system, Scope& scope, int index) {
    // Terminal ages: one per symbol; untimed productions live one time unit.
    std::map<int, std::pair<double, SourceSpan>> terminal;
    std::vector<std::pair<int, const ast::Rule*>> productions;
    for (const auto& production : system.productions) {
      int master = resolveModule(production.predecessor, index, /*predecessor=*/true);
      double age = 1.0;
      if (production.predecessor.age) {
        auto value = evaluateConstant(*production.predecessor.age, constantLookup(scope), sink_, "a terminal age");
        if (!value) continue;
        age = *value;
        if (!(age > 0)) {
          sink_.error(production.predecessor.age->span, "the terminal age must be greater than 0");
          continue;
        }
      }
      auto [it, inserted] = terminal.emplace(master, std::make_pair(age, production.predecessor.span));
      if (!inserted && it->second.first != age) {
        sink_.error(production.predecessor.span, "'" + production.predecessor.label + "' has terminal age " +
                                                     formatNumber(age) + " here but " + formatNumber(it->second.first) +
                                                     " at line " + std::to_string(it->second.second.line()) +
                                                     "; a symbol has one terminal age");
        continue;
      }
      productions.push_back({master, &production});
    }
    for (auto& [master, age] : terminal) {
      program_->masters[master].lifetime = age.first;
      program_->masters[master].declared = true;
    }
    for (auto& [master, production] : productions) {
      readsPosition_ = false;
      CompiledRule rule = compileRule(*production, master, index, scope, /*lsystem=*/true);
      if (readsPosition_) program_->masters[master].readsPosition = true;
      program_->masters[master].terminalRules.push_back(std::move(rule));
    }
  }

  // A development function named after a symbol develops it: an L-system's functions
  // its own symbols, top-level functions the program's cells and symbols. Functions
  // named after no symbol are helpers that others call.
  void attachDevelopmentFunctions() {
    for (size_t m = 0; m < program_->masters.size(); ++m) {
      MasterCell& master = program_->masters[m];
      const Scope& scope = master.scope >= 0 ? *scopes_[master.scope] : global_;
      int functionIndex = scope.findFunction(master.label);
      if (functionIndex < 0) continue;
      const DevelopmentFunction& definition = program_->functions[functionIndex];
      int moduleParams = 0;
      for (int source : definition.sources) moduleParams += source >= 0;
      if (moduleParams > static_cast<int>(master.stateCount())) {
        sink_.error(definition.span, "development function '" + definition.name + "' names " +
                                         std::to_string(moduleParams) + " module parameters, but '" + master.label +
                                         "' has " + std::to_string(master.stateCount()));
        continue;
      }
      master.developmentFunction = functionIndex;
    }
  }

  static std::string formatNumber(double value) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", value);
    return buffer;
  }

  // ---- cells ----
  void compileCells() {
    for (const auto& cell : tree_.cells) {
      auto it = cellMaster_.find(&cell);
      if (it == cellMaster_.end()) continue;
      int master = it->second;
      bool anyTerminal = false;
      for (const auto& rule : cell.rules) {
        readsPosition_ = false;
        CompiledRule compiled = compileRule(rule, master, -1, global_, /*lsystem=*/false);
        if (readsPosition_) program_->masters[master].readsPosition = true;
        if (rule.terminal) {
          anyTerminal = true;
          program_->masters[master].terminalRules.push_back(std::move(compiled));
        } else {
          program_->masters[master].rules.push_back(std::move(compiled));
        }
      }
      if (anyTerminal && program_->masters[master].lifetime == kForever)
        sink_.error(cell.nameSpan, "cell '" + cell.name + "' has 'terminal:' rules but no lifetime; add 'lifetime 1;'");
      for (const auto& block : cell.interpretations) compileInterpretation(block, master);
    }
  }

  CompiledRule compileRule(const ast::Rule& rule, int master, int scopeIndex, const Scope& scope, bool lsystem) {
    reader_ = Reader{master, -1};
    CompiledRule compiled;
    compiled.name = rule.name;
    compiled.span = rule.span;
    // Copies, not a reference: resolving context and successor labels may add masters.
    struct {
      std::string label;
      std::vector<std::string> stateNames;
    } self{program_->masters[master].label, program_->masters[master].stateNames};
    const int stateCount = static_cast<int>(self.stateNames.size());
    std::map<std::string, int, std::less<>> slots;
    std::map<std::string, SourceSpan, std::less<>> where;
    auto bind = [&](const std::string& name, int slot, SourceSpan span) {
      if (isReadOnlyName(name)) {
        sink_.error(span, "'" + name + "' is read-only internal state and cannot be a parameter name");
        return;
      }
      if (slots.emplace(name, slot).second) {
        where[name] = span;
      } else if (!where.count(name)) {
        sink_.error(span, "'" + name + "' is already a state variable of '" + self.label + "'");
      } else {
        sink_.error(span, "'" + name + "' is already bound in this rule (at line " +
                              std::to_string(where[name].line()) + ":" + std::to_string(where[name].column()) + ")");
      }
    };
    if (lsystem) {
      for (size_t i = 0; i < rule.predecessor.args.size(); ++i)
        bind(rule.predecessor.args[i]->name, static_cast<int>(i), rule.predecessor.args[i]->span);
    } else {
      for (int i = 0; i < stateCount; ++i) slots[self.stateNames[i]] = i;
      if (rule.predecessor.isMe && rule.predecessor.hasArgs)
        sink_.error(rule.predecessor.span, "'me' takes no parameters; the cell's state is read by name");
    }
    int nextSlot = stateCount + FrameSlot::kCount;
    auto contextBinding = [&](const ast::Module& module, bool leftSide) {
      ContextBinding binding;
      if (module.label == "[" || module.label == "]") {
        if (leftSide)
          sink_.error(module.span, "a left context cannot contain brackets; it follows the path to the root");
        binding.item.kind = module.label == "[" ? ContextItem::Kind::BranchOpen : ContextItem::Kind::BranchClose;
        return binding;
      }
      int contextMaster = resolveModule(module, lsystem ? scopeIndex : -1);
      binding.item.master = static_cast<uint32_t>(contextMaster);
      if (!module.args.empty()) {
        binding.firstSlot = nextSlot;
        binding.count = static_cast<int>(module.args.size());
        if (binding.count != static_cast<int>(program_->masters[contextMaster].stateCount()))
          sink_.error(module.span, "'" + module.label + "' has " +
                                       std::to_string(program_->masters[contextMaster].stateCount()) +
                                       " state values; a context binds all of them or none");
        for (const auto& arg : module.args) bind(arg->name, nextSlot++, arg->span);
      }
      return binding;
    };
    // Left context nearest first.
    for (auto it = rule.left.rbegin(); it != rule.left.rend(); ++it) compiled.left.push_back(contextBinding(*it, true));
    for (const auto& module : rule.right) compiled.right.push_back(contextBinding(module, false));
    compiled.contextDimensions = rule.contextDimensions;
    for (size_t k = 0; k < rule.offsets.size() && k < compiled.right.size(); ++k) {
      compiled.right[k].offset = rule.offsets[k];
      if (compiled.right[k].item.kind != ContextItem::Kind::Module)
        sink_.error(rule.right[k].span, "brackets have no place in a context of " +
                                            std::to_string(rule.contextDimensions) + " dimensions");
    }
    compiled.frameSize = nextSlot;
    for (const auto& binding : compiled.left) compiled.leftItems.push_back(binding.item);
    for (const auto& binding : compiled.right) compiled.rightItems.push_back(binding.item);
    if (compiled.leftItems.size() > kMaxContextItems || compiled.rightItems.size() > kMaxContextItems)
      sink_.error(rule.span, "a context has at most " + std::to_string(kMaxContextItems) + " modules on each side");

    NameLookup names = ruleLookup(slots, stateCount, scope, &compiled.aggregates, lsystem ? scopeIndex : -1);
    if (rule.predicate) compiled.predicate = compileExpression(*rule.predicate, names, sink_);
    for (const auto& assignment : rule.calculations) {
      StateCalculation calculation;
      calculation.span = assignment.span;
      if (assignment.isRate) {
        if (lsystem) {
          sink_.error(assignment.span, "'rate' belongs to the cell language; write the module as a cell");
          continue;
        }
        if (rule.terminal) {
          sink_.error(assignment.span, "'rate' integrates while a cell lives; a terminal rule fires once");
          continue;
        }
        if (assignment.op != TokenKind::Equal) {
          sink_.error(assignment.span, "write 'rate(x) = e': the rate is the derivative itself");
          continue;
        }
        calculation.isRate = true;
      }
      if (isReadOnlyName(assignment.target) || internalSlot(assignment.target) >= 0) {
        sink_.error(assignment.targetSpan, "'" + assignment.target + "' is read-only internal state");
        continue;
      }
      auto it = std::find(self.stateNames.begin(), self.stateNames.end(), assignment.target);
      if (lsystem || it == self.stateNames.end()) {
        sink_.error(assignment.targetSpan,
                    slots.count(assignment.target)
                        ? "'" + assignment.target + "' belongs to a neighbour; a cell writes only its own state"
                        : "'" + assignment.target + "' is not a state variable of '" + self.label + "'");
        continue;
      }
      calculation.slot = static_cast<int>(it - self.stateNames.begin());
      calculation.value = compileExpression(*combine(assignment), names, sink_);
      (calculation.isRate ? compiled.hasRate : compiled.hasDiscrete) = true;
      compiled.calculations.push_back(std::move(calculation));
    }
    compiled.hasAction = rule.hasAction;
    if (rule.hasAction) compiled.hasDiscrete = true;
    const ast::Module* identityKeeper = nullptr;  // `me` or `=X`: one cell goes on with the id
    for (const auto& successor : rule.successors) {
      SuccessorTemplate result;
      result.span = successor.span;
      if (successor.isMe || successor.keepsIdentity) {
        if (identityKeeper)
          sink_.error(successor.span, "only one successor keeps the cell's identity, and '" +
                                          (identityKeeper->isMe ? std::string("me") : "=" + identityKeeper->label) +
                                          "' already does");
        identityKeeper = &successor;
      }
      result.keepsIdentity = successor.keepsIdentity;
      if (successor.isMe) {
        if (lsystem) sink_.error(successor.span, "'me' is not part of the L-system notation; repeat the module");
        result.isMe = true;
        if (successor.hasArgs) sink_.error(successor.span, "'me' takes no parameters; set state before '->'");
        compiled.successors.push_back(std::move(result));
        continue;
      }
      int successorMaster = resolveModule(successor, lsystem ? scopeIndex : -1);
      result.master = static_cast<uint32_t>(successorMaster);
      const MasterCell& target = program_->masters[successorMaster];
      for (uint32_t i = 0; i < target.stateCount(); ++i) {
        if (i < successor.args.size())
          result.args.push_back(compileExpression(*successor.args[i], names, sink_));
        else
          result.args.push_back(CompiledExpression::constant(target.defaults[i]));
      }
      if (successor.age) result.birthAge = compileExpression(*successor.age, names, sink_);
      bool bornAtZero =
          result.birthAge.empty() || (result.birthAge.isConstant() && result.birthAge.constantValue() == 0.0);
      result.stateless = target.stateCount() == 0 && bornAtZero && target.lifetime > 0;
      compiled.successors.push_back(std::move(result));
    }
    if (rule.probability) {
      compiled.probability = compileExpression(*rule.probability, names, sink_);
      if (compiled.probability.isConstant() && !(compiled.probability.constantValue() >= 0))
        sink_.error(rule.probability->span, "a probability must be ≥ 0");
    }
    return compiled;
  }

  // `x += e` is compiled as `x = x + e`.
  std::unique_ptr<ast::Expr> combine(const ast::Assignment& assignment) {
    auto copy = cloneExpr(*assignment.value);
    if (assignment.op == TokenKind::Equal) return copy;
    auto target = std::make_unique<ast::Expr>();
    target->kind = ast::Expr::Kind::Name;
    target->name = assignment.target;
    target->span = assignment.targetSpan;
    auto node = std::make_unique<ast::Expr>();
    node->kind = ast::Expr::Kind::Binary;
    node->span = assignment.span;
    node->op = assignment.op == TokenKind::PlusEqual    ? TokenKind::Plus
               : assignment.op == TokenKind::MinusEqual ? TokenKind::Minus
               : assignment.op == TokenKind::StarEqual  ? TokenKind::Star
                                                        : TokenKind::Slash;
    node->args.push_back(std::move(target));
    node->args.push_back(std::move(copy));
    return node;
  }

  static std::unique_ptr<ast::Expr> cloneExpr(const ast::Expr& expr) {
    auto copy = std::make_unique<ast::Expr>();
    copy->kind = expr.kind;
    copy->span = expr.span;
    copy->number = expr.number;
    copy->name = expr.name;
    copy->op = expr.op;
    for (const auto& arg : expr.args) copy->args.push_back(cloneExpr(*arg));
    return copy;
  }

  NameLookup ruleLookup(const std::map<std::string, int, std::less<>>& slots, int stateCount, const Scope& scope,
                        std::vector<AggregateQuery>* aggregates = nullptr, int moduleScope = -1) {
    NameLookup names = constantLookup(scope);
    names.slot = [this, &slots, stateCount](std::string_view name) -> int {
      if (auto it = slots.find(name); it != slots.end()) return it->second;
      int internal = internalSlot(name);
      if (internal >= FrameSlot::kX && internal <= FrameSlot::kZ) readsPosition_ = true;
      return internal < 0 ? -1 : stateCount + internal;
    };
    if (aggregates)
      names.aggregate = [this, aggregates, moduleScope](const ast::Expr& call, DiagnosticSink& sink) {
        return registerAggregate(call, sink, *aggregates, moduleScope);
      };
    addFunctions(names, scope);
    names.ancestor = [this](const std::string& path, SourceSpan span) { return registerAncestor(path, span); };
    names.unknownHint = [](std::string_view) { return std::string(); };
    // Copy the lookup state that the lambdas above refer to by reference only while the
    // caller's maps live: compileRule uses names before returning.
    return names;
  }

  // `parent.x`, `parent.parent.age`, `root.x`: one AncestorRef per distinct read. Whether
  // the systems at that level have the variable is checked once the tree is known.
  int registerAncestor(const std::string& path, SourceSpan span) {
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
      if (reportedAncestors_.insert(span.begin).second)
        sink_.error(span, "'" + path + "': read an enclosing system as 'parent.x', 'parent.parent.x' or 'root.x'");
      return 0;
    }
    auto found = std::find(program_->ancestorRefs.begin(), program_->ancestorRefs.end(), ref);
    const int index = static_cast<int>(found - program_->ancestorRefs.begin());
    if (found == program_->ancestorRefs.end()) program_->ancestorRefs.push_back(ref);
    if (reportedAncestors_.insert(span.begin).second) ancestorReads_.push_back({reader_, ref, path, span});
    return index;
  }

  // `count()`, `count(A)`, `sum(x)`, `mean(A.x)`, `min(x)`, `max(x)`: one query per text.
  int registerAggregate(const ast::Expr& call, DiagnosticSink& sink, std::vector<AggregateQuery>& queries,
                        int moduleScope) {
    const ast::Expr* arg = call.args.empty() ? nullptr : call.args[0].get();
    std::string argText = !arg                                   ? ""
                          : arg->kind == ast::Expr::Kind::Name   ? arg->name
                          : arg->kind == ast::Expr::Kind::Member ? memberPath(*arg)
                                                                 : "?";
    std::string text = call.name + "(" + argText + ")";
    for (size_t i = 0; i < queries.size(); ++i)
      if (queries[i].text == text) return static_cast<int>(i);
    AggregateQuery query;
    query.text = text;
    query.kind = call.name == "count"  ? AggregateKind::Count
                 : call.name == "sum"  ? AggregateKind::Sum
                 : call.name == "mean" ? AggregateKind::Mean
                 : call.name == "min"  ? AggregateKind::Min
                                       : AggregateKind::Max;
    auto findLabel = [&](const std::string& label, SourceSpan span) {
      int master = program_->findMaster(label, moduleScope);
      if (master < 0) sink.error(span, "no cell is called '" + label + "'");
      return master;
    };
    if (query.kind == AggregateKind::Count) {
      if (arg) {
        if (arg->kind != ast::Expr::Kind::Name) {
          sink.error(arg->span, "count() takes a cell label, as in count(A), or nothing");
          return -1;
        }
        query.label = findLabel(arg->name, arg->span);
        if (query.label < 0) return -1;
      }
    } else {
      std::string variable;
      if (arg->kind == ast::Expr::Kind::Name) {
        variable = arg->name;
      } else if (!memberPath(*arg).empty()) {
        query.label = findLabel(arg->args[0]->name, arg->args[0]->span);
        if (query.label < 0) return -1;
        variable = arg->name;
      } else {
        sink.error(arg->span, "'" + call.name + "' over neighbours takes a state variable, as in " + call.name +
                                  "(x) or " + call.name + "(A.x)");
        return -1;
      }
      bool any = false;
      for (size_t m = 0; m < program_->masters.size(); ++m) {
        const auto& names = program_->masters[m].stateNames;
        auto it = std::find(names.begin(), names.end(), variable);
        bool has = it != names.end() && (query.label < 0 || query.label == static_cast<int>(m));
        query.slotOf.push_back(has ? static_cast<int>(it - names.begin()) : -1);
        any = any || has;
      }
      if (!any) {
        sink.error(arg->span, query.label >= 0 ? "'" + program_->masters[query.label].label +
                                                     "' has no state variable '" + variable + "'"
                                               : "no cell has a state variable '" + variable + "'");
        return -1;
      }
    }
    queries.push_back(std::move(query));
    return static_cast<int>(queries.size() - 1);
  }

  // `interpret SET X(a) { ... }` in an L-system: the block of the block's own symbol X,
  // its parameters named as the pattern names them.
  void compileSymbolInterpretations(const ast::System& system, const Scope& scope, int index) {
    for (const auto& item : system.interpretations) {
      int master = program_->findMaster(item.symbol, index);
      if (master < 0 || program_->masters[master].scope != index) {
        sink_.error(item.symbolSpan, "'" + item.symbol + "' is not a symbol of L-system '" + system.name + "'");
        continue;
      }
      const MasterCell& target = program_->masters[master];
      if (item.params.size() != target.stateCount()) {
        sink_.error(item.symbolSpan, "'" + item.symbol + "' has " + std::to_string(target.stateCount()) + " parameter" +
                                         (target.stateCount() == 1 ? "" : "s") + ", but " +
                                         std::to_string(item.params.size()) + " are named here");
        continue;
      }
      if (target.interpretation(item.block.setName)) continue;  // the first block counts
      compileInterpretation(item.block, master, &item.params, &scope);
    }
  }

  void compileInterpretation(const ast::Interpretation& block, int master,
                             const std::vector<std::string>* names_ = nullptr, const Scope* scope = nullptr) {
    InterpretationBlock compiled;
    compiled.setName = block.setName;
    compiled.span = block.span;
    const CommandSetInfo* set = nullptr;
    if (!options_.commandSets.empty()) {
      for (const auto& candidate : options_.commandSets)
        if (candidate.name == block.setName) set = &candidate;
      if (!set) {
        std::string known;
        for (const auto& candidate : options_.commandSets) known += (known.empty() ? "" : ", ") + candidate.name;
        sink_.error(block.span, "unknown interpretation set '" + block.setName + "' (known: " + known + ")");
        return;
      }
    }
    const MasterCell& self = program_->masters[master];
    const Scope& lookupScope = scope ? *scope : global_;
    std::map<std::string, int, std::less<>> slots;
    for (uint32_t i = 0; i < self.stateCount(); ++i)
      slots[names_ ? (*names_)[i] : self.stateNames[i]] = static_cast<int>(i);
    reader_ = Reader{master, -1};
    NameLookup names = ruleLookup(slots, static_cast<int>(self.stateCount()), lookupScope);
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
          sink_.error(module.span, "'" + module.label + "' is not a command of the '" + block.setName + "' set");
          continue;
        }
        int count = static_cast<int>(module.args.size());
        if (count < info->minArity || (info->maxArity >= 0 && count > info->maxArity)) {
          sink_.error(module.span, "'" + module.label + "' takes " + std::to_string(info->minArity) +
                                       (info->maxArity == info->minArity ? ""
                                        : info->maxArity < 0             ? " or more"
                                                                         : " to " + std::to_string(info->maxArity)) +
                                       " arguments, given " + std::to_string(count));
          continue;
        }
      }
      for (const auto& arg : module.args) instruction.args.push_back(compileExpression(*arg, names, sink_));
      compiled.instructions.push_back(std::move(instruction));
    }
    program_->masters[master].interpretations.push_back(std::move(compiled));
  }

  // ---- finishing ----
  void finishMasters() {
    for (auto& master : program_->masters) {
      const Scope* scope = master.scope >= 0 ? scopes_[master.scope].get() : &global_;
      const std::string* equiv = scope->findEquiv(master.label);
      master.command = equiv ? *equiv : master.label;
      if (master.command == "[") master.symbolClass = kSymbolBranchOpen;
      if (master.command == "]") master.symbolClass = kSymbolBranchClose;
    }
    for (auto& [index, system] : ignoreLists_) {
      SystemDefinition& definition = program_->systems[index];
      definition.symbolClass.resize(program_->masters.size());
      for (size_t m = 0; m < program_->masters.size(); ++m)
        definition.symbolClass[m] = program_->masters[m].symbolClass;
      if (!system->ignore.empty() && !system->consider.empty())
        sink_.error(system->consider.front().span, "a system has either 'ignore' or 'consider', not both");
      std::set<std::string> listed;
      for (const auto& list : system->ignore) listed.insert(list.symbols.begin(), list.symbols.end());
      for (const auto& list : system->consider) listed.insert(list.symbols.begin(), list.symbols.end());
      bool consider = !system->consider.empty();
      if (listed.empty()) continue;
      for (size_t m = 0; m < program_->masters.size(); ++m) {
        const MasterCell& master = program_->masters[m];
        if (master.symbolClass != kSymbolModule) continue;
        bool inList = listed.count(master.label) > 0;
        if (inList != consider) definition.symbolClass[m] |= kSymbolIgnored;
      }
    }
    for (size_t s = 0; s < program_->systems.size(); ++s) {
      SystemDefinition& definition = program_->systems[s];
      std::vector<bool> grows = reachable(definition);
      for (size_t m = 0; m < program_->masters.size(); ++m) {
        const MasterCell& master = program_->masters[m];
        if (!visibleIn(master, static_cast<int>(s))) continue;
        for (const auto& rule : master.terminalRules) {
          if (rule.hasContext() || !rule.aggregates.empty()) definition.terminalContext = true;
          if (rule.probability.empty() == false) definition.stochastic = true;
        }
        for (const auto& rule : master.rules)
          if (rule.hasDiscrete || (!rule.hasRate && !rule.hasAction)) definition.sampledRules = true;
        for (const auto& rule : master.rules) {
          if (rule.hasRate) definition.rates = true;
          if (definition.poolKind == PoolKind::Spatial && grows[m] && rule.hasContext())
            sink_.error(rule.span, "a positional context ('A me B') does not fit the spatial pool of system '" +
                                       definition.name + "', where neighbours are the cells within a distance; read "
                                       "them with count(), sum(x), mean(x), min(x) or max(x)");
          const int poolDimensions =
              definition.poolKind == PoolKind::Grid ? static_cast<int>(definition.grid.dimensions) : 1;
          if (definition.poolKind != PoolKind::Spatial && grows[m] && rule.hasContext() &&
              rule.contextDimensions != poolDimensions)
            sink_.error(rule.span,
                        "this context has " + std::to_string(rule.contextDimensions) + " dimension" +
                            (rule.contextDimensions == 1 ? " ('A me B')" : "s") + ", but the pool of system '" +
                            definition.name + "' is " +
                            (definition.poolKind == PoolKind::Grid
                                 ? "a " + std::to_string(poolDimensions) + "-D grid"
                                 : std::string("linear")) +
                            "; match its dimensions (parentheses mark them: '(A) (B me C) (D)' is 2-D) or read the "
                            "neighbours with count(), sum(x), mean(x), min(x) or max(x)");
        }
        if (definition.poolKind != PoolKind::Linear && grows[m] && !master.terminalRules.empty())
          sink_.error(master.terminalRules.front().span,
                      "terminal rules (lifetimes) in a " + std::string(poolKindName(definition.poolKind)) +
                          " pool are not available in this version; use a per-step rule with 'age > ...'");
      }
    }
  }

  // The masters a system's pool can hold: its axiom and placements, and every successor
  // of their rules, transitively.
  std::vector<bool> reachable(const SystemDefinition& system) const {
    return SystemTree::reachableMasters(*program_, system);
  }


  bool visibleIn(const MasterCell& master, int system) const { return master.scope == -1 || master.scope == system; }

  // A system that contains itself, directly or through others, is rejected: the
  // hierarchy is a tree (paper 002, section 2.2).
  bool checkCycles(const SystemTree& tree) {
    std::vector<int> cycle = tree.findCycle();
    if (cycle.empty()) return true;
    std::string path;
    for (int s : cycle) path += (path.empty() ? "" : " contains ") + ("'" + program_->systems[s].name + "'");
    sink_.error(program_->systems[cycle.front()].span,
                "system '" + program_->systems[cycle.front()].name + "' contains itself: " + path +
                    "; the systems must form a tree");
    return false;
  }

  // The root is the system named by --system, else the first one no other system contains.
  void chooseRoot(const SystemTree& tree) {
    if (program_->systems.empty()) {
      sink_.error(SourceSpan{program_->sources.front().get(), 0, 0},
                  "the program defines no system or lsystem to grow");
      return;
    }
    program_->root = 0;
    for (size_t i = 0; i < program_->systems.size(); ++i)
      if (tree.containers(static_cast<int>(i)).empty()) {
        program_->root = static_cast<int>(i);
        break;
      }
    if (!options_.rootSystem.empty()) {
      for (size_t i = 0; i < program_->systems.size(); ++i)
        if (program_->systems[i].name == options_.rootSystem) {
          program_->root = static_cast<int>(i);
          return;
        }
      std::string known;
      for (const auto& system : program_->systems) known += (known.empty() ? "" : ", ") + system.name;
      sink_.error(SourceSpan{}, "no system named '" + options_.rootSystem + "' (the program has: " + known + ")");
    }
  }

  // Every system a `parent...x` read can reach must have x (or it is `age`); a read past
  // the root is an error.
  void checkAncestorReads(const SystemTree& tree) {
    for (const AncestorRead& read : ancestorReads_) {
      std::set<int> level;
      if (read.reader.system >= 0)
        level.insert(read.reader.system);
      else
        for (int s : tree.systemsHolding(read.reader.master)) level.insert(s);
      if (read.ref.level == 0) level = {program_->root};
      for (int k = 1; k < read.ref.level && !level.empty(); ++k) {
        std::set<int> up;
        for (int s : level) {
          std::vector<int> containers = tree.containers(s);
          if (containers.empty() && s == program_->root) {
            sink_.error(read.span, "'" + read.path + "' goes above the root system '" + program_->systems[s].name +
                                       "', which has no parent");
            up.clear();
            break;
          }
          up.insert(containers.begin(), containers.end());
        }
        level = std::move(up);
      }
      for (int s : level) {
        if (read.ref.name == "age") continue;
        const SystemDefinition& system = program_->systems[s];
        const MasterCell* master = system.master >= 0 ? &program_->masters[system.master] : nullptr;
        bool has = master && std::find(master->stateNames.begin(), master->stateNames.end(), read.ref.name) !=
                                 master->stateNames.end();
        if (has) continue;
        std::string known = "age";
        if (master)
          for (const auto& name : master->stateNames) known += ", " + name;
        sink_.error(read.span, "'" + read.path + "' reads system '" + system.name + "', which has no state '" +
                                   read.ref.name + "' (it has: " + known + ")");
        break;
      }
    }
  }

  const ast::Program& tree_;
  DiagnosticSink& sink_;
  const CompileOptions& options_;
  std::map<std::string, double, std::less<>> overrides_;  // CompileOptions::defines, the last value of each name
  std::set<std::string, std::less<>> overridden_;         // the names of overrides_ some #define has
  std::unique_ptr<Program> program_;
  Scope global_;
  InterpretSettings globalSettings_;
  std::vector<std::unique_ptr<Scope>> scopes_;
  std::vector<bool> arityKnown_;
  std::unordered_map<const ast::Cell*, int> cellMaster_;
  std::vector<std::pair<int, const ast::System*>> ignoreLists_;
  std::set<size_t> reportedRecursion_;
  bool readsPosition_ = false;  // set by the rule lookup when a rule reads me.x, me.y, me.z
  // Who the expressions being compiled belong to: a master's rules or interpretation, or
  // a system's placements.
  struct Reader {
    int master = -1;
    int system = -1;
  };
  struct AncestorRead {
    Reader reader;
    AncestorRef ref;
    std::string path;
    SourceSpan span;
  };
  Reader reader_;
  std::vector<AncestorRead> ancestorReads_;
  std::set<size_t> reportedAncestors_;
  int ancestorUses_ = 0;  // reads of enclosing systems compiled so far
  std::map<size_t, int> systemMaster_;  // tree index of a system -> its master
};

}  // namespace

std::unique_ptr<Program> compile(const ast::Program& tree, std::shared_ptr<const SourceFile> source,
                                 DiagnosticSink& sink, const CompileOptions& options) {
  return Compiler(tree, sink, options).run({std::move(source)});
}

std::unique_ptr<Program> compile(const ast::Program& tree, std::vector<std::shared_ptr<const SourceFile>> sources,
                                 DiagnosticSink& sink, const CompileOptions& options) {
  return Compiler(tree, sink, options).run(std::move(sources));
}

std::unique_ptr<Program> compileSource(std::string name, std::string text, DiagnosticSink& sink,
                                       const CompileOptions& options) {
  auto source = std::make_shared<const SourceFile>(std::move(name), std::move(text));
  ParsedProgram parsed = parseWithImports(std::move(source), sink);
  if (sink.hasErrors()) return nullptr;
  return compile(parsed.tree, std::move(parsed.sources), sink, options);
}

}  // namespace ontogen
