#include "lang/convert/cpfg_reader.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "model/builtins.h"
#include "lang/convert/foreign_syntax.h"
#include "lang/convert/line_reader.h"

namespace ontogen::convert {

namespace {

// The text with its `/* */` and `//` comments and its backslashes before a line break
// made spaces, so that offsets stay the file's. cpfg reads its file through the C
// preprocessor, which removes the comments and joins such lines.
std::string withoutComments(std::string_view text) {
  std::string result(text);
  for (size_t at = 0; at + 1 < result.size(); ++at) {
    if (result[at] == '/' && result[at + 1] == '*') {
      size_t close = result.find("*/", at + 2);
      size_t stop = close == std::string::npos ? result.size() : close + 2;
      for (size_t i = at; i < stop; ++i)
        if (result[i] != '\n') result[i] = ' ';
      at = stop - 1;
    } else if (result[at] == '/' && result[at + 1] == '/') {
      for (; at < result.size() && result[at] != '\n'; ++at) result[at] = ' ';
    } else if (result[at] == '\\' && (result[at + 1] == '\n' || (result[at + 1] == '\r' && at + 2 < result.size() &&
                                                                result[at + 2] == '\n'))) {
      // The preprocessor joins a line that ends in a backslash to the next.
      for (; result[at] != '\n'; ++at) result[at] = ' ';
      result[at] = ' ';
    }
  }
  return result;
}

// Whether the statement [begin, end) opens a C block it does not close: a `{` before any
// `-->` (a block of Start: and the like, or of a production's condition) with fewer `}`
// after it. Braces after the arrow are cpfg's polygon modules, which a successor may open
// and another close.
bool opensCBlock(std::string_view text, Line line) {
  const std::string_view statement = text.substr(line.begin, line.end - line.begin);
  const size_t arrow = statement.find("-->");
  const std::string_view before = statement.substr(0, arrow);
  if (arrow != std::string_view::npos) return false;  // the block, if any, closed before it
  int depth = 0;
  for (char c : before) depth += c == '{' ? 1 : c == '}' ? -1 : 0;
  return depth > 0;
}

// cpfg's statements: a line and the lines after it that start with a tab (its reader
// takes a line break followed by a tab as a space), and a C block over several lines, to
// the line that closes it (the C code between its braces is read as one text).
std::vector<Line> statementLines(std::string_view text) {
  std::vector<Line> result;
  for (const Line& line : splitLines(text)) {
    if (!result.empty() && ((line.begin < line.end && text[line.begin] == '\t') || opensCBlock(text, result.back())))
      result.back().end = line.end;
    else
      result.push_back(line);
  }
  return result;
}

// The angle of a view file: `angle increment: D` or `angle factor: N`, the last of
// them (cpfg reads its labels in order, each setting the angle); cpfg's 45 degrees when
// it has neither.
std::string angleOfView(std::string_view view) {
  std::string angle = "45";
  for (const Line& line : splitLines(view)) {
    for (std::string_view label : {"angle increment:", "angle factor:"})
      if (auto at = afterKeyword(view, line, label)) {
        std::string value(view.substr(*at, line.end - *at));
        value.erase(0, value.find_first_not_of(" \t"));
        value.erase(value.find_last_not_of(" \t") + 1);
        if (!value.empty()) angle = label == "angle factor:" ? "360 / " + value : value;
      }
  }
  return angle;
}

// A turn that takes the default angle: `+` rather than `+(30)`.
bool turnsByDefault(const std::vector<ModuleText>& word) {
  return std::any_of(word.begin(), word.end(), [](const ModuleText& module) {
    static constexpr std::string_view kTurns[] = {"+", "-", "&", "^", "/", "\\"};
    return !module.hasArgs && std::find(std::begin(kTurns), std::end(kTurns), module.label) != std::end(kTurns);
  });
}

// Without a view file, the first line with a turn by the default angle warns: cpfg
// would turn it by the view file's angle, which the converter cannot know.
void warnOfMissingView(LSystemFile& file, std::string_view path) {
  SourceRange first;
  if (turnsByDefault(file.axiom)) first = file.axiomOrigin;
  for (const Statement& s : file.statements)
    if (s.kind == StatementKind::Production && turnsByDefault(s.successors) &&
        (!first.known() || s.origin.begin < first.begin)) {
      first = s.origin;
      break;
    }
  if (!first.known()) return;
  const std::string stem = std::filesystem::path(path).stem().string();
  file.warnings.push_back(
      {first, "no view file (neither one that a cpfg command in the folder's 'specifications' names with this "
              "file, nor '" + stem + ".v' beside it): cpfg turns by its view file's angle increment, which is "
              "unknown here, and the turns without an angle take ontogen's default of 90 degrees"});
}

class CpfgReader {
 public:
  CpfgReader(std::string_view text, std::string_view path, std::vector<SampledFunction> functions, uint64_t maxBytes)
      : clean_(withoutComments(text)), syntax_(Dialect::Cpfg, clean_, maxBytes) {
    syntax_.splineFunctions = std::move(functions);
    file_.dialect = Dialect::Cpfg;
    file_.name = blockNameOf(path);
  }

  LSystemFile read() {
    bool ended = false;
    int lsystems = 0;
    for (const Line& line : statementLines(clean_)) {
      uint32_t begin = firstNonSpace(clean_, line), end = line.end;
      syntax_.trim(begin, end);
      if (begin == end) continue;
      stamp();
      line_ = {begin, end};
      if (ended) syntax_.fail(begin, end, "text after endlsystem: ontogen convert reads one L-system per file", false);
      if (auto at = afterKeyword(clean_, line, "lsystem:")) {
        if (++lsystems > 1)
          syntax_.fail(begin, end, "a second L-system (cpfg's sub-L-systems) cannot be translated yet");
        (void)at;
        continue;
      }
      if (auto at = afterKeyword(clean_, line, "endlsystem")) {
        ended = true;
        continue;
      }
      if (auto at = afterKeyword(clean_, line, "#define")) {
        define(*at, end);
        continue;
      }
      if (auto at = afterKeyword(clean_, line, "#include")) {
        syntax_.fail(begin, end, "#include cannot be translated: put the included text in the file");
        continue;
      }
      if (auto at = keyword(line, {"#ignore", "ignore:"})) {
        symbols(StatementKind::Ignore, *at, end);
        continue;
      }
      if (auto at = keyword(line, {"#consider", "consider:"})) {
        symbols(StatementKind::Consider, *at, end);
        continue;
      }
      if (auto at = afterLabel(clean_, line, "seed")) {
        file_.seed = syntax_.expression(*at, end);
        continue;
      }
      if (auto at = afterLabel(clean_, line, "derivation length")) {
        uint32_t a = *at, b = end;
        syntax_.trim(a, b);
        // 0: cpfg shows the axiom, interpreted; ontogen's #until is at least 1, the same
        // word where no production rewrites it (checked at the end).
        if (clean_.substr(a, b - a) == "0") zeroLength_ = SourceRange{a, b};
        file_.derivationLength = zeroLength_ ? "1" : syntax_.expression(*at, end);
        file_.derivationLengthOrigin = line_;
        continue;
      }
      if (auto at = afterLabel(clean_, line, "axiom")) {
        file_.axiom = syntax_.modules(*at, end, false);
        file_.axiomOrigin = line_;
        continue;
      }
      if (auto at = afterLabel(clean_, line, "maximum depth")) {
        Statement s;
        s.kind = StatementKind::MaximumDepth;
        s.word = syntax_.maximumDepth(*at, end);
        file_.statements.push_back(std::move(s));
        continue;
      }
      if (auto section = sectionOf(line)) {
        Statement s;
        s.kind = StatementKind::Section;
        s.word = *section;
        syntax_.inHomomorphism = *section == "homomorphism";
        file_.statements.push_back(std::move(s));
        continue;
      }
      if (auto at = afterKeyword(clean_, line, "endgroup")) {
        group("0");
        continue;
      }
      if (auto at = afterKeyword(clean_, line, "group")) {
        uint32_t stop = end;
        if (stop > *at && clean_[stop - 1] == ':') --stop;
        group(syntax_.expression(*at, stop));
        continue;
      }
      if (auto at = afterKeyword(clean_, line, "define:")) {
        arrays(*at, end);
        continue;
      }
      if (!stepBlocksRead_ && (afterKeyword(clean_, line, "start:") || afterKeyword(clean_, line, "starteach:") ||
                               afterKeyword(clean_, line, "endeach:") || afterKeyword(clean_, line, "end:"))) {
        stepBlocksRead_ = true;
        stepBlocksOk_ = stepBlocks();
      }
      if (stepBlocksOk_ && (afterKeyword(clean_, line, "start:") || afterKeyword(clean_, line, "starteach:") ||
                            afterKeyword(clean_, line, "endeach:") || afterKeyword(clean_, line, "end:")))
        continue;
      if (codeBlock(line)) {
        syntax_.fail(begin, end,
                     "a C block (Start:, End:, StartEach:, EndEach: or '{ ... }'): C code, which ontogen convert "
                     "does not translate" +
                         (stepBlocksWhy_.empty() ? std::string() : " (" + stepBlocksWhy_ + ")"));
        continue;
      }
      if (syntax_.find(begin, end, "->") < end) {
        file_.statements.push_back(syntax_.production(begin, end));
        continue;
      }
      {
        syntax_.fail(begin, end,
                     "cannot read this line of a cpfg file (expected a production with '-->' or a "
                     "keyword such as Axiom:)",
                     false);
      }
    }
    stamp();
    if (zeroLength_ && rewritesTheAxiom(file_)) {
      syntax_.fail(zeroLength_->begin, zeroLength_->end,
                   "derivation length 0 (the word is the axiom) where productions or decompositions would "
                   "rewrite it: ontogen's #until is at least 1; ask for the axiom with word --at 0");
    }
    file_.warnings = std::move(syntax_.warnings);
    return std::move(file_);
  }

  LSystemFile file_;

 private:
  // The statements read from the line before have its place.
  void stamp() {
    for (; stamped_ < file_.statements.size(); ++stamped_)
      if (!file_.statements[stamped_].origin.known()) file_.statements[stamped_].origin = line_;
  }

  std::optional<uint32_t> keyword(const Line& line, std::initializer_list<std::string_view> words) const {
    for (std::string_view word : words)
      if (auto at = afterKeyword(clean_, line, word)) return at;
    return std::nullopt;
  }

  // `decomposition`, `homomorphism` (optionally `: ` and cpfg's `no warnings`), `production:`.
  std::optional<std::string> sectionOf(const Line& line) const {
    for (std::string_view word : {"decomposition", "homomorphism", "production"})
      if (auto at = afterKeyword(clean_, line, word)) {
        std::string rest(clean_.substr(*at, line.end - *at));
        for (char& c : rest) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        rest.erase(0, rest.find_first_not_of(" \t:"));
        rest.erase(rest.find_last_not_of(" \t") + 1);
        if (rest.empty() || rest == "warnings" || rest == "no warnings") return std::string(word);
      }
    return std::nullopt;
  }

  bool codeBlock(const Line& line) const {
    for (std::string_view word : {"start:", "end:", "starteach:", "endeach:", "{"})
      if (afterKeyword(clean_, line, word)) return true;
    return false;
  }

  // `Define: { array c[3] = {1, 3, 2}; array len[2] = {1, 0.85}; }`: arrays of constants
  // (ForeignSyntax::arrays). C fills the elements an initialiser leaves out with 0.
  void arrays(uint32_t at, uint32_t end) {
    uint32_t open = at;
    while (open < end && std::isspace(static_cast<unsigned char>(clean_[open]))) ++open;
    if (open == end || clean_[open] != '{' || clean_[end - 1] != '}')
      syntax_.fail(at, end, "expected a Define: block '{ ... }'", false);
    for (uint32_t from = open + 1; from < end - 1;) {
      uint32_t semicolon = from;
      for (int depth = 0; semicolon < end - 1 && (depth > 0 || clean_[semicolon] != ';'); ++semicolon) {
        if (clean_[semicolon] == '{') ++depth;
        if (clean_[semicolon] == '}') --depth;
      }
      uint32_t a = from, b = semicolon;
      syntax_.trim(a, b);
      from = semicolon + 1;
      if (a == b) continue;
      array(a, b);
    }
  }

  // `array NAME[N] = {v, ...}`.
  void array(uint32_t a, uint32_t b) {
    auto refuse = [&] {
      syntax_.fail(a, b,
                   "a statement of a Define: block other than an array of constants of one dimension, "
                   "'array c[3] = {1, 3, 2}': C code, which ontogen convert does not translate");
    };
    auto at = afterKeyword(clean_, Line{a, b}, "array");
    if (!at) refuse();
    uint32_t x = *at;
    while (x < b && std::isspace(static_cast<unsigned char>(clean_[x]))) ++x;
    uint32_t stop = x;
    while (stop < b && (std::isalnum(static_cast<unsigned char>(clean_[stop])) || clean_[stop] == '_')) ++stop;
    const std::string name(clean_.substr(x, stop - x));
    const uint32_t close = syntax_.find(stop, b, "]");
    const uint32_t equals = syntax_.find(stop, b, "=");
    if (name.empty() || stop >= b || clean_[stop] != '[' || close >= equals || equals == b) refuse();
    uint32_t sa = stop + 1, sb = close;
    syntax_.trim(sa, sb);
    const std::string size(clean_.substr(sa, sb - sa));
    char* last = nullptr;
    const long count = std::strtol(size.c_str(), &last, 10);
    if (size.empty() || last != size.c_str() + size.size() || count < 1 || count > 4096) refuse();
    uint32_t va = equals + 1, vb = b;
    syntax_.trim(va, vb);
    if (va >= vb || clean_[va] != '{' || clean_[vb - 1] != '}') refuse();
    std::vector<std::string> elements;
    for (uint32_t from = va + 1; from < vb - 1;) {
      const uint32_t comma = syntax_.find(from, vb - 1, ",");
      if (!namesConstantsOnly(from, comma)) refuse();
      elements.push_back(syntax_.expression(from, comma));
      from = comma + 1;
    }
    if (elements.size() > static_cast<size_t>(count))
      syntax_.fail(va, vb, "more values than the array '" + name + "' holds", false);
    elements.resize(static_cast<size_t>(count), "0");
    syntax_.arrays[name] = std::move(elements);
  }

  void define(uint32_t at, uint32_t end) {
    while (at < end && std::isspace(static_cast<unsigned char>(clean_[at]))) ++at;
    uint32_t stop = at;
    while (stop < end && (std::isalnum(static_cast<unsigned char>(clean_[stop])) || clean_[stop] == '_')) ++stop;
    if (stop == at) syntax_.fail(at, end, "expected a name after #define", false);
    if (stop < end && clean_[stop] == '(') {
      macro(std::string(clean_.substr(at, stop - at)), stop, end);
      return;
    }
    std::string name(clean_.substr(at, stop - at));
    // Read as text where it stands among operators (ForeignSyntax::macros).
    ForeignSyntax::Function macro;
    macro.begin = stop;
    macro.end = end;
    // A value that starts as a module string, `[,(3)F(1)]`, is put in where the name
    // stands among modules (ForeignSyntax::modules); no expression.
    uint32_t first = stop;
    while (first < end && std::isspace(static_cast<unsigned char>(clean_[first]))) ++first;
    const bool word = first < end && clean_[first] == '[';
    macro.constant = !word && namesConstantsOnly(stop, end);
    if (macro.constant) file_.defines.push_back({name, syntax_.expression(stop, end), line_});
    syntax_.macros[std::move(name)] = macro;
  }

  // Whether the names of [begin, end), other than those of calls, are constants: earlier
  // #defines of constants and the cell language's own constants.
  bool namesConstantsOnly(uint32_t begin, uint32_t end) const {
    for (uint32_t at = begin; at < end;) {
      const char c = clean_[at];
      if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
        while (at < end && (std::isalnum(static_cast<unsigned char>(clean_[at])) || clean_[at] == '.')) ++at;
        continue;
      }
      if (!(std::isalpha(static_cast<unsigned char>(c)) || c == '_')) {
        ++at;
        continue;
      }
      uint32_t stop = at;
      while (stop < end && (std::isalnum(static_cast<unsigned char>(clean_[stop])) || clean_[stop] == '_')) ++stop;
      const std::string_view name = std::string_view(clean_).substr(at, stop - at);
      uint32_t next = stop;
      while (next < end && std::isspace(static_cast<unsigned char>(clean_[next]))) ++next;
      at = stop;
      // A call; one that draws a random number is drawn anew where C puts the text.
      if (next < end && clean_[next] == '(') {
        if (name == "ran" || name == "nran" || name == "bran" || name == "biran" || name == "srand") return false;
        continue;
      }
      bool known = findConstant(name) != nullptr;
      for (const Define& define : file_.defines) known = known || define.name == name;
      if (!known) return false;
    }
    return true;
  }

  // cpfg's blocks of C around the derivation: Start: runs once before it, StartEach: and
  // EndEach: before and after each step, End: after it. The assignments in them that no
  // production assigns are read (all of the file's blocks together, at the first):
  //   Start: {a = 2; b = a / 2; srand(7);}   constants, #define a 2, and the seed;
  //   Start: {n = A;} StartEach: {n = n + D;}  a counter: (A) + (D) * time at the
  //                                            step fired at time (EndEach: time - 1);
  //   StartEach: {p = EXPR;}                   its value at that step (EXPR of counters
  //                                            and constants).
  // printf(...) prints and changes no word. Anything else leaves every block C code.
  struct Assignment {
    std::string name;
    uint32_t begin = 0, end = 0;  // the value
  };
  struct StepBlock {
    bool seen = false;
    uint32_t begin = 0, end = 0;  // the braces
    std::vector<Assignment> assignments;
    std::optional<std::pair<uint32_t, uint32_t>> seed;
  };
  enum Hook { kStart, kStartEach, kEndEach, kEnd, kHooks };

  // The statements of `{ ... }` at [at, end).
  bool readStepBlock(uint32_t at, uint32_t end, StepBlock& block, std::string& why) const {
    uint32_t a = at, b = end;
    syntax_.trim(a, b);
    if (block.seen || b - a < 2 || clean_[a] != '{' || clean_[b - 1] != '}') {
      why = block.seen ? "a second block of one kind" : "a block other than '{ ... }'";
      return false;
    }
    block.seen = true;
    block.begin = a;
    block.end = b;
    for (uint32_t from = a + 1; from < b - 1;) {
      uint32_t semi = from;
      for (char quote = 0; semi < b - 1 && (quote || clean_[semi] != ';'); ++semi)
        if (clean_[semi] == '"') quote = quote ? 0 : '"';
      uint32_t x = from, y = semi;
      syntax_.trim(x, y);
      from = semi + 1;
      if (x == y) continue;
      uint32_t stop = x;
      while (stop < y && isNameChar(clean_[stop])) ++stop;
      uint32_t op = stop;
      while (op < y && std::isspace(static_cast<unsigned char>(clean_[op]))) ++op;
      const std::string statement(clean_.substr(x, y - x));
      why = "the statement '" + statement + "', which is no assignment, printf or srand";
      if (stop == x || std::isdigit(static_cast<unsigned char>(clean_[x])) || op >= y) return false;
      const std::string name(clean_.substr(x, stop - x));
      if (clean_[op] == '(' && clean_[y - 1] == ')') {
        if (name == "printf") continue;
        if (name != "srand" || block.seed) return false;
        block.seed = std::make_pair(op + 1, y - 1);
        continue;
      }
      if (clean_[op] != '=' || (op + 1 < y && clean_[op + 1] == '=')) return false;
      block.assignments.push_back({name, op + 1, y});
    }
    return true;
  }

  static bool isNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

  // Whether `name` is assigned outside the blocks (in a production's block).
  bool assignedElsewhere(const std::string& name, const StepBlock (&blocks)[kHooks]) const {
    for (size_t k = clean_.find(name); k != std::string::npos; k = clean_.find(name, k + 1)) {
      if ((k > 0 && isNameChar(clean_[k - 1])) || (k + name.size() < clean_.size() && isNameChar(clean_[k + name.size()])))
        continue;
      bool inside = false;
      for (const StepBlock& block : blocks) inside = inside || (block.seen && k >= block.begin && k < block.end);
      if (inside) continue;
      size_t after = k + name.size();
      while (after < clean_.size() && (clean_[after] == ' ' || clean_[after] == '\t')) ++after;
      if (after < clean_.size() && clean_[after] == '=' && (after + 1 >= clean_.size() || clean_[after + 1] != '='))
        return true;
    }
    return false;
  }

  // `name = name + D`, `name = name - D`, `name = D + name` with D constant: D, signed.
  std::optional<std::string> increment(const Assignment& assignment) {
    uint32_t a = assignment.begin, b = assignment.end;
    syntax_.trim(a, b);
    const std::string_view value = std::string_view(clean_).substr(a, b - a);
    const std::string& name = assignment.name;
    auto isNameAt = [&](size_t at) {
      return value.compare(at, name.size(), name) == 0 &&
             (at + name.size() == value.size() || !isNameChar(value[at + name.size()]));
    };
    if (isNameAt(0)) {
      size_t op = name.size();
      while (op < value.size() && std::isspace(static_cast<unsigned char>(value[op]))) ++op;
      if (op >= value.size() || (value[op] != '+' && value[op] != '-')) return std::nullopt;
      const uint32_t from = a + static_cast<uint32_t>(op) + 1;
      if (syntax_.find(from, b, "+") < b || syntax_.find(from, b, "-") < b || !namesConstantsOnly(from, b))
        return std::nullopt;
      return std::string(value[op] == '-' ? "-" : "") + "(" + syntax_.expression(from, b) + ")";
    }
    // D + name
    if (value.size() > name.size() && isNameAt(value.size() - name.size()) &&
        !isNameChar(value[value.size() - name.size() - 1])) {
      size_t op = value.size() - name.size();
      while (op > 0 && std::isspace(static_cast<unsigned char>(value[op - 1]))) --op;
      if (op == 0 || value[op - 1] != '+') return std::nullopt;
      const uint32_t to = a + static_cast<uint32_t>(op) - 1;
      if (syntax_.find(a, to, "+") < to || syntax_.find(a, to, "-") < to || !namesConstantsOnly(a, to))
        return std::nullopt;
      return "(" + syntax_.expression(a, to) + ")";
    }
    return std::nullopt;
  }

  // All of the file's step blocks read as above; false if any statement of them is
  // otherwise (each block then stays C code, an error at its line).
  bool stepBlocks() {
    StepBlock blocks[kHooks];
    static constexpr std::string_view kWords[kHooks] = {"start:", "starteach:", "endeach:", "end:"};
    for (const Line& line : statementLines(clean_))
      for (int hook = 0; hook < kHooks; ++hook)
        if (auto at = afterKeyword(clean_, line, kWords[hook]))
          if (!readStepBlock(*at, line.end, blocks[hook], stepBlocksWhy_)) return false;
    if (!blocks[kEnd].assignments.empty() || blocks[kStartEach].seed || blocks[kEndEach].seed) {
      stepBlocksWhy_ = blocks[kEnd].assignments.empty() ? "srand in StartEach: or EndEach: (a seed each step)"
                                                        : "assignments in End: (after the derivation)";
      return false;
    }
    // Each name: the assignments of each block.
    auto count = [](const StepBlock& block, const std::string& name) {
      size_t n = 0;
      for (const Assignment& assignment : block.assignments) n += assignment.name == name;
      return n;
    };
    std::vector<std::string> names;
    for (const StepBlock& block : blocks)
      for (const Assignment& assignment : block.assignments)
        if (std::find(names.begin(), names.end(), assignment.name) == names.end()) names.push_back(assignment.name);
    for (const std::string& name : names) {
      if (assignedElsewhere(name, blocks)) {
        stepBlocksWhy_ = "the variable '" + name + "', which a production's block assigns too (state between "
                         "productions)";
        return false;
      }
      if (count(blocks[kStart], name) > 1 || count(blocks[kStartEach], name) > 1 || count(blocks[kEndEach], name) > 1) {
        stepBlocksWhy_ = "the variable '" + name + "', assigned twice in one block";
        return false;
      }
    }
    std::vector<Define> defines;
    struct Counter {
      std::string start, step;
      bool atStart;  // incremented in StartEach:
    };
    std::map<std::string, Counter> counters;
    const size_t defined = file_.defines.size();
    for (const Assignment& assignment : blocks[kStart].assignments) {
      const std::string& name = assignment.name;
      const bool each = count(blocks[kStartEach], name) > 0, end = count(blocks[kEndEach], name) > 0;
      if (!each && !end) {
        file_.defines.push_back({name, syntax_.expression(assignment.begin, assignment.end), line_});
        continue;
      }
      if (each && end) {
        stepBlocksWhy_ = "the variable '" + name + "', which both StartEach: and EndEach: change";
        return false;
      }
      const StepBlock& block = blocks[each ? kStartEach : kEndEach];
      const Assignment& change =
          *std::find_if(block.assignments.begin(), block.assignments.end(), [&](const Assignment& x) { return x.name == name; });
      std::optional<std::string> step = increment(change);
      // A counter (not a value of StartEach: that reads the Start: value).
      if (!step && each) continue;
      if (!step || !namesConstantsOnly(assignment.begin, assignment.end)) {
        stepBlocksWhy_ = "the variable '" + name + "', which EndEach: changes otherwise than by a constant step";
        file_.defines.resize(defined);
        return false;
      }
      counters[name] = {syntax_.expression(assignment.begin, assignment.end), *step, each};
    }
    auto counterAt = [](const Counter& counter, bool after) {
      return "(" + counter.start + ") + " + counter.step + " * " + (after ? "time" : "(time - 1)");
    };
    // Before StartEach: runs, each counter has its value of the step before.
    for (const auto& [name, counter] : counters) syntax_.stepVariables[name] = {counterAt(counter, false), false, ""};
    for (const Assignment& assignment : blocks[kStartEach].assignments) {
      const std::string& name = assignment.name;
      if (auto counter = counters.find(name); counter != counters.end()) {
        syntax_.stepVariables[name] = {counterAt(counter->second, true), false, ""};
        continue;
      }
      // A value of each step: of constants, counters and the values before it.
      if (!valueOfStep(assignment)) {
        stepBlocksWhy_ = "the variable '" + name + "', whose value of each step reads its own value or a variable "
                         "that is no constant, counter or value of the step";
        file_.defines.resize(defined);
        syntax_.stepVariables.clear();
        return false;
      }
      syntax_.stepVariables[name] = {syntax_.expression(assignment.begin, assignment.end),
                                     count(blocks[kEndEach], name) > 0, ""};
    }
    for (const Assignment& assignment : blocks[kEndEach].assignments) {
      if (auto counter = counters.find(assignment.name); counter != counters.end()) {
        // The homomorphism reads the word of `time` steps, each ended by this block.
        syntax_.stepVariables[assignment.name].stepEnd = true;
        syntax_.stepVariables[assignment.name].afterStep = counterAt(counter->second, true);
        continue;
      }
      if (count(blocks[kStartEach], assignment.name) == 0) {  // read before EndEach: assigns it
        stepBlocksWhy_ = "the variable '" + assignment.name + "', which EndEach: sets and the next step reads";
        file_.defines.resize(defined);
        syntax_.stepVariables.clear();
        return false;
      }
    }
    if (blocks[kStart].seed) file_.seed = syntax_.expression(blocks[kStart].seed->first, blocks[kStart].seed->second);
    return true;
  }

  // Whether the value names constants, counters and values of the step only.
  bool valueOfStep(const Assignment& assignment) const {
    for (uint32_t at = assignment.begin; at < assignment.end;) {
      const char c = clean_[at];
      if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
        while (at < assignment.end && (isNameChar(clean_[at]) || clean_[at] == '.')) ++at;
        continue;
      }
      if (!(std::isalpha(static_cast<unsigned char>(c)) || c == '_')) {
        ++at;
        continue;
      }
      uint32_t stop = at;
      while (stop < assignment.end && isNameChar(clean_[stop])) ++stop;
      const std::string_view name = std::string_view(clean_).substr(at, stop - at);
      uint32_t next = stop;
      while (next < assignment.end && std::isspace(static_cast<unsigned char>(clean_[next]))) ++next;
      at = stop;
      if (next < assignment.end && clean_[next] == '(') continue;  // a call
      if (name == assignment.name) return false;
      bool known = findConstant(name) != nullptr || syntax_.stepVariables.count(name) > 0 ||
                   syntax_.macros.count(name) > 0;
      for (const Define& define : file_.defines) known = known || define.name == name;
      if (!known) return false;
    }
    return true;
  }

  // `#define f(x, y) EXPR`, a C macro with parameters: inlined where it is used after
  // this line (see ForeignSyntax::inlined for where C's textual replacement would read
  // otherwise).
  void macro(std::string name, uint32_t open, uint32_t end) {
    uint32_t close = open + 1;
    while (close < end && clean_[close] != ')' && clean_[close] != '(') ++close;
    if (close == end || clean_[close] != ')') syntax_.fail(open, end, "the parameters of a macro without their ')'", false);
    ForeignSyntax::Function function;
    for (uint32_t from = open + 1; from < close;) {
      uint32_t comma = from;
      while (comma < close && clean_[comma] != ',') ++comma;
      uint32_t a = from, b = comma;
      syntax_.trim(a, b);
      bool isName = a < b && !std::isdigit(static_cast<unsigned char>(clean_[a]));
      for (uint32_t k = a; k < b; ++k)
        isName = isName && (std::isalnum(static_cast<unsigned char>(clean_[k])) || clean_[k] == '_');
      if (!isName) syntax_.fail(a, b, "a macro's parameter is a name", false);
      function.parameters.emplace_back(clean_.substr(a, b - a));
      from = comma + 1;
    }
    uint32_t a = close + 1, b = end;
    syntax_.trim(a, b);
    if (a == b) syntax_.fail(open, end, "a macro without a value: ontogen convert reads macros of one expression");
    function.begin = a;
    function.end = b;
    syntax_.functions[std::move(name)] = std::move(function);
  }

  void symbols(StatementKind kind, uint32_t at, uint32_t end) {
    Statement s;
    s.kind = kind;
    s.symbols = syntax_.symbols(at, end);
    // Brackets in a consider: list keep them read, as the cell language always does.
    auto bracket = [](const std::string& symbol) { return symbol == "[" || symbol == "]"; };
    if (kind == StatementKind::Consider && !std::all_of(s.symbols.begin(), s.symbols.end(), bracket))
      std::erase_if(s.symbols, bracket);
    file_.statements.push_back(std::move(s));
  }

  void group(std::string value) {
    Statement s;
    s.kind = StatementKind::Group;
    s.word = std::move(value);
    file_.statements.push_back(std::move(s));
  }

  std::string clean_;
  ForeignSyntax syntax_;
  SourceRange line_;
  size_t stamped_ = 0;
  bool stepBlocksRead_ = false;
  bool stepBlocksOk_ = false;
  std::string stepBlocksWhy_;  ///< why the blocks stay C code
  std::optional<SourceRange> zeroLength_;  ///< `derivation length: 0`, its value
};

}  // namespace

LSystemFile readCpfg(std::string_view text, std::string_view path, std::optional<std::string_view> view,
                     const SideFileReader& readSideFile, uint64_t maxBytes) {
  CpfgReader reader(text, path, viewFunctions(view.value_or(""), readSideFile), maxBytes);
  LSystemFile file = reader.read();
  if (view)
    file.angle = angleOfView(*view);
  else
    warnOfMissingView(file, path);
  return file;
}

}  // namespace ontogen::convert
