#pragma once
// What `ontogen convert` reads from another tool's L-system file (cpfg's .l, L-Py's
// .lpy), before it is written in the cell language: the readers (cpfg_reader.h,
// lpy_reader.h) fill one LSystemFile, the writer prints it as an lsystem block. Labels
// and expressions are held already spelt as ontogen spells them, so the writer only
// lays them out; statements keep their order, so sections, groups and ignore lists
// stay where the file put them.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ontogen::convert {

/// The text of a file beside the converted one, named as the view file names it;
/// nullopt where there is none or it cannot be read.
using SideFileReader = std::function<std::optional<std::string>(const std::string& name)>;

/// The tool whose file this is.
enum class Dialect { Cpfg, LPy };

/// Bytes [begin, end) of the file read: where a statement came from, so that what the
/// compiler finds in the converted text is shown at the file's own line. Empty
/// (begin == end) for text the converter writes of itself.
struct SourceRange {
  uint32_t begin = 0;
  uint32_t end = 0;
  bool known() const { return end > begin; }
};

/// A construct converted with a loss the user should know of, at its place in the file.
struct ConvertWarning {
  SourceRange at;
  std::string message;
};

/// "cpfg" or "L-Py".
std::string_view dialectName(Dialect dialect);

/// One module of an axiom, predecessor, context or successor.
struct ModuleText {
  std::string label;              ///< as the cell language spells it: `F`, `+`, `?P`, `*`
  bool hasArgs = false;           ///< `X()` and `X` differ
  std::vector<std::string> args;  ///< cell-language expressions (patterns: parameter names)
};

enum class StatementKind {
  Production,    ///< `left < predecessor > right : condition -> successors : probability`
  Section,       ///< `production:`, `decomposition:`, `homomorphism:`
  MaximumDepth,  ///< `maximum depth: N` of the section before it
  Group,         ///< `group N:`: the group of the productions after it
  Ignore,        ///< `ignore: A B`
  Consider,      ///< `consider: A B`
};

struct Statement {
  StatementKind kind = StatementKind::Production;
  std::string word;                  ///< Section: its name; MaximumDepth, Group: the value
  std::vector<std::string> symbols;  ///< Ignore, Consider
  std::vector<ModuleText> left;      ///< Production: the left context, in text order
  std::string leftArrow = "<";       ///< `<`, or `<<` for a new left context
  ModuleText predecessor;
  std::vector<ModuleText> right;
  std::string rightArrow = ">";        ///< `>`, or `>>` for a new right context
  std::string condition;               ///< empty: none
  std::vector<ModuleText> successors;  ///< empty: the empty word
  std::string probability;             ///< empty: none
  /// A way of an L-Py body's random choice that produces nothing, written as the module
  /// itself: L-Py would try the module's later productions instead, so there must be none.
  bool keepsModule = false;
  SourceRange origin;                  ///< the line or lines of the file it was read from
};

struct Define {
  std::string name;
  std::string value;  ///< a cell-language expression
  SourceRange origin;
};

/// L-Py's `module A, B : scale = N`.
struct ScaleDeclaration {
  std::string scale;                ///< a whole number, 0 to 255
  std::vector<std::string> labels;
  SourceRange origin;
};

struct LSystemFile {
  Dialect dialect = Dialect::Cpfg;
  std::string name;                                          ///< the block's name, an identifier
  std::vector<Define> defines;
  std::optional<std::string> angle;  ///< degrees: the default turn
  std::optional<std::string> seed;
  std::optional<std::string> derivationLength;  ///< steps: `#until`
  SourceRange derivationLengthOrigin;
  std::optional<std::string> useGroup;  ///< `use group:`, an expression of time
  SourceRange useGroupOrigin;
  std::vector<ModuleText> axiom;
  SourceRange axiomOrigin;
  std::vector<Statement> statements;
  std::vector<ConvertWarning> warnings;
  /// Module scales, written as `scale N:` lines where `multiscale` (L-Py's option
  /// 'String matching' set to its multiscale tree), `level N:` lines where `levels` too
  /// (its multi-level tree); otherwise they change no match.
  std::vector<ScaleDeclaration> scales;
  bool multiscale = false;
  bool levels = false;
};

/// A converted program and, for each of its lines (index: line − 1), the range of the
/// file it was written from.
struct CellProgram {
  std::string text;
  std::vector<SourceRange> lineOrigins;
};

/// The file as a cell-language program: one lsystem block, with a comment naming the
/// file it came from. A block whose labels include digits gets `#letters`.
CellProgram writeCellProgram(const LSystemFile& file, std::string_view sourceName);

/// The bytes of the line writeCellProgram writes for `statement`, its newline included.
size_t statementLineBytes(const Statement& statement);

/// A block name from a file name: its stem, other characters than letters, digits and
/// '_' made '_', a leading digit prefixed with "l_".
std::string blockNameOf(std::string_view path);

}  // namespace ontogen::convert
