#include "lang/convert/cpfg_reader.h"

#include <cctype>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lang/builtins.h"
#include "lang/convert/foreign_syntax.h"
#include "lang/convert/line_reader.h"

namespace ontogen::convert {

namespace {

// The text with its `/* */` and `//` comments made spaces, so that offsets stay the
// file's. cpfg reads its file through the C preprocessor, which removes both.
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
    }
  }
  return result;
}

// cpfg's statements: a line and the lines after it that start with a tab (its reader
// takes a line break followed by a tab as a space).
std::vector<Line> statementLines(std::string_view text) {
  std::vector<Line> result;
  for (const Line& line : splitLines(text)) {
    if (!result.empty() && line.begin < line.end && text[line.begin] == '\t')
      result.back().end = line.end;
    else
      result.push_back(line);
  }
  return result;
}

// The angle of a view file: `angle increment: D` or `angle factor: N`.
std::optional<std::string> angleOfView(std::string_view view) {
  for (const Line& line : splitLines(view)) {
    if (auto at = afterKeyword(view, line, "angle increment:")) {
      std::string value(view.substr(*at, line.end - *at));
      value.erase(0, value.find_first_not_of(" \t"));
      value.erase(value.find_last_not_of(" \t") + 1);
      if (!value.empty()) return value;
    }
    if (auto at = afterKeyword(view, line, "angle factor:")) {
      std::string value(view.substr(*at, line.end - *at));
      value.erase(0, value.find_first_not_of(" \t"));
      value.erase(value.find_last_not_of(" \t") + 1);
      if (!value.empty()) return "360 / " + value;
    }
  }
  return std::nullopt;
}

class CpfgReader {
 public:
  CpfgReader(std::string_view text, std::string_view path)
      : clean_(withoutComments(text)), syntax_(Dialect::Cpfg, clean_) {
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
        file_.derivationLength = syntax_.expression(*at, end);
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
      if (auto at = afterKeyword(clean_, line, "start:"); at && startBlock(*at, end)) continue;
      if (codeBlock(line)) {
        syntax_.fail(begin, end,
                     "a C block (Start:, End:, StartEach:, EndEach: or '{ ... }'): C code, which ontogen convert "
                     "does not translate");
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
    macro.constant = namesConstantsOnly(stop, end);
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
      if (next < end && clean_[next] == '(') continue;  // a call
      bool known = findConstant(name) != nullptr;
      for (const Define& define : file_.defines) known = known || define.name == name;
      if (!known) return false;
    }
    return true;
  }

  // `Start: {a = 2; b = a / 2; srand(7);}`: assignments to variables nothing else in the
  // file assigns are constants, `#define a 2`, and srand(N) the seed. False (the block is
  // then C code) for anything else, or a variable assigned elsewhere too.
  bool startBlock(uint32_t at, uint32_t end) {
    uint32_t a = at, b = end;
    syntax_.trim(a, b);
    if (b - a < 2 || clean_[a] != '{' || clean_[b - 1] != '}') return false;
    struct Assignment {
      std::string name;
      uint32_t begin, end;
    };
    std::vector<Assignment> assignments;
    std::optional<std::pair<uint32_t, uint32_t>> seed;
    auto isName = [&](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (uint32_t from = a + 1; from < b - 1;) {
      uint32_t semi = from;
      while (semi < b - 1 && clean_[semi] != ';') ++semi;
      uint32_t x = from, y = semi;
      syntax_.trim(x, y);
      from = semi + 1;
      if (x == y) continue;
      uint32_t stop = x;
      while (stop < y && isName(clean_[stop])) ++stop;
      uint32_t op = stop;
      while (op < y && std::isspace(static_cast<unsigned char>(clean_[op]))) ++op;
      if (stop == x || std::isdigit(static_cast<unsigned char>(clean_[x])) || op >= y) return false;
      const std::string name(clean_.substr(x, stop - x));
      if (name == "srand" && clean_[op] == '(' && clean_[y - 1] == ')' && !seed) {
        seed = std::make_pair(op + 1, y - 1);
        continue;
      }
      if (clean_[op] != '=' || (op + 1 < y && clean_[op + 1] == '=')) return false;
      for (const Assignment& other : assignments)
        if (other.name == name) return false;
      // Assigned anywhere else in the file: a variable, not a constant.
      for (size_t k = clean_.find(name); k != std::string::npos; k = clean_.find(name, k + 1)) {
        if ((k > 0 && isName(clean_[k - 1])) || (k + name.size() < clean_.size() && isName(clean_[k + name.size()])))
          continue;
        if (k >= a && k < b) continue;
        size_t after = k + name.size();
        while (after < clean_.size() && (clean_[after] == ' ' || clean_[after] == '\t')) ++after;
        if (after < clean_.size() && clean_[after] == '=' && (after + 1 >= clean_.size() || clean_[after + 1] != '='))
          return false;
      }
      assignments.push_back({name, op + 1, y});
    }
    for (const Assignment& assignment : assignments)
      file_.defines.push_back({assignment.name, syntax_.expression(assignment.begin, assignment.end), line_});
    if (seed) file_.seed = syntax_.expression(seed->first, seed->second);
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
};

}  // namespace

LSystemFile readCpfg(std::string_view text, std::string_view path, std::string_view view) {
  CpfgReader reader(text, path);
  LSystemFile file = reader.read();
  file.angle = angleOfView(view);
  return file;
}

}  // namespace ontogen::convert
