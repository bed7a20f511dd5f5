#include "lang/convert/lpy_reader.h"

#include <cctype>
#include <string>

#include "lang/convert/foreign_syntax.h"
#include "lang/convert/line_reader.h"

namespace ontogen::convert {

namespace {

constexpr std::string_view kInitialisation = "###### INITIALISATION ######";

bool isNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// The text with Python's `#` comments made spaces (not `#define`), offsets kept.
std::string withoutComments(std::string_view text) {
  std::string result(text);
  bool lineStart = true;
  char quote = 0;
  for (size_t i = 0; i < result.size(); ++i) {
    const char c = result[i];
    if (c == '\n') {
      lineStart = true;
      quote = 0;
      continue;
    }
    if (quote) {
      if (c == quote) quote = 0;
      continue;
    }
    if (c == '"' || c == '\'') quote = c;
    if (c == '#' && !(lineStart && result.compare(i, 7, "#define") == 0)) {
      while (i < result.size() && result[i] != '\n') result[i++] = ' ';
      --i;
      continue;
    }
    if (!std::isspace(static_cast<unsigned char>(c))) lineStart = false;
  }
  return result;
}

class LPyReader {
 public:
  LPyReader(std::string_view text, std::string_view path)
      : original_(text), clean_(withoutComments(text)), syntax_(Dialect::LPy, clean_) {
    file_.dialect = Dialect::LPy;
    file_.name = blockNameOf(path);
    file_.angle = std::string(kLPyDefaultAngle);
  }

  LSystemFile read() {
    const std::vector<Line> lines = splitLines(clean_);
    bool ended = false;
    for (size_t i = 0; i < lines.size(); ++i) {
      const Line& line = lines[i];
      if (original_.substr(firstNonSpace(original_, line), kInitialisation.size()) == kInitialisation) {
        initialisation(lines, i + 1);
        break;
      }
      uint32_t begin = firstNonSpace(clean_, line), end = line.end;
      syntax_.trim(begin, end);
      if (begin == end) continue;
      stamp();
      line_ = {begin, end};
      const bool indented = begin > line.begin;
      if (ended || indented) python(begin, end);
      if (auto at = afterLabel(clean_, line, "axiom")) {
        file_.axiom = syntax_.modules(*at, end, false);
        file_.axiomOrigin = line_;
        continue;
      }
      if (auto at = afterLabel(clean_, line, "derivation length")) {
        uint32_t a = *at, b = end;
        syntax_.trim(a, b);
        if (clean_.substr(a, b - a) == "0")
          syntax_.fail(a, b,
                       "derivation length 0 (the word is the axiom): ontogen's #until is at least 1; "
                       "ask for the axiom with word --at 0");
        file_.derivationLength = syntax_.expression(*at, end);
        file_.derivationLengthOrigin = line_;
        continue;
      }
      if (auto at = afterLabel(clean_, line, "maximum depth")) {
        add(StatementKind::MaximumDepth, syntax_.expression(*at, end));
        continue;
      }
      if (auto section = sectionOf(line)) {
        add(StatementKind::Section, *section);
        continue;
      }
      if (auto at = afterLabel(clean_, line, "ignore")) {
        symbols(StatementKind::Ignore, *at, end);
        continue;
      }
      if (auto at = afterLabel(clean_, line, "consider")) {
        symbols(StatementKind::Consider, *at, end);
        continue;
      }
      if (afterKeyword(clean_, line, "endgroup")) {
        add(StatementKind::Group, "0");
        continue;
      }
      if (auto at = afterKeyword(clean_, line, "group")) {
        uint32_t stop = end;
        if (stop > *at && clean_[stop - 1] == ':') --stop;
        add(StatementKind::Group, syntax_.expression(*at, stop));
        continue;
      }
      if (afterKeyword(clean_, line, "endlsystem")) {
        ended = true;
        continue;
      }
      if (auto at = afterKeyword(clean_, line, "module")) {
        declare(*at, end);
        continue;
      }
      if (auto at = afterKeyword(clean_, line, "#define")) {
        define(*at, end, "#define");
        continue;
      }
      if (syntax_.find(begin, end, "->") < end) {
        file_.statements.push_back(syntax_.production(begin, end));
        continue;
      }
      if (clean_[end - 1] == ':' && !pythonKeyword(begin, end)) {
        i = producedBody(lines, i, begin, end);
        continue;
      }
      if (isAssignment(begin, end)) {
        define(begin, end, "=");
        continue;
      }
      { python(begin, end); }
    }
    stamp();
    // L-Py derives once unless the file says otherwise.
    if (!file_.derivationLength) file_.derivationLength = "1";
    file_.warnings = std::move(syntax_.warnings);
    return std::move(file_);
  }

 private:
  [[noreturn]] void python(uint32_t begin, uint32_t end) const {
    uint32_t stop = begin;
    while (stop < end && isNameChar(clean_[stop])) ++stop;
    std::string what = stop > begin ? "'" + std::string(clean_.substr(begin, stop - begin)) + "'" : "this line";
    syntax_.fail(begin, end,
                 what +
                     ": Python code, which ontogen convert does not translate (it reads L-Py's declarative "
                     "part: Axiom:, derivation length:, productions with -->, constants NAME = number)");
  }

  bool pythonKeyword(uint32_t begin, uint32_t end) const {
    for (std::string_view word :
         {"def", "class", "if", "elif", "else", "for", "while", "with", "try", "except", "lambda"})
      if (afterKeyword(clean_, Line{begin, end}, word)) return true;
    return false;
  }

  // `A(x) :` with an indented body of one `produce SUCCESSORS` line.
  size_t producedBody(const std::vector<Line>& lines, size_t i, uint32_t begin, uint32_t end) {
    size_t body = i + 1;
    auto blank = [&](size_t k) {
      uint32_t a = firstNonSpace(clean_, lines[k]);
      return a == lines[k].end;
    };
    while (body < lines.size() && blank(body)) ++body;
    if (body >= lines.size() || firstNonSpace(clean_, lines[body]) == lines[body].begin)
      syntax_.fail(begin, end, "a production head without a body", false);
    auto produce = afterKeyword(clean_, lines[body], "produce");
    size_t next = body + 1;
    while (next < lines.size() && blank(next)) ++next;
    const bool single = next >= lines.size() || firstNonSpace(clean_, lines[next]) == lines[next].begin;
    if (!produce || !single) {
      uint32_t a = firstNonSpace(clean_, lines[produce ? next : body]);
      const Line& where = lines[produce ? next : body];
      python(a, where.end);
    }
    // The head as a production whose arrow is the body's `produce`.
    Statement s = productionOf(begin, end - 1, *produce, lines[body].end);
    s.origin = {begin, lines[body].end};
    file_.statements.push_back(std::move(s));
    return body;
  }

  Statement productionOf(uint32_t headBegin, uint32_t headEnd, uint32_t bodyBegin, uint32_t bodyEnd) {
    // Read the head and the body as `head --> body` through a copy that keeps offsets
    // for the head (the body is read in place).
    Statement s;
    uint32_t a = headBegin, b = headEnd;
    syntax_.trim(a, b);
    const uint32_t colon = syntax_.find(a, b, ":");
    uint32_t patternEnd = b;
    if (colon < b) {
      s.condition = syntax_.expression(colon + 1, b);
      patternEnd = colon;
    }
    uint32_t predBegin = a, predEnd = patternEnd;
    const uint32_t less = syntax_.find(a, patternEnd, "<");
    if (less < patternEnd) {
      s.leftArrow = clean_.compare(less, 2, "<<") == 0 ? "<<" : "<";
      s.left = syntax_.modules(a, less, true);
      predBegin = less + static_cast<uint32_t>(s.leftArrow.size());
    }
    const uint32_t greater = syntax_.find(predBegin, patternEnd, ">");
    if (greater < patternEnd) {
      s.rightArrow = clean_.compare(greater, 2, ">>") == 0 ? ">>" : ">";
      s.right = syntax_.modules(greater + static_cast<uint32_t>(s.rightArrow.size()), patternEnd, true);
      predEnd = greater;
    }
    std::vector<ModuleText> predecessor = syntax_.modules(predBegin, predEnd, true);
    if (predecessor.size() != 1) syntax_.fail(predBegin, predEnd, "a production has one predecessor module", false);
    syntax_.checkPredecessor(predecessor.front(), predBegin, predEnd);
    s.predecessor = std::move(predecessor.front());
    uint32_t c = bodyBegin, d = bodyEnd;
    syntax_.trim(c, d);
    if (clean_.substr(c, d - c) != "*") s.successors = syntax_.modules(c, d, false);
    return s;
  }

  std::optional<std::string> sectionOf(const Line& line) const {
    struct Word {
      std::string_view lpy, cell;
    };
    for (Word word : {Word{"production", "production"}, Word{"decomposition", "decomposition"},
                      Word{"homomorphism", "homomorphism"}, Word{"interpretation", "homomorphism"}})
      if (auto at = afterLabel(clean_, line, word.lpy)) {
        uint32_t a = *at, b = line.end;
        syntax_.trim(a, b);
        if (a == b) return std::string(word.cell);
      }
    return std::nullopt;
  }

  bool isAssignment(uint32_t begin, uint32_t end) const {
    uint32_t at = begin;
    if (at >= end || !(std::isalpha(static_cast<unsigned char>(clean_[at])) || clean_[at] == '_')) return false;
    while (at < end && isNameChar(clean_[at])) ++at;
    while (at < end && std::isspace(static_cast<unsigned char>(clean_[at]))) ++at;
    return at + 1 < end && clean_[at] == '=' && clean_[at + 1] != '=';
  }

  // `NAME = EXPR` (Python) or `#define NAME EXPR`.
  void define(uint32_t at, uint32_t end, std::string_view form) {
    while (at < end && std::isspace(static_cast<unsigned char>(clean_[at]))) ++at;
    uint32_t stop = at;
    while (stop < end && isNameChar(clean_[stop])) ++stop;
    if (stop == at) syntax_.fail(at, end, "expected a name after #define", false);
    std::string name(clean_.substr(at, stop - at));
    uint32_t value = stop;
    if (form == "=") {
      while (value < end && clean_[value] != '=') ++value;
      ++value;
    }
    file_.defines.push_back({std::move(name), syntax_.expression(value, end), line_});
  }

  void declare(uint32_t at, uint32_t end) {
    // `module A, Apex(x), B`, `module A = F` (an alias), `module B : scale = 1`.
    const uint32_t colon = syntax_.find(at, end, ":");
    if (colon < end)
      syntax_.fail(colon, end,
                   "L-Py's module attributes (scale = N: multiscale modules; base = A: a module that matches as "
                   "another) have no cell-language counterpart yet");
    const uint32_t equals = syntax_.find(at, end, "=");
    std::vector<std::string> names;
    for (uint32_t i = at; i < equals;) {
      while (i < equals && !isNameChar(clean_[i])) ++i;
      uint32_t stop = i;
      while (stop < equals && isNameChar(clean_[stop])) ++stop;
      if (stop > i) names.emplace_back(clean_.substr(i, stop - i));
      // Past the parameters, A(x, y), to the next name.
      for (int depth = 0; stop < equals && (depth > 0 || clean_[stop] != ','); ++stop) {
        if (clean_[stop] == '(') ++depth;
        if (clean_[stop] == ')') --depth;
      }
      i = stop + 1;
    }
    for (const std::string& name : names) syntax_.declaredNames.emplace(name);
    if (equals == end) return;
    uint32_t a = equals + 1, b = end;
    syntax_.trim(a, b);
    std::vector<ModuleText> target = a < b ? syntax_.modules(a, b, false) : std::vector<ModuleText>{};
    if (target.size() != 1 || target.front().hasArgs)
      syntax_.fail(a, b, "an alias names one module, as in module A = F", false);
    for (const std::string& name : names) syntax_.aliases[name] = target.front().label;
  }

  // The section the L-Py editor writes after the L-system: its options are read where
  // they change what the productions mean.
  void initialisation(const std::vector<Line>& lines, size_t from) {
    constexpr std::string_view kMatching = "'String matching'";
    for (size_t k = from; k < lines.size(); ++k) {
      std::string_view text = original_.substr(lines[k].begin, lines[k].end - lines[k].begin);
      const size_t at = text.find(kMatching);
      if (at == std::string_view::npos || text.find("setSelection") == std::string_view::npos) continue;
      // 1, L-Py's default, matches contexts as an axial tree, as ontogen does; 0 reads the
      // word as a plain string, 2 and 3 as multiscale trees.
      size_t value = at + kMatching.size();
      while (value < text.size() && (text[value] == ',' || text[value] == ' ')) ++value;
      if (value < text.size() && text[value] == '1') continue;
      const uint32_t begin = lines[k].begin + static_cast<uint32_t>(at);
      syntax_.fail(begin, begin + static_cast<uint32_t>(kMatching.size()),
                   "L-Py's option 'String matching' other than 'As AxialTree' (multiscale or plain-string "
                   "matching of contexts) has no cell-language counterpart yet");
    }
  }

  // The statements read from the line before have its place.
  void stamp() {
    for (; stamped_ < file_.statements.size(); ++stamped_)
      if (!file_.statements[stamped_].origin.known()) file_.statements[stamped_].origin = line_;
  }

  void symbols(StatementKind kind, uint32_t at, uint32_t end) {
    Statement s;
    s.kind = kind;
    s.symbols = syntax_.symbols(at, end);
    file_.statements.push_back(std::move(s));
  }

  void add(StatementKind kind, std::string word) {
    Statement s;
    s.kind = kind;
    s.word = std::move(word);
    file_.statements.push_back(std::move(s));
  }

  std::string_view original_;
  std::string clean_;
  ForeignSyntax syntax_;
  LSystemFile file_;
  SourceRange line_;
  size_t stamped_ = 0;
};

}  // namespace

LSystemFile readLPy(std::string_view text, std::string_view path) {
  return LPyReader(text, path).read();
}

}  // namespace ontogen::convert
