#pragma once
// The shared state of one compilation. The driver (lang/compiler.cpp) makes one
// CompileContext and runs the stages of lang/compile_stages.h over it in order; each
// stage is a set of free functions in a file of its own. What a stage leaves for a later
// one lives here: the scopes of the program and of each block, the masters made so far,
// the reads of enclosing systems to check once the system tree is known. So do the
// services every stage uses: the name lookups expressions are compiled against and the
// resolution of a module's label to its master.

#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "lang/ast.h"
#include "lang/compiler.h"
#include "model/diagnostics.h"
#include "lang/expression_compiler.h"
#include "model/program.h"

namespace ontogen::detail {

/// `age`, `tau`, `τ`: the cell's age.
bool isAgeName(std::string_view name);
/// `beta`, `β`, `lifetime`: the cell's terminal age.
bool isTerminalAgeName(std::string_view name);
/// The names of a cell's internal state, which no state variable or parameter may take.
bool isReadOnlyName(std::string_view name);
/// The slot of internal state a name reads (FrameSlot, counted after the state values), or -1.
int internalSlot(std::string_view name);

/// "file:line" of a declaration (the file's name without its folders), for messages that
/// name two places.
std::string where(const SourceSpan& span);

/// Constants visible in a scope: the block's #defines, then the program's, then built-ins.
struct ConstantScope {
  std::map<std::string, double, std::less<>> values;
  const ConstantScope* outer = nullptr;

  std::optional<double> find(std::string_view name) const;
};

/// Everything a system block sees: constants, equivs, functions, its index.
struct Scope {
  int system = -1;  ///< the L-system whose symbols are looked up first; -1: the program's top level
  ConstantScope constants;
  std::map<std::string, std::string, std::less<>> equivs;  ///< symbol -> command
  std::map<std::string, int, std::less<>> functions;       ///< name -> index into Program::functions
  const Scope* outer = nullptr;

  int findFunction(std::string_view name) const;
  const std::string* findEquiv(std::string_view symbol) const;
};

/// Who the expressions being compiled belong to: a master's rules or interpretation, or
/// a system's axiom and placements.
struct Reader {
  int master = -1;
  int system = -1;
};

/// A `parent.x` or `root.x` as written, checked once the system tree is known.
struct AncestorRead {
  Reader reader;
  AncestorRef ref;
  std::string path;
  SourceSpan span;
};

/// Frame slots by name: a rule's state variables and bound parameters.
using SlotMap = std::map<std::string, int, std::less<>>;

struct CompileContext {
  CompileContext(const ast::Program& tree, DiagnosticSink& sink, const CompileOptions& options)
      : tree(tree), sink(sink), options(options), program(std::make_unique<Program>()) {}

  const ast::Program& tree;
  DiagnosticSink& sink;
  const CompileOptions& options;
  std::unique_ptr<Program> program;

  // ---- scopes ----
  Scope global;
  InterpretSettings globalSettings;            ///< the top-level directives, each system's start
  std::vector<std::unique_ptr<Scope>> scopes;  ///< one per system, in the order of tree.systems

  // ---- #define values from outside (CompileOptions::defines) ----
  std::map<std::string, double, std::less<>> overrides;  ///< the last value of each name
  std::set<std::string, std::less<>> overridden;         ///< the names of overrides some #define has

  // ---- functions, masters ----
  std::set<size_t> reportedRecursion;  ///< functions already reported as calling themselves
  std::vector<bool> arityKnown;        ///< per master: its state count is fixed by a declaration or a first use
  /// Every master's index by its label, in the order they were added: a program of
  /// 200,000 productions looks labels up hundreds of thousands of times.
  std::map<std::string, std::vector<int>, std::less<>> mastersByLabel;
  std::unordered_map<const ast::Cell*, int> cellMaster;  ///< a declared cell -> its master
  std::map<size_t, int> systemMaster;                    ///< tree index of a system -> its master

  // ---- systems ----
  std::vector<std::pair<int, const ast::System*>> ignoreLists;  ///< every compiled system, for its symbol classes

  // ---- reads, set while expressions compile ----
  bool readsPosition = false;  ///< set by the frame lookup when an expression reads me.x, me.y, me.z
  bool readsParent = false;    ///< set by the frame lookup when an expression reads me.parent
  Reader reader;               ///< who the expressions being compiled belong to
  std::vector<AncestorRead> ancestorReads;
  std::set<size_t> reportedAncestors;  ///< spans (their begin) of ancestor reads already registered
  int ancestorUses = 0;                ///< reads of enclosing systems compiled so far

  /// The scope a master's label is resolved in: its L-system's, or the top level.
  const Scope& scopeOf(const MasterCell& master) const;

  /// Names of a scope's constants only (a #define, a default value, a grid size).
  NameLookup constantLookup(const Scope& scope) const;
  /// Adds the scope's development functions to a lookup.
  void addFunctions(NameLookup& names, const Scope& scope) const;
  /// Names of an expression compiled against a frame: the slots given (`stateCount`
  /// state values first), internal state, constants, functions, enclosing systems.
  /// The lookup refers to `slots` and `scope`: they must outlive it.
  NameLookup frameLookup(const SlotMap& slots, int stateCount, const Scope& scope);
  /// `parent.x`, `parent.parent.age`, `root.x`: one AncestorRef per distinct read, its
  /// index returned. Whether the systems at that level have the variable is checked
  /// once the tree is known (lang/program_checks.cpp).
  int registerAncestor(const std::string& path, SourceSpan span);

  /// A new master with no state yet; returns its index.
  int addMaster(std::string label, int scope, SourceSpan span);
  /// The master labelled `label` in `scope`, else the global one (-1: none), as
  /// Program::findMaster answers, through mastersByLabel.
  int findMaster(std::string_view label, int scope = -1) const;
  /// A cell's or a system's state variables and their constant defaults.
  void declareState(const std::vector<ast::Parameter>& state, int index);
  /// Finds or creates the master a module label refers to in a scope, and checks that
  /// every use gives it the same number of parameters.
  int resolveModule(const ast::Module& module, int scope, bool predecessor = false);
};

}  // namespace ontogen::detail
