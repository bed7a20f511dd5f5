#include "lang/convert/foreign_syntax.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <optional>
#include <utility>

#include "lang/compile_context.h"
#include "lang/convert/foreign_text.h"
#include "lang/convert/foreign_vocabulary.h"
#include "lang/convert/python_operators.h"
#include "model/builtins.h"
#include "model/program.h"

namespace ontogen::convert {

using chars::isCellSymbol;
using chars::isLetter;
using chars::isNameChar;
using chars::isSpace;
using chars::shown;

std::string cellName(std::string_view name) {
  // A built-in function's name (`step`, `max`) read as a value is the file's own
  // constant or parameter, which the cell language would refuse to define.
  return detail::isReadOnlyName(name) || findBuiltin(name) ? std::string(name) + "_" : std::string(name);
}

ForeignSyntax::Nested::Nested(const ForeignSyntax& syntax, uint32_t begin, uint32_t end) : depth(syntax.depth_) {
  if (++depth > kMaxConvertNesting) {
    --depth;
    syntax.fail(begin, end,
                "nested too deeply (more than " + std::to_string(kMaxConvertNesting) +
                    " levels of conditionals or alternatives)",
                false);
  }
}

void ForeignSyntax::fail(uint32_t begin, uint32_t end, std::string message, bool untranslatable) const {
  throw ConvertError{begin, end > begin ? end : begin + 1, std::move(message), untranslatable};
}

void ForeignSyntax::trim(uint32_t& begin, uint32_t& end) const {
  while (begin < end && isSpace(text_[begin])) ++begin;
  while (end > begin && isSpace(text_[end - 1])) --end;
}

uint32_t ForeignSyntax::find(uint32_t begin, uint32_t end, std::string_view what) const {
  int depth = 0;
  for (uint32_t at = begin; at < end; ++at) {
    const char c = text_[at];
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if (depth == 0 && text_.compare(at, what.size(), what) == 0 && at + what.size() <= end) return at;
  }
  return end;
}

// The end of the label that starts at `at` (before its parameters).
uint32_t ForeignSyntax::moduleEnd(uint32_t at, uint32_t end, std::string& label) const {
  const char c = text_[at];
  // Query modules ?P ?H ?L ?U (ABOP section 1.10), in both tools; L-Py's ?R ?F as well.
  if (c == '?' && at + 1 < end && isLetter(text_[at + 1])) {
    label = std::string(text_.substr(at, 2));
    if (label == "?R" || label == "?F")
      fail(at, at + 2,
           "L-Py's query " + shown(label) +
               " has no cell-language counterpart: ontogen's turtle fills ?P, ?H, ?L and ?U only, so the word "
               "would differ");
    if (label == "?E")
      fail(at, at + 2,
           "cpfg's ?E, the query an environmental program answers (cpfg -e FILE): ontogen runs no environment "
           "process, so the values the query holds, and the word, would differ");
    return at + 2;
  }
  // '@' modules: the longest predefined name, as the tools read them (@GcI is @Gc I).
  if (c == '@' && at + 1 < end &&
      (isNameChar(text_[at + 1]) || (dialect_ == Dialect::Cpfg && (text_[at + 1] == '#' || text_[at + 1] == '!')))) {
    size_t best = 0;
    for (const Predefined& p : predefinedModules())
      if (p.name[0] == '@' && inDialect(p, dialect_) && p.name.size() > best &&
          at + p.name.size() <= end && text_.compare(at, p.name.size(), p.name) == 0)
        best = p.name.size();
    if (best == 0 && dialect_ == Dialect::LPy) {
      // L-Py reads the longest name it knows and else one character: `@c` is the
      // modules @ and c, both of no meaning to its turtle (cpfg's @c is a circle).
      uint32_t stop = at + 1;
      while (stop < end && isNameChar(text_[stop])) ++stop;
      const std::string name(text_.substr(at, stop - at));
      warnOnce(name, at, stop,
               "L-Py predefines no module " + shown(name) + ": it reads '@' and the letters after it as modules of "
               "their own, which draw nothing, and so does the converted word");
      label = "@";
      return at + 1;
    }
    if (best == 0) {
      uint32_t stop = at + 1;
      while (stop < end && isNameChar(text_[stop])) ++stop;
      fail(at, stop,
           std::string(dialectName(dialect_)) + "'s module " + shown(text_.substr(at, stop - at)) +
               " is none ontogen can translate (it knows @O, @o, @v, @M, @R, @L, @b, @Ge, @Gc" +
               (dialect_ == Dialect::LPy ? ", @B, @g, @h, @D, @Dd, @Di, @Ts, @Tp, @2D, @3D"
                                         : ", @Gs, @Gt, @Gr, @c, @bo, @bc, @D, @Dd, @Di, @Tx, @Ti, @Td, @Ts, @Tp, @Tf, "
                                           "@#, @!") +
               ")");
    }
    label = std::string(text_.substr(at, best));
    return at + static_cast<uint32_t>(best);
  }
  // A predefined surface, ~l: one letter names it in both tools.
  if (c == '~' && at + 1 < end && isLetter(text_[at + 1])) {
    label = std::string(text_.substr(at, 2));
    return at + 2;
  }
  if (dialect_ == Dialect::LPy && isLetter(c)) {
    // Longest declared or predefined name first; otherwise one letter is one module.
    size_t best = 1;
    auto consider = [&](std::string_view name) {
      if (name.size() > best && at + name.size() <= end && text_.compare(at, name.size(), name) == 0)
        best = name.size();
    };
    for (const std::string& name : declaredNames) consider(name);
    for (const Predefined& p : predefinedModules())
      if (p.name[0] != '@') consider(p.name);
    label = std::string(text_.substr(at, best));
    return at + static_cast<uint32_t>(best);
  }
  if (isNameChar(c) || isCellSymbol(c) || c == ';' || c == ',' || c == '{' || c == '}' || c == '.' ||
      (dialect_ == Dialect::Cpfg && (c == '#' || c == '='))) {
    label = std::string(1, c);
    return at + 1;
  }
  std::string name(1, c);
  if (static_cast<unsigned char>(c) >= 0x80) {
    uint32_t stop = at + 1;
    while (stop < end && (static_cast<unsigned char>(text_[stop]) & 0xC0) == 0x80) ++stop;
    name = std::string(text_.substr(at, stop - at));
  }
  fail(at, at + 1,
       "the module " + shown(name) + " of " + std::string(dialectName(dialect_)) +
           " has no cell-language spelling (labels are names or one of + - ^ & / \\ | ! < > [ ] $ ~ @ %)");
}

void ForeignSyntax::warnOnce(const std::string& label, uint32_t begin, uint32_t end, std::string message) const {
  if (!warned_.insert(label).second) return;
  warnings.push_back({SourceRange{begin, end > begin ? end : begin + 1}, std::move(message)});
}

// A module of the other tool's vocabulary as the cell language has it (kPredefined).
void ForeignSyntax::vocabulary(ModuleText& module, uint32_t begin, uint32_t end, bool pattern) const {
  if (auto alias = aliases.find(module.label); alias != aliases.end()) module.label = alias->second;
  if (declaredNames.count(module.label)) return;  // the file's own module
  const std::string tool(dialectName(dialect_));
  auto inert = [&](std::string name, const std::string& what) {
    warnOnce(module.label, begin, end,
             tool + "'s " + what + " " + shown(module.label) +
                 " has no counterpart in ontogen's turtle: it stays a module named " + shown(name) +
                 ", so the word is " + tool + "'s, but it draws nothing");
    module.label = std::move(name);
  };
  const std::string label = module.label;
  if (label == "?P" || label == "?H" || label == "?L" || label == "?U") {
    if (module.hasArgs) return;
    // L-Py writes a query bare; ontogen's has the three parameters the turtle fills.
    if (pattern)
      fail(begin, end,
           "a query " + shown(label) + " without parameters in a pattern: write " + label +
               "(x, y, z) to match it",
           false);
    module.hasArgs = true;
    module.args = {"0", "0", "0"};
    return;
  }
  if (label == ";" || (label == "," && module.hasArgs && !module.args.empty())) {
    module.label = "color";  // ;  and ;(i) take the next colour or colour i; ,(i) colour i
    return;
  }
  if (label == ",") return inert("DecColor", "colour module (the previous colour)");
  if (label == "{") return inert("BP", "polygon module");
  if (label == "}") return inert("EP", "polygon module");
  if (label == ".") return inert("PP", "polygon module");
  if (label == "#") return inert("IncWidth", "module");
  if (label == "=" && !pattern)  // in a right context: production() reads it
    fail(begin, end,
         "cpfg's '=' (in a right context before ']': the rest of the branch) as a module, which the cell "
         "language cannot spell");
  if (label.size() == 2 && label[0] == '~') return inert("Surface_" + label.substr(1), "surface");
  const Predefined* p = predefined(label, dialect_);
  if (!p) return;
  if (p->fate == Fate::Refuse)
    fail(begin, end, tool + "'s module " + shown(label) + " has no cell-language counterpart; the word would differ");
  if (p->fate == Fate::Inert) return inert(std::string(p->cell), "module");
  if (p->cell == "color" && module.args.size() > 1) return inert("SetColor", "colour by components");
  module.label = std::string(p->cell);
}

std::vector<ModuleText> ForeignSyntax::modules(uint32_t begin, uint32_t end, bool pattern) const {
  std::vector<ModuleText> result;
  uint32_t at = begin;
  uint32_t tokenEnd = begin;  // cpfg: the end of the C token `at` is within
  while (at < end) {
    if (isSpace(text_[at])) {
      ++at;
      continue;
    }
    // cpfg reads its file through the C preprocessor, which puts a macro's text in place
    // of a name (a whole C token: `BACKGROUND`, not the B of `AB`): its modules.
    if (dialect_ == Dialect::Cpfg && at >= tokenEnd && isNameChar(text_[at])) {
      tokenEnd = at;
      while (tokenEnd < end && isNameChar(text_[tokenEnd])) ++tokenEnd;
      const auto macro = isLetter(text_[at]) ? macros.find(text_.substr(at, tokenEnd - at)) : macros.end();
      uint32_t next = tokenEnd;
      while (next < end && isSpace(text_[next])) ++next;
      if (macro != macros.end() && next < end && text_[next] == '(')
        fail(at, next + 1,
             "the macro " + shown(macro->first) +
                 " before parameters: C's preprocessor puts its value in place of the name, so the parameters "
                 "would be its last module's; give the module another name than the macro");
      if (macro != macros.end()) {
        // Macros of modules that name macros multiply as those in expressions do.
        countInlined(macro->second.end - macro->second.begin, at, tokenEnd);
        const Nested nested(*this, at, tokenEnd);
        for (ModuleText& m : modules(macro->second.begin, macro->second.end, pattern)) result.push_back(std::move(m));
        at = tokenEnd;
        continue;
      }
      if (next < end && text_[next] == '(' && functions.count(text_.substr(at, tokenEnd - at)))
        fail(at, tokenEnd,
             "a macro with parameters among modules: C puts its value there, which the converter does not "
             "write among modules (it writes a macro's value of modules without parameters)");
    }
    if (text_[at] == '(' || text_[at] == ')')
      fail(at, at + 1, "expected a module before " + shown(text_.substr(at, 1)), false);
    ModuleText module;
    const uint32_t moduleBegin = at;
    if (dialect_ == Dialect::LPy && text_.compare(at, 4, "None") == 0 && at + 4 <= end &&
        (at + 4 == end || !isNameChar(text_[at + 4])) && !declaredNames.count("None")) {
      if (!pattern) fail(at, at + 4, "L-Py's None stands in a context, for no module there", false);
      // L-Py's None in a context: no module there, the cell language's ∅ (the start of
      // the word on the left, the end of the branch or word on the right).
      module.label = "∅";
      at += 4;
      result.push_back(std::move(module));
      continue;
    }
    if (text_[at] == '*' && pattern) {
      module.label = "*";  // a wildcard in a context
      ++at;
    } else if (text_[at] == '*') {
      fail(at, at + 1, "'*' (the empty word) stands alone as a successor, as in A --> *", false);
    } else if (pattern && dialect_ == Dialect::LPy && text_.substr(at, 3) == "or(") {
      module.label = "or";  // L-Py's alternatives, below
      at += 2;
    } else {
      at = moduleEnd(at, end, module.label);
    }
    if (pattern && dialect_ == Dialect::LPy && module.label == "x" && at < end && text_[at] == '(' &&
        !declaredNames.count("x"))
      fail(moduleBegin, at + 1,
           "L-Py's repetition x(...) in a context has no cell-language counterpart (a context of the cell "
           "language is a fixed sequence of modules)");
    // cpfg's reader passes over spaces between a module and its parameters, `\ (90)`.
    if (dialect_ == Dialect::Cpfg) {
      uint32_t next = at;
      while (next < end && isSpace(text_[next])) ++next;
      if (next < end && text_[next] == '(') at = next;
    }
    if (at < end && text_[at] == '(') {
      int depth = 0;
      uint32_t stop = at;
      for (; stop < end; ++stop) {
        if (text_[stop] == '(') ++depth;
        if (text_[stop] == ')' && --depth == 0) break;
      }
      if (stop >= end) fail(at, end, "the parameters of " + shown(module.label) + " have no closing ')'", false);
      if (pattern && dialect_ == Dialect::LPy && module.label == "or") {
        const Nested nested(*this, moduleBegin, stop + 1);
        // L-Py's or(B(x) C, D) in a context: the cell language's alternatives (B(x) C | D).
        std::string group;
        uint32_t argBegin = at + 1;
        for (uint32_t comma = find(argBegin, stop, ","); argBegin <= stop; comma = find(argBegin, stop, ",")) {
          std::string sequence;
          uint32_t a = argBegin, b = comma;
          trim(a, b);
          // L-Py's None: an alternative of nothing.
          const bool none = text_.substr(a, b - a) == "None";
          for (const ModuleText& item : none ? std::vector<ModuleText>{} : modules(argBegin, comma, true)) {
            sequence += (sequence.empty() ? "" : " ") + item.label;
            if (!item.hasArgs) continue;
            sequence += "(";
            for (size_t k = 0; k < item.args.size(); ++k) sequence += (k ? ", " : "") + item.args[k];
            sequence += ")";
          }
          group += (group.empty() ? "(" : sequence.empty() ? " |" : " | ") + sequence;
          if (comma == stop) break;
          argBegin = comma + 1;
        }
        module.label = group + ")";
        at = stop + 1;
        result.push_back(std::move(module));
        continue;
      }
      module.hasArgs = true;
      bool skippedLabel = false;  // L-Py's *(name, ...)
      uint32_t argBegin = at + 1;
      // L-Py's vector parameters (foreign_vectors.cpp), by the number of parameters.
      size_t count = 0;
      for (uint32_t from = argBegin; from <= stop; from = find(from, stop, ",") + 1) ++count;
      const std::pair<std::string, size_t> key{module.label, count};
      size_t index = 0;
      auto dimension = [&]() {
        const auto slots = vectorParameters.find(key);
        return slots == vectorParameters.end() ? 0 : slots->second[index];
      };
      // Parameters split at commas outside inner parentheses.
      for (uint32_t comma = find(argBegin, stop, ","); argBegin <= stop; comma = find(argBegin, stop, ",")) {
        uint32_t a = argBegin, b = comma;
        trim(a, b);
        if (a == b) {
          if (comma == stop && module.args.empty()) break;  // X()
          fail(argBegin, comma, "an empty parameter of " + shown(module.label), false);
        }
        if (pattern) {
          std::string_view name = text_.substr(a, b - a);
          bool isName = isLetter(name[0]);
          for (char c : name) isName = isName && isNameChar(c);
          // A value pattern, A(3) or A(-1.5): a number, as the cell language writes it.
          bool isNumber = !name.empty();
          size_t digits = 0;
          for (size_t k = 0; k < name.size(); ++k) {
            const char c = name[k];
            if (std::isdigit(static_cast<unsigned char>(c)))
              ++digits;
            else if (!(c == '.' || (c == '-' && k == 0)))
              isNumber = false;
          }
          isNumber = isNumber && digits > 0;
          if (name[0] == '*')
            fail(a, b,
                 "L-Py's '*args' takes any number of parameters; a pattern of the cell language takes a "
                 "fixed number, as in *(x, y)");
          if (const int d = dialect_ == Dialect::LPy ? dimension() : 0; d > 0) {
            if (!isName) fail(a, b, "a vector parameter's pattern other than a name");
            for (int k = 0; k < d; ++k) module.args.push_back(cellName(name) + "_" + std::to_string(k));
            vectorNames[cellName(name)] = d;
            ++index;
            if (comma == stop) break;
            argBegin = comma + 1;
            continue;
          }
          if (!isName && !isNumber)
            fail(a, b,
                 "a pattern's parameter " + shown(std::string(name)) +
                     " is neither a name nor a number; write a "
                     "name and test it in a condition, as in " +
                     module.label + "(x) : x == ...");
          // L-Py's wildcard names the module's label first, *(name, x): the cell language
          // has numbers only, so its wildcard binds the parameters alone.
          if (dialect_ == Dialect::LPy && module.label == "*" && !skippedLabel)
            skippedLabel = true;
          else
            module.args.push_back(isNumber ? std::string(name) : cellName(name));
        } else if (std::optional<std::string> number = labelText(module.label, a, b)) {
          module.args.push_back(std::move(*number));
        } else if (const std::optional<int> call = dialect_ == Dialect::LPy ? vectorCall(a, b) : std::nullopt;
                   call || dimension() > 0) {
          if (!dimension()) {
            if (readModules_.count(key))
              fail(a, b, "a vector where the file gave this parameter of " + shown(module.label) + " a number before");
            vectorParameters[key].resize(count);
            vectorParameters[key][index] = *call;
          }
          for (std::string& c : vectorComponents(a, b, dimension())) module.args.push_back(std::move(c));
        } else {
          module.args.push_back(expression(a, b));
          if (dialect_ == Dialect::LPy) noVectorRead(module.args.back(), a, b);
        }
        ++index;
        if (comma == stop) break;
        argBegin = comma + 1;
      }
      if (dialect_ == Dialect::LPy) readModules_.insert(key);
      at = stop + 1;
    }
    vocabulary(module, moduleBegin, at, pattern);
    result.push_back(std::move(module));
  }
  return result;
}

std::optional<std::pair<uint32_t, uint32_t>> ForeignSyntax::textOfNumber(uint32_t a, uint32_t b) const {
  trim(a, b);
  if (text_.compare(a, 4, "str(") != 0) return std::nullopt;
  uint32_t close = find(a + 3, b, ")");
  if (close >= b) return std::nullopt;
  // str(x)[:5]: the text cut, still of the number x.
  if (close + 1 < b && (text_[close + 1] != '[' || text_[b - 1] != ']' || find(close + 1, b, "]") != b - 1))
    return std::nullopt;
  uint32_t x = a + 4, y = close;
  trim(x, y);
  // str(round(x, 2)): the text of x rounded, still of the number x.
  if (text_.compare(x, 6, "round(") == 0 && find(x + 5, y, ")") == y - 1) {
    const uint32_t comma = find(x + 6, y - 1, ",");
    if (comma < y - 1) y = comma;
    x += 6;
    trim(x, y);
  }
  return std::pair{x, y};
}

std::optional<std::string> ForeignSyntax::labelText(const std::string& label, uint32_t a, uint32_t b) const {
  if (dialect_ != Dialect::LPy || (label != "@L" && label != "Label")) return std::nullopt;
  std::optional<std::string> number;
  if (auto x = textOfNumber(a, b)) {
    number = expression(x->first, x->second);
  } else {
    // A helper function of one line returning such a text, `def txt(v): return str(v)`.
    uint32_t open = a;
    while (open < b && isNameChar(text_[open])) ++open;
    const auto function = functions.find(text_.substr(a, open - a));
    if (function == functions.end() || function->second.translated || open >= b || text_[open] != '(' ||
        find(open, b, ")") != b - 1)
      return std::nullopt;
    const auto inner = textOfNumber(function->second.begin, function->second.end);
    if (!inner) return std::nullopt;
    Function value = function->second;
    value.begin = inner->first;
    value.end = inner->second;
    uint32_t stop = b;
    number = inlined(value, a, a, open, b, stop);
  }
  warnOnce("the text of a number in a Label", a, b,
           "L-Py's Label shows the text of a number (str(x), rounded or cut): the converted Label holds the number "
           "x itself (the word writes it as a number, not as Python's text of it), and draws nothing");
  return number;
}

std::string ForeignSyntax::maximumDepth(uint32_t begin, uint32_t end) const {
  std::string value = expression(begin, end);
  char* stop = nullptr;
  const double depth = std::strtod(value.c_str(), &stop);
  if (stop == value.c_str() + value.size() && depth > kMaxRewriteDepth) {
    trim(begin, end);
    warnings.push_back({SourceRange{begin, end},
                        "maximum depth " + value + " is above ontogen's limit of " +
                            std::to_string(kMaxRewriteDepth) + ": the block rewrites at most " +
                            std::to_string(kMaxRewriteDepth) +
                            " deep, which differs only where the rules recurse deeper"});
    value = std::to_string(kMaxRewriteDepth);
  }
  return value;
}

std::vector<std::string> ForeignSyntax::symbols(uint32_t begin, uint32_t end) const {
  std::vector<std::string> result;
  for (const ModuleText& module : modules(begin, end, false)) result.push_back(module.label);
  return result;
}

void ForeignSyntax::checkPredecessor(const ModuleText& predecessor, uint32_t begin, uint32_t end) const {
  trim(begin, end);
  if (predecessor.label == "*")
    fail(begin, end,
         "a wildcard predecessor: a production of the cell language belongs to the module it rewrites; "
         "write one production per label");
  if (!predecessor.label.empty() && predecessor.label[0] == '(')
    fail(begin, end, "alternatives as the predecessor: write one production per alternative");
}

Statement ForeignSyntax::production(uint32_t begin, uint32_t end) const {
  Statement s;
  vectorNames.clear();
  uint32_t arrow = find(begin, end, "-->");
  uint32_t arrowEnd = arrow + 3;
  if (arrow == end) {
    arrow = find(begin, end, "->");
    arrowEnd = arrow + 2;
  }
  // The head: left < predecessor > right : condition.
  uint32_t headEnd = arrow;
  const uint32_t colon = find(begin, arrow, ":");
  uint32_t condBegin = arrow, condEnd = arrow;
  if (colon < arrow) {
    uint32_t a = colon + 1, b = arrow;
    trim(a, b);
    if (text_.substr(a, b - a) != "*") {  // cpfg's '*': no condition
      condBegin = a;
      condEnd = b;
    }
    headEnd = colon;
  }
  uint32_t predBegin = begin, predEnd = headEnd;
  const uint32_t less = find(begin, headEnd, "<");
  if (less < headEnd) {
    s.leftArrow = text_.compare(less, 2, "<<") == 0 ? "<<" : "<";
    s.left = modules(begin, less, true);
    predBegin = less + static_cast<uint32_t>(s.leftArrow.size());
  }
  const uint32_t greater = find(predBegin, headEnd, ">");
  if (greater < headEnd) {
    s.rightArrow = text_.compare(greater, 2, ">>") == 0 ? ">>" : ">";
    s.right = modules(greater + static_cast<uint32_t>(s.rightArrow.size()), headEnd, true);
    predEnd = greater;
  }
  // cpfg's '=' before ']' in a right context skips the rest of the branch, as the cell
  // language's ']' in a right context does. cpfg's ']' alone matches only where the
  // branch ends right there (ignored modules and nested branches aside), which the cell
  // language cannot say; '=' anywhere else has no counterpart either.
  if (dialect_ == Dialect::Cpfg)
    for (size_t i = 0; i < s.right.size(); ++i) {
      const bool skips = s.right[i].label == "=" && !s.right[i].hasArgs && i + 1 < s.right.size() &&
                         s.right[i + 1].label == "]";
      if (s.right[i].label == "=" && !skips)
        fail(greater, headEnd,
             "cpfg's '=' in a right context stands before ']' (the rest of the branch); elsewhere it has no "
             "cell-language counterpart");
      if (s.right[i].label == "]")
        fail(greater, headEnd,
             "cpfg's ']' in a right context matches where the branch ends right after the modules before it; "
             "the cell language's skips the rest of the branch, as cpfg's '=]' does: this context has no "
             "counterpart");
      if (skips) s.right.erase(s.right.begin() + static_cast<std::ptrdiff_t>(i));  // the ']' is next
    }
  for (const ModuleText& m : s.left)
    if (m.label == "=")
      fail(begin, less, "cpfg's '=' in a left context has no cell-language counterpart (it skips the rest of a "
                        "branch in a right context)");
  std::vector<ModuleText> predecessor = modules(predBegin, predEnd, true);
  for (const ModuleText& m : predecessor)
    if (m.label == "=") fail(predBegin, predEnd, "cpfg's '=' as a predecessor: it stands in a right context before ']'");
  if (predecessor.size() != 1) {
    uint32_t a = predBegin, b = predEnd;
    trim(a, b);
    // cpfg rewrites modules that stand strictly side by side together; the cell language
    // one module a production, and contexts would match across ignored modules and
    // branches, and overlapping occurrences, where cpfg's predecessor does not.
    if (!predecessor.empty() && dialect_ == Dialect::Cpfg)
      fail(a, b,
           "cpfg's predecessor of " + std::to_string(predecessor.size()) + " modules (" +
               std::string(text_.substr(a, b - a)) +
               "): the cell language rewrites one module a production, and contexts would also match across "
               "ignored modules and branches, where cpfg's modules must stand side by side");
    fail(a, b,
         predecessor.empty() ? std::string("expected a predecessor before the arrow")
                             : "a production has one predecessor module, found " + std::to_string(predecessor.size()) +
                                   " (" + std::string(text_.substr(a, b - a)) + ")",
         false);
  }
  checkPredecessor(predecessor.front(), predBegin, predEnd);
  s.predecessor = std::move(predecessor.front());
  // The production's parameters hide the globals of the same name.
  const Scope scope(*this, parametersOf(s));
  // cpfg's blocks around the condition, `{t = t - PL;} t > 0 {u = t / 2;}`: assignments
  // put in where they are read after them.
  std::vector<std::pair<std::string, std::string>> locals;
  if (condBegin < condEnd) {
    uint32_t a = condBegin, b = condEnd;
    if (text_[a] == '{') a = block(a, b, s, begin, end, locals);
    const uint32_t post = find(a, b, "{");
    uint32_t x = a, y = post;
    trim(x, y);
    // cpfg's '*' between blocks is no condition, as it is alone.
    if (x < y && text_.substr(x, y - x) != "*") s.condition = substituted(condition(x, y), locals);
    if (post < b && block(post, b, s, begin, end, locals) < b)
      fail(post, b, "a C block '{ ... }' in the condition: C code, which ontogen convert does not translate", false);
  }
  // The body: successors : probability (cpfg's stochastic productions).
  uint32_t bodyEnd = end;
  const uint32_t probability = find(arrowEnd, end, ":");
  if (probability < end) {
    if (dialect_ == Dialect::LPy)
      fail(probability, probability + 1, "L-Py writes no probability after a production; this ':' cannot be read",
           false);
    s.probability = expression(probability + 1, end);
    bodyEnd = probability;
  }
  uint32_t a = arrowEnd, b = bodyEnd;
  trim(a, b);
  if (text_.substr(a, b - a) != "*") s.successors = modules(a, b, false);
  for (ModuleText& m : s.successors)
    for (std::string& arg : m.args) arg = substituted(arg, locals);
  if (!s.probability.empty()) s.probability = substituted(s.probability, locals);
  written(statementLineBytes(s));
  return s;
}

void ForeignSyntax::written(uint64_t bytes) const {
  fits(bytes);
  writtenBytes_ += bytes;
}

void ForeignSyntax::fits(uint64_t bytes) const {
  if (bytes > maxWrittenBytes_ - std::min(writtenBytes_, maxWrittenBytes_)) throw ConvertedTextTooLarge{maxWrittenBytes_};
}

std::string ForeignSyntax::substituted(const std::string& expr,
                                       const std::vector<std::pair<std::string, std::string>>& locals) const {
  std::string result;
  for (size_t i = 0; i < expr.size();) {
    const bool starts = isLetter(expr[i]) && (i == 0 || !(isNameChar(expr[i - 1]) || expr[i - 1] == '.'));
    if (!starts) {
      result += expr[i++];
      continue;
    }
    size_t stop = i;
    while (stop < expr.size() && isNameChar(expr[stop])) ++stop;
    const std::string name = expr.substr(i, stop - i);
    const std::string* value = nullptr;
    for (const auto& [local, text] : locals)
      if (local == name) value = &text;
    result += value && (stop == expr.size() || expr[stop] != '(') ? *value : name;
    fits(result.size());
    i = stop;
  }
  return result;
}

ForeignSyntax::Scope::Scope(const ForeignSyntax& syntax, std::set<std::string, std::less<>> names)
    : syntax_(syntax), saved_(std::exchange(syntax.bound_, std::move(names))) {}

std::set<std::string, std::less<>> parametersOf(const Statement& production) {
  std::set<std::string, std::less<>> names;
  for (const std::vector<ModuleText>* modules : {&production.left, &production.right})
    for (const ModuleText& m : *modules) names.insert(m.args.begin(), m.args.end());
  names.insert(production.predecessor.args.begin(), production.predecessor.args.end());
  return names;
}

bool rewritesTheAxiom(const LSystemFile& file) {
  bool homomorphism = false;
  for (const Statement& s : file.statements) {
    if (s.kind == StatementKind::Section) homomorphism = s.word == "homomorphism";
    if (s.kind == StatementKind::Production && !homomorphism) return true;
  }
  return false;
}

bool ForeignSyntax::bindsParameter(size_t at, std::string_view name) const {
  // The statement's first line: cpfg continues a statement on lines that start with a tab.
  size_t begin = text_.rfind('\n', at) == std::string_view::npos ? 0 : text_.rfind('\n', at) + 1;
  while (begin >= 2 && text_[begin] == '\t') {
    const size_t before = text_.rfind('\n', begin - 2);
    begin = before == std::string_view::npos ? 0 : before + 1;
  }
  size_t arrow = text_.find("->", begin);
  if (arrow == std::string_view::npos) return false;
  // The head ends at the condition's ':' or the arrow; the statement must reach `at`.
  size_t head = begin;
  int depth = 0;
  for (; head < arrow && !(depth == 0 && text_[head] == ':'); ++head) {
    if (text_[head] == '\n' && (head + 1 >= text_.size() || text_[head + 1] != '\t')) return false;
    if (text_[head] == '(') ++depth;
    if (text_[head] == ')') --depth;
  }
  for (size_t k = arrow; k < at; ++k)
    if (text_[k] == '\n' && (k + 1 >= text_.size() || text_[k + 1] != '\t')) return false;
  depth = 0;
  for (size_t k = begin; k < head; ++k) {
    if (text_[k] == '(') ++depth;
    if (text_[k] == ')') --depth;
    if (depth > 0 && text_.compare(k, name.size(), name) == 0 && !isNameChar(text_[k - 1]) &&
        (k + name.size() >= text_.size() || !isNameChar(text_[k + name.size()])))
      return true;
  }
  return false;
}

// A block `{ name = expr; ... }` at `at` of a cpfg condition; the offset after its '}'.
// A name that is no parameter of the production is a variable of the whole file in
// cpfg: it is taken as the production's own only where every other line that reads it
// assigns it in a block of its own.
uint32_t ForeignSyntax::block(uint32_t at, uint32_t end, const Statement& s, uint32_t statementBegin,
                              uint32_t statementEnd, std::vector<std::pair<std::string, std::string>>& locals) const {
  uint32_t close = at;
  for (int depth = 0; close < end; ++close) {
    if (text_[close] == '{') ++depth;
    if (text_[close] == '}' && --depth == 0) break;
  }
  if (close >= end) fail(at, at + 1, "a C block '{' without its '}'", false);
  auto code = [&](uint32_t a, uint32_t b, const std::string& what) {
    fail(a, b, what + ": C code, which ontogen convert does not translate (it reads blocks of assignments "
                      "name = expression; before and after a condition)");
  };
  // The statements end at ';', and at the braces of a compound statement within the
  // block, `{{ y = 1; }}`, whose assignments are the block's in their order.
  for (uint32_t from = at + 1; from < close;) {
    uint32_t semi = from;
    while (semi < close && text_[semi] != ';' && text_[semi] != '{' && text_[semi] != '}') ++semi;
    uint32_t a = from, b = semi;
    trim(a, b);
    from = semi + 1;
    if (a == b) continue;
    uint32_t stop = a;
    while (stop < b && isNameChar(text_[stop])) ++stop;
    uint32_t eq = stop;
    while (eq < b && isSpace(text_[eq])) ++eq;
    if (stop == a || !isLetter(text_[a]) || eq >= b || text_[eq] != '=' || (eq + 1 < b && text_[eq + 1] == '='))
      code(a, b, "a statement other than an assignment in a C block");
    const std::string name(text_.substr(a, stop - a));
    bool parameter = false;
    auto binds = [&](const std::vector<ModuleText>& modules) {
      for (const ModuleText& m : modules)
        for (const std::string& arg : m.args) parameter = parameter || arg == name;
    };
    binds(s.left);
    binds({s.predecessor});
    binds(s.right);
    if (!parameter) {
      // Every other place of the name must be on a line that assigns it in a block, or in
      // a production that has a parameter of that name (its own).
      for (size_t k = text_.find(name); k != std::string_view::npos; k = text_.find(name, k + 1)) {
        if ((k > 0 && isNameChar(text_[k - 1])) || (k + name.size() < text_.size() && isNameChar(text_[k + name.size()])))
          continue;
        if (k >= statementBegin && k < statementEnd) continue;
        if (bindsParameter(k, name)) continue;
        size_t lineBegin = text_.rfind('\n', k) == std::string_view::npos ? 0 : text_.rfind('\n', k) + 1;
        size_t lineEnd = text_.find('\n', k);
        if (lineEnd == std::string_view::npos) lineEnd = text_.size();
        // The whole statement: cpfg continues one on the lines after it that start with a tab.
        while (lineBegin >= 2 && text_[lineBegin] == '\t') {
          const size_t previous = text_.rfind('\n', lineBegin - 2);
          lineBegin = previous == std::string_view::npos ? 0 : previous + 1;
        }
        while (lineEnd + 1 < text_.size() && text_[lineEnd + 1] == '\t') {
          lineEnd = text_.find('\n', lineEnd + 1);
          if (lineEnd == std::string_view::npos) lineEnd = text_.size();
        }
        const std::string_view line = text_.substr(lineBegin, lineEnd - lineBegin);
        const size_t brace = line.find('{');
        bool assigns = brace != std::string_view::npos && line.find("-->") != std::string_view::npos;
        if (assigns) {
          const size_t own = line.find(name, brace);
          size_t after = own == std::string_view::npos ? line.size() : own + name.size();
          while (after < line.size() && isSpace(line[after])) ++after;
          assigns = after < line.size() && line[after] == '=' && (after + 1 >= line.size() || line[after + 1] != '=');
        }
        if (!assigns)
          code(a, stop,
               "the variable '" + name +
                   "', which other statements of the file read (a variable of cpfg holds its value between "
                   "productions)");
      }
    }
    std::string value = substituted(expression(eq + 1, b), locals);
    written(value.size());
    locals.emplace_back(cellName(name), "(" + value + ")");
  }
  return close + 1;
}

}  // namespace ontogen::convert
