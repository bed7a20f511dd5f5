#include "lang/convert/lpy_reader.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <map>
#include <optional>
#include <string>
#include <tuple>

#include "lang/convert/foreign_syntax.h"
#include "lang/convert/foreign_text.h"
#include "lang/convert/line_reader.h"
#include "lang/convert/lpy_constants.h"
#include "lang/convert/lpy_globals.h"
#include "lang/convert/lpy_hooks.h"
#include "lang/convert/lpy_imports.h"
#include "lang/convert/lpy_multiscale.h"
#include "lang/convert/python_block.h"
#include "lang/convert/python_body.h"

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

// While it lives, L-Py's getIterationNb() reads as 0, its value while L-Py
// loads the file: the top level, the axiom, the derivation length.
class AtLoading {
 public:
  explicit AtLoading(ForeignSyntax& syntax) : syntax_(syntax), saved_(syntax.iterationNumber) {
    syntax_.iterationNumber = "0";
  }
  ~AtLoading() { syntax_.iterationNumber = saved_; }
  AtLoading(const AtLoading&) = delete;
  AtLoading& operator=(const AtLoading&) = delete;

 private:
  ForeignSyntax& syntax_;
  std::string saved_;
};

class LPyReader {
 public:
  LPyReader(std::string_view text, std::string_view path, uint64_t maxBytes)
      : original_(text), clean_(withoutComments(text)), syntax_(Dialect::LPy, clean_, maxBytes) {
    file_.dialect = Dialect::LPy;
    file_.name = blockNameOf(path);
    file_.angle = std::string(kLPyDefaultAngle);
  }

  LSystemFile read() {
    const std::vector<Line> lines = splitLines(clean_);
    pythonVersion(lines);
    for (const Line& line : lines) {
      if (original_.substr(firstNonSpace(original_, line), kInitialisation.size()) == kInitialisation) break;
      // Where a word is written: after `Axiom:`, an arrow, `produce` or `nproduce`.
      const std::string_view text = std::string_view(clean_).substr(line.begin, line.end - line.begin);
      size_t word = text.find("->");
      if (auto at = afterLabel(clean_, line, "axiom")) word = std::min<size_t>(word, *at - line.begin);
      for (size_t k = text.find("produce"); k != std::string_view::npos; k = text.find("produce", k + 1))
        if ((k == 0 || !isNameChar(text[k - 1])) && (k + 7 == text.size() || !isNameChar(text[k + 7])))
          word = std::min(word, k);
      if (word != std::string_view::npos) sharpModule(line.begin + static_cast<uint32_t>(word), line.end);
    }
    editorObjects(lines);
    std::map<size_t, size_t> helpers = functions(lines);
    bool ended = false;
    for (size_t i = 0; i < lines.size(); ++i) {
      if (auto helper = helpers.find(i); helper != helpers.end()) {
        i = helper->second;
        continue;
      }
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
      // A string alone, as a comment (`' --> titi )'`): Python evaluates it and drops it.
      // A name given a string (`a = ' --> b'`) is no number of the block: a production or
      // value that reads it names what the block does not define, an error the compiler
      // shows at the line that reads it.
      if (!indented && (chars::isStringLiteral(std::string_view(clean_).substr(begin, end - begin)) ||
                        (isAssignment(begin, end) && stringValue(begin, end))))
        continue;
      if (ended || indented) python(begin, end);
      if (auto last = hook(lines, i, begin, end)) {
        i = *last;
        continue;
      }
      // What L-Py computes when it loads the file (the axiom, the derivation length, the
      // top level's values) reads getIterationNb() as 0.
      if (auto at = afterLabel(clean_, line, "axiom")) {
        const AtLoading loading(syntax_);
        if (auto last = functionalAxiom(lines, i, *at, end)) {
          i = *last;
          continue;
        }
        file_.axiom = syntax_.modules(*at, end, false);
        file_.axiomOrigin = line_;
        if (file_.axiom.empty())
          syntax_.fail(begin, end,
                       "an empty axiom: L-Py starts from the empty word, from which no block of the cell language "
                       "starts");
        continue;
      }
      if (auto at = afterLabel(clean_, line, "derivation length")) {
        const AtLoading loading(syntax_);
        uint32_t a = *at, b = end;
        syntax_.trim(a, b);
        // 0: L-Py shows the axiom. Without productions every step's word is the axiom, so
        // one step says the same (checked when the whole file is read).
        if (clean_.substr(a, b - a) == "0") zeroLength_ = SourceRange{a, b};
        file_.derivationLength = zeroLength_ ? "1" : syntax_.expression(*at, end);
        file_.derivationLengthOrigin = line_;
        continue;
      }
      if (auto at = afterLabel(clean_, line, "maximum depth")) {
        add(StatementKind::MaximumDepth, syntax_.maximumDepth(*at, end));
        continue;
      }
      if (auto section = sectionOf(line)) {
        syntax_.inHomomorphism = *section == "homomorphism";
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
      if (readImport(syntax_, clean_, begin, end)) continue;
      if (topLevelStatement(begin, end)) continue;
      if (angleIncrement(begin, end)) continue;
      // print(...) writes to the terminal, which changes no word.
      if (afterKeyword(clean_, line, "print")) continue;
      // seed(N): the run's seed (ontogen's streams are its own, so the numbers differ
      // from Python's; a run is still the same for the same seed).
      if (auto at = seedCall(begin, end)) {
        file_.seed = *at;
        continue;
      }
      if (const uint32_t colon = syntax_.find(begin, end, ":"); colon < end && !pythonKeyword(begin, end)) {
        uint32_t a = colon + 1, b = end;
        syntax_.trim(a, b);
        if (a == b || startsStatement(a, b)) {
          i = producedBody(lines, i, begin, colon, a == b);
          continue;
        }
      }
      const AtLoading loading(syntax_);
      if (auto set = readAssignment(clean_, begin, end); set && (set->op != '=' || isAssignment(begin, end))) {
        const bool again = std::any_of(file_.defines.begin(), file_.defines.end(),
                                       [&](const Define& d) { return cellName(d.name) == cellName(set->name); });
        if (again && setAgain(syntax_, file_, set->name, set->op, syntax_.expression(set->valueBegin, end), line_))
          continue;
        if (set->op == '=') {
          define(begin, end, "=");
          continue;
        }
      }
      if (tupleAssignment(begin, end)) continue;
      { python(begin, end); }
    }
    stamp();
    if (!file_.axiomOrigin.known()) {
      uint32_t first = 0;
      while (first < original_.size() && std::isspace(static_cast<unsigned char>(original_[first]))) ++first;
      uint32_t stop = first;
      while (stop < original_.size() && original_[stop] != '\n') ++stop;
      syntax_.fail(first, stop,
                   "no Axiom: in this file: L-Py starts from the empty word, from which no block of the cell language "
                   "starts");
    }
    applyHooks();
    leaveOutUnreadBodyGlobals(syntax_, file_);
    writeFixedConstantsInPlace(syntax_, file_);
    loadedOnce();
    checkChoices();
    if (zeroLength_ && rewritesTheAxiom(file_)) {
      syntax_.fail(zeroLength_->begin, zeroLength_->end,
                   "derivation length 0 (the word is the axiom) where productions would rewrite it: ontogen's "
                   "#until is at least 1; ask for the axiom with word --at 0");
    }
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

  // Python 2 shows in a print statement, `<>`, and names Python 3 dropped; its `/`
  // floors between integers unless division comes from __future__, and its round()
  // takes halves away from zero (ForeignSyntax::python2).
  void pythonVersion(const std::vector<Line>& lines) {
    for (const Line& line : lines) {
      const uint32_t first = firstNonSpace(clean_, line);
      const std::string_view text = std::string_view(clean_).substr(first, line.end - first);
      if (text.rfind("from __future__ import", 0) == 0 && text.find("division") != std::string_view::npos)
        syntax_.futureDivision = true;
      if (syntax_.python2) continue;
      if (text.rfind("print", 0) == 0 && text.size() > 5 && (text[5] == ' ' || text[5] == '\t' || text[5] == '"' ||
                                                              text[5] == '\'')) {
        size_t k = 5;
        while (k < text.size() && (text[k] == ' ' || text[k] == '\t')) ++k;
        if (k < text.size() && text[k] != '(' && text[k] != '=') syntax_.python2 = first;
      }
      for (std::string_view mark : {"<>", "xrange(", ".has_key(", ".iteritems(", ".itervalues(", ".iterkeys(",
                                    "raw_input("})
        if (!syntax_.python2 && text.find(mark) != std::string_view::npos)
          syntax_.python2 = first + static_cast<uint32_t>(text.find(mark));
    }
  }

  // Statements of Python's top level that change no word the block derives: `global`
  // (at the top level, names are global already), `assert` (a warning: the block does not
  // check it), and `backward()` / `forward()`, the direction of every step (L-Py keeps it
  // from the file's loading on).
  bool topLevelStatement(uint32_t begin, uint32_t end) {
    const Line line{begin, end};
    if (afterKeyword(clean_, line, "global")) return true;
    if (afterKeyword(clean_, line, "assert")) {
      syntax_.warnings.push_back({SourceRange{begin, end},
                                  "'assert' at L-Py's top level is not checked: the converted block runs on where "
                                  "L-Py stops at an assertion that fails"});
      return true;
    }
    for (std::string_view call : {"backward", "forward"}) {
      const Line rest{static_cast<uint32_t>(begin + call.size()), end};
      if (clean_.compare(begin, call.size(), call) != 0 || rest.begin >= end || isNameChar(clean_[rest.begin]))
        continue;
      uint32_t a = rest.begin, b = end;
      syntax_.trim(a, b);
      if (clean_.substr(a, b - a) != "()") continue;
      direction_ = std::pair{call == "backward", SourceRange{begin, end}};
      return true;
    }
    return false;
  }

  // L-Py's hooks, `def StartEach():` and the like (lpy_hooks.h): recorded, and read
  // when the whole file is. The index of the hook's last line.
  std::optional<size_t> hook(const std::vector<Line>& lines, size_t i, uint32_t begin, uint32_t end) {
    auto at = afterKeyword(clean_, Line{begin, end}, "def");
    if (!at) return std::nullopt;
    uint32_t a = *at;
    while (a < end && std::isspace(static_cast<unsigned char>(clean_[a]))) ++a;
    uint32_t stop = a;
    while (stop < end && isNameChar(clean_[stop])) ++stop;
    HookText hook;
    hook.name = std::string(clean_.substr(a, stop - a));
    if (!isLPyHook(hook.name)) return std::nullopt;
    while (stop < end && std::isspace(static_cast<unsigned char>(clean_[stop]))) ++stop;
    if (stop >= end || clean_[stop] != '(') return std::nullopt;
    uint32_t close = stop + 1;
    while (close < end && clean_[close] != ')' && clean_[close] != '(') ++close;
    if (close == end || clean_[close] != ')') return std::nullopt;
    const uint32_t colon = syntax_.find(close + 1, end, ":");
    if (colon == end) return std::nullopt;
    for (uint32_t from = stop + 1; from < close;) {
      const uint32_t comma = syntax_.find(from, close, ",");
      uint32_t x = from, y = comma;
      syntax_.trim(x, y);
      if (x < y) hook.parameters.emplace_back(clean_.substr(x, y - x));
      from = comma + 1;
    }
    hook.begin = begin;
    hook.end = colon + 1;
    const size_t last = lastIndentedLine(lines, i);
    hook.body = logicalLines(clean_, colon + 1, lines[last].end);
    hooks_.push_back(std::move(hook));
    return last;
  }

  // What the hooks set, put into the block: their constants as #defines, the values of
  // each step where the productions read them, the group, the seed.
  void applyHooks() {
    syntax_.inHomomorphism = false;  // the hooks run around the steps
    std::map<std::string, std::string, std::less<>> initial;
    for (const Define& d : file_.defines) initial[cellName(d.name)] = d.value;
    HookEffects effects = translateHooks(syntax_, clean_, hooks_, initial);
    checkFixedConstantsAgainstHooks(syntax_, effects);
    if (!effects.backward) effects.backward = direction_;
    keepLoadTimeValues(effects, initial);
    for (const auto& [key, value] : effects.defines) {
      const std::string& name = key;
      auto given = std::find_if(file_.defines.begin(), file_.defines.end(),
                                [&](const Define& d) { return cellName(d.name) == name; });
      if (given != file_.defines.end()) {
        given->value = value.value;
        given->origin = value.origin;
      } else {
        file_.defines.push_back({name, value.value, value.origin});
      }
    }
    if (effects.useGroup) {
      file_.useGroup = effects.useGroup->value;
      file_.useGroupOrigin = effects.useGroup->origin;
    }
    if (effects.seed) file_.seed = effects.seed->value;
    bool homomorphism = false;
    for (Statement& s : file_.statements) {
      if (s.kind == StatementKind::Section) homomorphism = s.word == "homomorphism";
      if (s.kind != StatementKind::Production) continue;
      if (effects.backward && (effects.backward->first ? s.leftArrow == "<<" : s.rightArrow == ">>"))
        syntax_.fail(effects.backward->second.begin, effects.backward->second.end,
                     std::string(effects.backward->first ? "backward()" : "forward()") +
                         " on every step, where a production has a new context of the other direction (" +
                         (effects.backward->first ? "<<" : ">>") +
                         "): the block derives one way, right to left exactly when its productions use >>");
      if (effects.stepValues.empty()) continue;
      std::vector<std::string> bound;
      for (const std::vector<ModuleText>* word : {&s.left, &s.right})
        for (const ModuleText& m : *word) bound.insert(bound.end(), m.args.begin(), m.args.end());
      bound.insert(bound.end(), s.predecessor.args.begin(), s.predecessor.args.end());
      bool replaced = false;
      s.condition = withHookValues(s.condition, effects.stepValues, bound, &replaced);
      s.probability = withHookValues(s.probability, effects.stepValues, bound, &replaced);
      for (ModuleText& m : s.successors)
        for (std::string& arg : m.args) arg = withHookValues(arg, effects.stepValues, bound, &replaced);
      if (replaced && homomorphism)
        syntax_.fail(s.origin.begin, s.origin.end,
                     "a global L-Py's StartEach() sets at each step, read in the interpretation: its value after "
                     "the last step is not written");
    }
  }

  // A helper function of several lines is translated once, as productions read it: where
  // the axiom or the derivation length calls one that reads getIterationNb(), the value
  // would change with the step, where L-Py reads 0 once.
  void loadedOnce() const {
    auto readsTime = [](const std::string& text) {
      for (size_t at = text.find("time"); at != std::string::npos; at = text.find("time", at + 1))
        if ((at == 0 || !isNameChar(text[at - 1])) && (at + 4 == text.size() || !isNameChar(text[at + 4]))) return true;
      return false;
    };
    bool axiom = false;
    for (const ModuleText& m : file_.axiom)
      for (const std::string& arg : m.args) axiom = axiom || readsTime(arg);
    const bool length = file_.derivationLength && readsTime(*file_.derivationLength);
    if (axiom || length) {
      const SourceRange at = axiom ? file_.axiomOrigin : file_.derivationLengthOrigin;
      syntax_.fail(at.begin, at.end,
                   "getIterationNb() read through a helper function where L-Py loads the file (it reads 0 there): "
                   "the converter writes the helper as productions read it");
    }
  }

  // L-Py computes the file's top level, the axiom and the derivation length when it loads
  // the file, before Start or StartEach set any global: where those read a global a hook
  // sets, they read the file's value of it, put in here; a global the file does not give
  // is one L-Py could not read there.
  void keepLoadTimeValues(const HookEffects& effects, const std::map<std::string, std::string, std::less<>>& initial) {
    std::map<std::string, HookValue, std::less<>> fileValues, unset;
    for (const auto* set : {&effects.defines, &effects.stepValues})
      for (const auto& [name, value] : *set) {
        if (auto given = initial.find(name); given != initial.end())
          fileValues[name] = {given->second, {}};
        else
          unset[name] = value;
      }
    if (fileValues.empty() && unset.empty()) return;
    auto loaded = [&](std::string& text, SourceRange where) {
      bool early = false;
      withHookValues(text, unset, {}, &early);
      if (early)
        syntax_.fail(where.begin, where.end,
                     "a global that only a hook of L-Py sets, read where L-Py loads the file, before any hook runs");
      text = withHookValues(text, fileValues, {});
    };
    for (ModuleText& m : file_.axiom)
      for (std::string& arg : m.args) loaded(arg, file_.axiomOrigin);
    if (file_.derivationLength) loaded(*file_.derivationLength, file_.derivationLengthOrigin);
    for (Define& d : file_.defines)
      if (!fileValues.count(cellName(d.name)) && !unset.count(cellName(d.name))) loaded(d.value, d.origin);
    for (auto& [name, elements] : syntax_.arrays)
      for (std::string& element : elements) element = withHookValues(element, fileValues, {});
  }

  // The helper functions, `def f(x, y): return EXPR` on one line or with `return EXPR`
  // alone on the lines below, or a body of ifs, locals and returns
  // (translatePythonFunction), before `endlsystem` or the editor's section: each is
  // recorded for calls to be inlined (Python looks a function up when it
  // is called, so it may be defined after its use). The first and last line of each.
  std::map<size_t, size_t> functions(const std::vector<Line>& lines) {
    std::map<size_t, size_t> found;
    struct Longer {
      std::string name;
      ForeignSyntax::Function function;
      std::vector<BodyLine> body;
    };
    std::vector<Longer> longer;
    for (size_t i = 0; i < lines.size(); ++i) {
      const Line& line = lines[i];
      if (original_.substr(firstNonSpace(original_, line), kInitialisation.size()) == kInitialisation) break;
      if (afterKeyword(clean_, line, "endlsystem")) break;
      auto at = afterKeyword(clean_, line, "def");
      // A def indented is a class's method or a function's own: no helper of the file.
      if (!at || firstNonSpace(clean_, line) != line.begin) continue;
      uint32_t a = *at, end = line.end;
      while (a < end && std::isspace(static_cast<unsigned char>(clean_[a]))) ++a;
      uint32_t stop = a;
      while (stop < end && isNameChar(clean_[stop])) ++stop;
      std::string name(clean_.substr(a, stop - a));
      while (stop < end && std::isspace(static_cast<unsigned char>(clean_[stop]))) ++stop;
      if (name.empty() || stop >= end || clean_[stop] != '(' || isLPyHook(name)) continue;
      uint32_t close = stop + 1;
      while (close < end && clean_[close] != ')' && clean_[close] != '(') ++close;
      if (close == end || clean_[close] != ')') continue;
      ForeignSyntax::Function function;
      bool plain = true;
      for (uint32_t from = stop + 1; from < close;) {
        const uint32_t comma = syntax_.find(from, close, ",");
        uint32_t x = from, y = comma;
        syntax_.trim(x, y);
        bool isName = x < y && !std::isdigit(static_cast<unsigned char>(clean_[x]));
        for (uint32_t k = x; k < y; ++k) isName = isName && isNameChar(clean_[k]);
        plain = plain && isName;
        if (isName) function.parameters.emplace_back(clean_.substr(x, y - x));
        from = comma + 1;
      }
      uint32_t colon = close + 1;
      while (colon < end && std::isspace(static_cast<unsigned char>(clean_[colon]))) ++colon;
      if (!plain || colon >= end || clean_[colon] != ':') continue;
      // The body: the rest of the line, or the indented lines below.
      const size_t last = lastIndentedLine(lines, i);
      const std::vector<BodyLine> body = logicalLines(clean_, colon + 1, lines[last].end);
      found[i] = last;
      auto value = body.size() == 1 ? afterKeyword(clean_, Line{body[0].begin, body[0].end}, "return") : std::nullopt;
      uint32_t x = value ? *value : 0, y = body.empty() ? 0 : body[0].end;
      syntax_.trim(x, y);
      if (value && x < y) {
        function.begin = x;
        function.end = y;
        syntax_.functions[name] = std::move(function);
        continue;
      }
      // Of several lines: translated when those of one line are all known (it may call them).
      function.begin = line.begin;
      function.end = line.end;
      longer.push_back({std::move(name), std::move(function), body});
    }
    for (auto& [name, function, body] : longer) {
      const size_t warned = syntax_.warnings.size();
      try {
        function.translated = translatePythonFunction(syntax_, clean_, function.parameters, body);
      } catch (const ConvertError& error) {
        function.untranslatable = error;
        syntax_.warnings.resize(warned);  // of a function no word may read
      }
      syntax_.functions[name] = std::move(function);
    }
    return found;
  }

  // `context().turtle.setAngleIncrement(A)` (or execContext(), or the editor's
  // `context.turtle...`): the block's #angle.
  bool angleIncrement(uint32_t begin, uint32_t end) {
    for (std::string_view call : {"context().turtle.setAngleIncrement(", "execContext().turtle.setAngleIncrement(",
                                  "context.turtle.setAngleIncrement("}) {
      if (clean_.compare(begin, call.size(), call) != 0) continue;
      const uint32_t open = begin + static_cast<uint32_t>(call.size()) - 1;
      uint32_t close = end;
      while (close > open && clean_[close - 1] != ')') --close;
      if (close <= open + 1) return false;
      file_.angle = syntax_.expression(open + 1, close - 1);
      return true;
    }
    return false;
  }

  // The editor's scalars, `scalars = [('N', 'Integer', 10, 1, 20), ('B', 'Bool', True)]`:
  // #defines of their values, unless the file gives the name itself.
  void scalars(uint32_t begin, uint32_t end) {
    uint32_t at = syntax_.find(begin, end, "[");
    for (at = at < end ? at + 1 : end; at < end;) {
      uint32_t open = at;
      while (open < end && clean_[open] != '(') ++open;
      if (open == end) break;
      int depth = 0;
      uint32_t close = open;
      for (; close < end; ++close) {
        if (clean_[close] == '(') ++depth;
        if (clean_[close] == ')' && --depth == 0) break;
      }
      if (close == end) break;
      std::vector<std::string> fields;
      for (uint32_t a = open + 1; a <= close;) {
        uint32_t comma = syntax_.find(a, close, ",");
        uint32_t x = a, y = comma;
        syntax_.trim(x, y);
        fields.emplace_back(clean_.substr(x, y - x));
        a = comma + 1;
      }
      at = close + 1;
      if (fields.size() < 2) continue;
      auto quoted = [](const std::string& text) { return !text.empty() && (text[0] == '\'' || text[0] == '"'); };
      auto unquote = [&](std::string text) {
        if (text.size() >= 2 && quoted(text)) text = text.substr(1, text.size() - 2);
        return text;
      };
      // ('N', 'Integer', 10, 1, 20), or as older editors wrote it, ('N', 10, 1, 20) and
      // ('B', True, False, True); ('Title', None) names a category of no value.
      const bool typed = quoted(fields[1]);
      if (typed && fields.size() < 3) continue;
      const std::string name = unquote(fields[0]), type = typed ? unquote(fields[1]) : "";
      std::string value = typed ? fields[2] : fields[1];
      if (type == "Bool" || (!typed && (value == "True" || value == "False")))
        value = value == "True" ? "1" : "0";
      else if (typed && type != "Integer" && type != "Float")
        continue;
      bool given = false;
      for (const Define& d : file_.defines) given = given || d.name == name;
      if (given || name.empty()) continue;
      char* stop = nullptr;
      (void)std::strtod(value.c_str(), &stop);
      if (value.empty() || stop != value.c_str() + value.size()) continue;
      file_.defines.push_back({name, value, SourceRange{open, close + 1}});
    }
  }

  std::optional<std::string> seedCall(uint32_t begin, uint32_t end) const {
    for (std::string_view call : {"seed(", "random.seed("}) {
      if (clean_.compare(begin, call.size(), call) != 0 || clean_[end - 1] != ')') continue;
      const uint32_t open = begin + static_cast<uint32_t>(call.size()) - 1;
      if (syntax_.find(open + 1, end, ")") != end) continue;  // the ')' is the call's own
      return syntax_.expression(open + 1, end - 1);
    }
    return std::nullopt;
  }

  bool startsStatement(uint32_t begin, uint32_t end) const {
    for (std::string_view word : {"produce", "nproduce", "pass", "return"})
      if (afterKeyword(clean_, Line{begin, end}, word)) return true;
    return false;
  }

  // `A(x) :` and a Python body: on the line (`A(x) : produce B`) or on the indented lines
  // after it. The index of the body's last line.
  size_t producedBody(const std::vector<Line>& lines, size_t i, uint32_t begin, uint32_t colon, bool below) {
    const size_t last = lastIndentedLine(lines, i);
    if (below && last == i) syntax_.fail(begin, colon + 1, "a production head without a body", false);
    const uint32_t bodyEnd = lines[last].end;
    Statement head = headOf(begin, colon);
    head.origin = {begin, bodyEnd};
    for (Statement& s : translatePythonBody(syntax_, clean_, head, logicalLines(clean_, colon + 1, bodyEnd)))
      file_.statements.push_back(std::move(s));
    return last;
  }

  // The editor's objects, `NAME = pgl.NurbsCurve2D(` (or any class) indented under
  // `def __initialiseContext__(context):` after the INITIALISATION line.
  void editorObjects(const std::vector<Line>& lines) {
    size_t k = 0;
    while (k < lines.size() &&
           original_.substr(firstNonSpace(original_, lines[k]), kInitialisation.size()) != kInitialisation)
      ++k;
    for (++k; k < lines.size(); ++k) {
      uint32_t a = firstNonSpace(clean_, lines[k]);
      const uint32_t end = lines[k].end;
      uint32_t stop = a;
      while (stop < end && isNameChar(clean_[stop])) ++stop;
      if (stop == a || std::isdigit(static_cast<unsigned char>(clean_[a]))) continue;
      const std::string name(clean_.substr(a, stop - a));
      while (stop < end && std::isspace(static_cast<unsigned char>(clean_[stop]))) ++stop;
      if (stop >= end || clean_[stop] != '=' || (stop + 1 < end && clean_[stop + 1] == '=')) continue;
      uint32_t value = stop + 1;
      while (value < end && std::isspace(static_cast<unsigned char>(clean_[value]))) ++value;
      if (clean_.compare(value, 4, "pgl.") == 0) value += 4;
      uint32_t close = value;
      while (close < end && isNameChar(clean_[close])) ++close;
      if (close == value || close >= end || clean_[close] != '(' ||
          !std::isupper(static_cast<unsigned char>(clean_[value])))
        continue;
      syntax_.editorObjects[name] = std::string(clean_.substr(value, close - value));
    }
  }

  // `#(` in a word [begin, end) of the file: L-Py reads `#` there as the start of a
  // comment and refuses `#(` (cpfg's width module), so the word would not be the file's.
  void sharpModule(uint32_t begin, uint32_t end) const {
    for (uint32_t k = begin; k < end && k < original_.size(); ++k) {
      if (original_[k] != '#' || clean_[k] == '#') continue;
      uint32_t next = k + 1;
      while (next < end && (original_[next] == ' ' || original_[next] == '\t')) ++next;
      if (next < end && original_[next] == '(')
        syntax_.fail(k, next + 1,
                     "'#(' in a word: L-Py reads '#' as the start of a comment and refuses '#(' (cpfg's module of "
                     "width, which L-Py writes _)");
      return;
    }
  }

  // L-Py's functional axiom: `Axiom:` alone on its line and a Python body below it,
  // read as a production body (nproduce, produce, locals, loops over ranges) whose one
  // way, with no test and no random choice, is the axiom. The index of its last line.
  // The last of the lines indented below line i (blank lines skipped), or i if none is:
  // the extent of a Python block that starts at the end of line i.
  size_t lastIndentedLine(const std::vector<Line>& lines, size_t i) const {
    size_t last = i;
    for (size_t k = i + 1; k < lines.size(); ++k) {
      const uint32_t first = firstNonSpace(clean_, lines[k]);
      if (first == lines[k].end) continue;
      if (first == lines[k].begin) break;
      last = k;
    }
    return last;
  }

  std::optional<size_t> functionalAxiom(const std::vector<Line>& lines, size_t i, uint32_t at, uint32_t end) {
    uint32_t a = at, b = end;
    syntax_.trim(a, b);
    if (a < b) return std::nullopt;
    const size_t last = lastIndentedLine(lines, i);
    if (last == i) return std::nullopt;
    const uint32_t bodyBegin = firstNonSpace(clean_, lines[i + 1]), bodyEnd = lines[last].end;
    Statement head;
    head.predecessor.label = "Axiom";
    const std::vector<Statement> ways = translatePythonBody(syntax_, clean_, head, logicalLines(clean_, end, bodyEnd));
    if (ways.size() != 1 || !ways.front().condition.empty() || !ways.front().probability.empty() ||
        ways.front().keepsModule)
      syntax_.fail(bodyBegin, bodyEnd,
                   ways.empty()
                       ? "a functional axiom that produces nothing (the empty word, which no block starts from)"
                       : "a functional axiom whose word depends on a test or a random choice: the converter "
                         "writes one axiom");
    if (ways.front().successors.empty())
      syntax_.fail(bodyBegin, bodyEnd, "a functional axiom that produces the empty word, which no block starts from");
    file_.axiom = ways.front().successors;
    file_.axiomOrigin = {line_.begin, bodyEnd};
    return last;
  }

  // The contexts and predecessor of a production head [begin, end).
  Statement headOf(uint32_t begin, uint32_t end) {
    Statement s;
    syntax_.vectorNames.clear();
    uint32_t a = begin, b = end;
    syntax_.trim(a, b);
    uint32_t predBegin = a, predEnd = b;
    const uint32_t less = syntax_.find(a, b, "<");
    if (less < b) {
      s.leftArrow = clean_.compare(less, 2, "<<") == 0 ? "<<" : "<";
      s.left = syntax_.modules(a, less, true);
      predBegin = less + static_cast<uint32_t>(s.leftArrow.size());
    }
    const uint32_t greater = syntax_.find(predBegin, b, ">");
    if (greater < b) {
      s.rightArrow = clean_.compare(greater, 2, ">>") == 0 ? ">>" : ">";
      s.right = syntax_.modules(greater + static_cast<uint32_t>(s.rightArrow.size()), b, true);
      predEnd = greater;
    }
    std::vector<ModuleText> predecessor = syntax_.modules(predBegin, predEnd, true);
    if (predecessor.size() != 1) syntax_.fail(predBegin, predEnd, "a production has one predecessor module", false);
    syntax_.checkPredecessor(predecessor.front(), predBegin, predEnd);
    s.predecessor = std::move(predecessor.front());
    return s;
  }

  // The cell language chooses among a module's matching weighted productions together,
  // L-Py takes the first body that produces. So a body's random choice stands alone: no
  // later production of the module in its section may join it (a weighted one would be
  // chosen with it), nor follow a way that keeps the module (L-Py would try it there).
  void checkChoices() const {
    const std::vector<Statement>& all = file_.statements;
    for (size_t k = 0; k < all.size(); ++k) {
      if (all[k].probability.empty()) continue;
      for (size_t j = k + 1; j < all.size() && all[j].kind != StatementKind::Section; ++j) {
        const Statement& later = all[j];
        if (later.kind != StatementKind::Production || later.origin.begin == all[k].origin.begin) continue;
        if (later.predecessor.label != all[k].predecessor.label ||
            later.predecessor.args.size() != all[k].predecessor.args.size() ||
            later.predecessor.hasArgs != all[k].predecessor.hasArgs)
          continue;
        if (all[k].keepsModule)
          syntax_.fail(all[k].origin.begin, all[k].origin.end,
                       "a random choice of this body produces nothing on one way, where L-Py tries the later "
                       "productions of " +
                           all[k].predecessor.label +
                           ": the cell language chooses among weighted productions together; make the way produce");
        if (!later.probability.empty())
          syntax_.fail(later.origin.begin, later.origin.end,
                       "a second body with a random choice for " + later.predecessor.label +
                           ": the cell language would choose among both bodies' ways together, where L-Py takes the "
                           "first body that produces; join them in one body");
      }
    }
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

  // Whether the assignment [begin, end) gives its name a string.
  bool stringValue(uint32_t begin, uint32_t end) const {
    uint32_t a = begin;
    while (a < end && clean_[a] != '=') ++a;
    uint32_t b = end;
    syntax_.trim(++a, b);
    return a < b && chars::isStringLiteral(std::string_view(clean_).substr(a, b - a));
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
      uint32_t a = value, b = end;
      syntax_.trim(a, b);
      if (a < b && clean_[a] == '[' && clean_[b - 1] == ']' && syntax_.find(a + 1, b, "]") == b - 1) {
        list(name, a, b);
        return;
      }
    }
    std::string text = syntax_.expression(value, end);
    recordFileConstant(syntax_, cellName(name), text);
    file_.defines.push_back({std::move(name), std::move(text), line_});
  }

  // `color = [1, 3, 2]`: a list of constants, which `color[i]` reads
  // (ForeignSyntax::arrays); any other use of the list is Python the block cannot say.
  void list(const std::string& name, uint32_t a, uint32_t b) {
    std::vector<std::string> elements;
    for (uint32_t from = a + 1; from < b - 1;) {
      const uint32_t comma = syntax_.find(from, b - 1, ",");
      uint32_t x = from, y = comma;
      syntax_.trim(x, y);
      if (x == y && comma == b - 1 && !elements.empty()) break;  // [1, 2,]
      elements.push_back(syntax_.expression(from, comma));
      from = comma + 1;
    }
    if (elements.empty()) syntax_.fail(a, b, "an empty list: Python code, which ontogen convert does not translate");
    syntax_.arrays[name] = std::move(elements);
  }

  // `MAX_AGE, dr = 10, 0.02`: constants set together. Python computes the values first,
  // so a value may not name a constant this line sets.
  bool tupleAssignment(uint32_t begin, uint32_t end) {
    const uint32_t equals = syntax_.find(begin, end, "=");
    if (equals >= end || syntax_.find(begin, equals, ",") >= equals || clean_.compare(equals, 2, "==") == 0) return false;
    std::vector<std::pair<uint32_t, uint32_t>> names, values;
    for (auto [from, to, into] : {std::tuple{begin, equals, &names}, std::tuple{equals + 1, end, &values}}) {
      for (uint32_t at = from; at <= to;) {
        const uint32_t comma = syntax_.find(at, to, ",");
        uint32_t x = at, y = comma;
        syntax_.trim(x, y);
        into->emplace_back(x, y);
        at = comma + 1;
      }
    }
    for (auto [x, y] : names) {
      if (x == y || !(std::isalpha(static_cast<unsigned char>(clean_[x])) || clean_[x] == '_')) return false;
      for (uint32_t k = x; k < y; ++k)
        if (!isNameChar(clean_[k])) return false;
    }
    if (names.size() != values.size())
      syntax_.fail(begin, end, "names and values of this assignment differ in number (a value that is a sequence): Python "
                             "code, which ontogen convert does not translate");
    for (size_t k = 0; k < names.size(); ++k) {
      const std::string value = syntax_.expression(values[k].first, values[k].second);
      for (auto [x, y] : names) {
        const std::string other(clean_.substr(x, y - x));
        for (size_t at = value.find(other); at != std::string::npos; at = value.find(other, at + 1))
          if ((at == 0 || !isNameChar(value[at - 1])) &&
              (at + other.size() == value.size() || !isNameChar(value[at + other.size()])))
            syntax_.fail(values[k].first, values[k].second,
                         "a value naming '" + other + "', which this line sets: Python computes every value first");
      }
      const std::string name(clean_.substr(names[k].first, names[k].second - names[k].first));
      recordFileConstant(syntax_, cellName(name), value);
      file_.defines.push_back({name, value, line_});
    }
    return true;
  }

  void declare(uint32_t at, uint32_t end) {
    // `module A, Apex(x), B`, `module A = F` (an alias), `module B : scale = 1`.
    const uint32_t colon = syntax_.find(at, end, ":");
    if (colon < end) return declareScaled(syntax_, clean_, at, colon, end, line_, file_);
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
      {
        uint32_t a = firstNonSpace(clean_, lines[k]), b = lines[k].end;
        syntax_.trim(a, b);
        if (a < b && !angleIncrement(a, b) && afterKeyword(clean_, Line{a, b}, "scalars")) {
          uint32_t eq = a + 7;
          while (eq < b && std::isspace(static_cast<unsigned char>(clean_[eq]))) ++eq;
          if (eq < b && clean_[eq] == '=') scalars(eq + 1, b);
        }
      }
      const size_t at = text.find(kMatching);
      if (at == std::string_view::npos || text.find("setSelection") == std::string_view::npos) continue;
      // 1, L-Py's default, matches contexts as an axial tree, as ontogen does; 3 as a
      // multiscale tree (`scale N:` lines), 2 as a multi-level tree (`level N:`); 0
      // reads the word as a plain string.
      size_t value = at + kMatching.size();
      while (value < text.size() && (text[value] == ',' || text[value] == ' ')) ++value;
      if (value < text.size() && (text[value] == '1' || readsMultiscale(text[value], file_))) continue;
      const uint32_t begin = lines[k].begin + static_cast<uint32_t>(at);
      syntax_.fail(begin, begin + static_cast<uint32_t>(kMatching.size()),
                   "L-Py's option 'String matching' set to 'As String' (plain-string matching of contexts, "
                   "branches read as modules) has no cell-language counterpart yet");
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
  std::vector<HookText> hooks_;
  std::optional<SourceRange> zeroLength_;                  ///< `derivation length: 0`, its value
  std::optional<std::pair<bool, SourceRange>> direction_;  ///< backward() or forward() at the top level
};

}  // namespace

LSystemFile readLPy(std::string_view text, std::string_view path, uint64_t maxBytes) {
  return LPyReader(text, path, maxBytes).read();
}

}  // namespace ontogen::convert
