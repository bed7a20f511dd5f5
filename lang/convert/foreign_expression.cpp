// ForeignSyntax's expressions (declared in foreign_syntax.h): C's in cpfg and Python's in
// L-Py, read token by token into the cell language's, with the calls of helper functions
// and macros put in and the operators whose meaning differs rewritten (python_operators.h).
#include <cctype>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lang/convert/cpfg_macro_text.h"
#include "lang/convert/foreign_syntax.h"
#include "lang/convert/foreign_text.h"
#include "lang/convert/python_operators.h"

namespace ontogen::convert {

using chars::isCellSymbol;
using chars::isLetter;
using chars::isNameChar;
using chars::isSpace;
using chars::shown;

// The conditionals, C's `c ? a : b` and Python's `a if c else b`, become the cell
// language's if(c, a, b); they bind loosest, so they are split off first.
std::optional<std::string> ForeignSyntax::conditional(uint32_t begin, uint32_t end) const {
  if (dialect_ == Dialect::Cpfg) {
    const uint32_t question = find(begin, end, "?");
    if (question == end) return std::nullopt;
    const Nested nested(*this, question, question + 1);
    // The ':' that matches this '?' (conditionals nest to the right).
    int open = 0;
    uint32_t colon = end;
    int depth = 0;
    for (uint32_t at = question + 1; at < end && colon == end; ++at) {
      if (text_[at] == '(') ++depth;
      if (text_[at] == ')') --depth;
      if (depth != 0) continue;
      if (text_[at] == '?') ++open;
      if (text_[at] == ':' && open-- == 0) colon = at;
    }
    if (colon == end) fail(question, question + 1, "a '?' without its ':'", false);
    return "if(" + condition(begin, question) + ", " + expression(question + 1, colon) + ", " +
           expression(colon + 1, end) + ")";
  }
  auto word = [&](uint32_t from, std::string_view name) {
    for (uint32_t at = find(from, end, name); at < end; at = find(at + 1, end, name)) {
      const bool startsWord = at == begin || !isNameChar(text_[at - 1]);
      const bool endsWord = at + name.size() >= end || !isNameChar(text_[at + name.size()]);
      if (startsWord && endsWord) return at;
    }
    return end;
  };
  const uint32_t ifAt = word(begin, "if");
  if (ifAt == end) return std::nullopt;
  const Nested nested(*this, ifAt, ifAt + 2);
  const uint32_t elseAt = word(ifAt + 2, "else");
  if (elseAt == end) fail(ifAt, ifAt + 2, "Python's 'if' without 'else' in an expression", false);
  return "if(" + condition(ifAt + 2, elseAt) + ", " + expression(begin, ifAt) + ", " + expression(elseAt + 4, end) +
         ")";
}

bool ForeignSyntax::atomic(uint32_t begin, uint32_t end) const {
  trim(begin, end);
  if (begin == end) return false;
  uint32_t at = begin;
  while (at < end && (isNameChar(text_[at]) || text_[at] == '.')) ++at;
  if (at == end) return true;
  while (at < end && isSpace(text_[at])) ++at;
  if (at < end && text_[at] == '(' && (at == begin || isNameChar(text_[begin]))) {
    int depth = 0;
    for (uint32_t k = at; k < end; ++k) {
      if (text_[k] == '(') ++depth;
      if (text_[k] == ')' && --depth == 0) return k + 1 == end;
    }
  }
  return false;
}

std::string ForeignSyntax::inlined(const Function& function, uint32_t begin, uint32_t at, uint32_t open,
                                   uint32_t end, uint32_t& stop) const {
  const std::string name(text_.substr(at, open - at));
  int depth = 0;
  uint32_t close = open;
  for (; close < end; ++close) {
    if (text_[close] == '(') ++depth;
    if (text_[close] == ')' && --depth == 0) break;
  }
  if (close >= end) fail(at, end, "the call of '" + name + "' has no closing ')'", false);
  const Nested nested(*this, at, close + 1);
  std::vector<std::pair<std::string, std::string>> arguments;
  uint32_t a = open + 1, b = close;
  trim(a, b);
  for (uint32_t from = open + 1; a < b && from <= close;) {
    const uint32_t comma = find(from, close, ",");
    if (arguments.size() < function.parameters.size()) {
      std::string value = expression(from, comma);
      bool single = true;  // a name or a number needs no parentheses
      for (char c : value) single = single && (isNameChar(c) || c == '.');
      // The body spells the parameter as the cell language does (`time` is `time_`).
      arguments.emplace_back(cellName(function.parameters[arguments.size()]), single ? value : "(" + value + ")");
    }
    else
      arguments.emplace_back("", "");
    from = comma + 1;
  }
  if (arguments.size() != function.parameters.size())
    fail(at, close + 1,
         "the function '" + name + "' takes " + std::to_string(function.parameters.size()) +
             " parameters; this call gives " + std::to_string(arguments.size()),
         false);
  // A C macro is replaced as text: its value is the same as that of the parenthesised
  // expression only where each parameter and the body are single operands where they
  // stand; elsewhere (#define sq(x) x*x with sq(a+1)) C reads another expression.
  if (dialect_ == Dialect::Cpfg) {
    auto alone = [](char before, char after) {
      return (before == '\0' || before == '(' || before == ',') && (after == '\0' || after == ')' || after == ',');
    };
    auto compound = [this](std::string_view macro) {
      auto found = macros.find(macro);
      return found != macros.end() && !plainMacro(found->second, 0);
    };
    if (!atomic(function.begin, function.end) && !alone(previous(at, begin), following(close + 1, end)) &&
        !replacementReadsAsParenthesised(text_.substr(function.begin, function.end - function.begin),
                                         text_.substr(begin, at - begin), text_.substr(close + 1, end - close - 1),
                                         compound))
      fail(at, close + 1,
           "the macro '" + name +
               "' is replaced as text by C: its value, which is no single operand, would join the operators around "
               "this call; put the macro's value in parentheses");
    uint32_t from = open + 1;
    for (const std::string& parameter : function.parameters) {
      const uint32_t comma = find(from, close, ",");
      if (!atomic(from, comma)) {
        for (uint32_t k = function.begin; k < function.end; ++k) {
          if (text_.compare(k, parameter.size(), parameter) != 0 || (k > 0 && isNameChar(text_[k - 1])) ||
              (k + parameter.size() < text_.size() && isNameChar(text_[k + parameter.size()])))
            continue;
          const uint32_t after = k + static_cast<uint32_t>(parameter.size());
          if (!alone(previous(k, function.begin), following(after, function.end)))
            fail(from, comma,
                 "the macro '" + name + "' is replaced as text by C: this argument, which is no single operand, "
                 "would join the operators around '" + parameter + "' in its value; put the argument in parentheses");
        }
      }
      from = comma + 1;
    }
  }
  std::string body;
  if (function.untranslatable) throw *function.untranslatable;
  if (function.translated) {
    body = *function.translated;
  } else if (dialect_ == Dialect::LPy) {
    // A Python function reads its own parameters, not the caller's, over the globals.
    const Scope scope(*this, {function.parameters.begin(), function.parameters.end()});
    body = expression(function.begin, function.end);
  } else {
    body = expression(function.begin, function.end);
  }
  // A Python function reads the globals of the file; written into the caller, a name the
  // caller binds (a production's parameter, a body's local) would read the caller's.
  if (dialect_ == Dialect::LPy) {
    for (size_t i = 0; i < body.size();) {
      if (!isLetter(body[i]) || (i > 0 && (isNameChar(body[i - 1]) || body[i - 1] == '.'))) {
        ++i;
        continue;
      }
      size_t nameEnd = i;
      while (nameEnd < body.size() && isNameChar(body[nameEnd])) ++nameEnd;
      const std::string global = body.substr(i, nameEnd - i);
      bool parameter = false;
      for (const std::string& p : function.parameters) parameter = parameter || p == global || cellName(p) == global;
      if (!parameter && (nameEnd >= body.size() || body[nameEnd] != '(') && bound_.count(global))
        fail(at, close + 1,
             "'" + name + "' reads the global " + shown(global) +
                 ", which is a parameter or local here: written into this production, it would read that instead");
      i = nameEnd;
    }
  }
  // An argument that draws a random number is drawn once by Python: it may be read once
  // (a C macro draws it as often as its text names it, as the cell language does).
  for (const auto& [parameter, value] : arguments) {
    size_t uses = 0;
    for (size_t k = body.find(parameter); k != std::string::npos; k = body.find(parameter, k + 1))
      if ((k == 0 || !(isNameChar(body[k - 1]) || body[k - 1] == '.')) &&
          (k + parameter.size() == body.size() || !isNameChar(body[k + parameter.size()])))
        ++uses;
    bool draws = false;
    for (std::string_view f : {"uniform(", "gaussian(", "ran(", "bernoulli("})
      draws = draws || value.find(f) != std::string::npos;
    if (uses > 1 && draws && dialect_ == Dialect::LPy)  // C's macros draw again as cpfg does
      fail(at, close + 1,
           "an argument that draws a random number, read " + std::to_string(uses) + " times by '" + name +
               "': the cell language would draw it anew each time; pass a local holding the draw");
  }
  stop = close + 1;
  std::string value = "(" + substituted(body, arguments) + ")";
  countInlined(value.size(), at, stop);
  return value;
}

// Macros that name macros multiply as calls within calls do: #define M1 M0+M0 ... M40
// would write 2^40 copies.
void ForeignSyntax::countInlined(size_t bytes, uint32_t at, uint32_t stop) const {
  inlinedBytes_ += bytes;
  if (inlinedBytes_ > kMaxInlinedBytes)
    fail(at, stop,
         "the calls of helper functions or macros write more than " + std::to_string(kMaxInlinedBytes >> 20) +
             " MiB (calls within calls multiply)",
         false);
}

char ForeignSyntax::previous(uint32_t at, uint32_t from) const {
  while (at > from && isSpace(text_[at - 1])) --at;
  return at == from ? '\0' : text_[at - 1];
}

char ForeignSyntax::following(uint32_t at, uint32_t to) const {
  while (at < to && isSpace(text_[at])) ++at;
  return at == to ? '\0' : text_[at];
}

bool ForeignSyntax::plainMacro(const Function& macro, int depth) const {
  if (!atomic(macro.begin, macro.end)) return false;
  uint32_t a = macro.begin, b = macro.end;
  trim(a, b);
  // A name that is itself a macro is as plain as that one's value.
  if (auto inner = macros.find(text_.substr(a, b - a)); inner != macros.end())
    return depth < kMaxConvertNesting && &inner->second != &macro && plainMacro(inner->second, depth + 1);
  return true;
}

namespace {

// The bytes [open, close] of a call's parentheses: the offset of its ')', or `end`.
uint32_t closingParenthesis(std::string_view text, uint32_t open, uint32_t end) {
  int depth = 0;
  for (uint32_t at = open; at < end; ++at) {
    if (text[at] == '(') ++depth;
    if (text[at] == ')' && --depth == 0) return at;
  }
  return end;
}

bool drawsRandom(std::string_view text) {
  for (std::string_view f : {"uniform(", "gaussian(", "ran(", "bernoulli("})
    if (text.find(f) != std::string_view::npos) return true;
  return false;
}

}  // namespace

std::optional<std::string> ForeignSyntax::degreeCall(const std::string& name, uint32_t at, uint32_t open,
                                                     uint32_t end, uint32_t& stop) const {
  const bool direct = name == "sin" || name == "cos" || name == "tan";
  const bool inverse = name == "asin" || name == "acos" || name == "atan";
  if (name == "atan2")
    fail(at, open,
         "cpfg's atan2, in degrees, whose arguments its evaluator takes in an order of its own: write "
         "atan(y / x) with the quadrant's test");
  if (!direct && !inverse) return std::nullopt;
  const uint32_t close = closingParenthesis(text_, open, end);
  if (close >= end) fail(at, end, "the call of '" + name + "' has no closing ')'", false);
  const Nested nested(*this, at, close + 1);
  const std::string x = expression(open + 1, close);
  stop = close + 1;
  // cpfg's angles are degrees (generate.c), the cell language's radians.
  return direct ? name + "(rad(" + x + "))" : "deg(" + name + "(" + x + "))";
}

std::string ForeignSyntax::splineCall(uint32_t at, uint32_t open, uint32_t end, uint32_t& stop) const {
  const uint32_t close = closingParenthesis(text_, open, end);
  if (close >= end) fail(at, end, "the call of 'func' has no closing ')'", false);
  const uint32_t comma = find(open + 1, close, ",");
  if (comma >= close) fail(at, close + 1, "cpfg's func(n, x) takes two arguments", false);
  // The function's number, written in the file or as a macro of a number.
  uint32_t a = open + 1, b = comma;
  trim(a, b);
  std::string number(text_.substr(a, b - a));
  if (auto macro = macros.find(number); macro != macros.end()) {
    uint32_t ma = macro->second.begin, mb = macro->second.end;
    trim(ma, mb);
    number = std::string(text_.substr(ma, mb - ma));
  }
  // A function set's names stand for the functions' numbers (cpfg defines them so).
  for (size_t i = 0; i < splineFunctions.size(); ++i) {
    if (splineFunctions[i].setUnread) fail(at, close + 1, "func(" + number + ", x): " + splineFunctions[i].error);
    if (!splineFunctions[i].name.empty() && splineFunctions[i].name == number) number = std::to_string(i + 1);
  }
  char* last = nullptr;
  const long n = std::strtol(number.c_str(), &last, 10);
  if (number.empty() || last != number.c_str() + number.size())
    fail(a, b, "the number of cpfg's function, func(n, x), is a whole number written in the file or a macro of one");
  if (n < 1 || static_cast<size_t>(n) > splineFunctions.size())
    fail(at, close + 1,
         "func(" + number + ", x): the view file names " + std::to_string(splineFunctions.size()) +
             " functions ('function: FILE N' lines), which func(1, x) and on read in order");
  const SampledFunction& function = splineFunctions[static_cast<size_t>(n) - 1];
  if (!function.error.empty()) fail(at, close + 1, "func(" + number + ", x): " + function.error);
  const Nested nested(*this, at, close + 1);
  uint32_t xa = comma + 1, xb = close;
  trim(xa, xb);
  const std::string x = expression(xa, xb);
  if (drawsRandom(x))
    fail(xa, xb,
         "an argument of func that draws a random number: the converter writes it once per sample, so it would "
         "be drawn anew each time");
  stop = close + 1;
  std::string value = sampledValue(function, x);
  countInlined(value.size(), at, stop);
  return value;
}

std::string ForeignSyntax::pythonRound(uint32_t at, uint32_t open, uint32_t end, uint32_t& stop) const {
  const uint32_t close = closingParenthesis(text_, open, end);
  if (close >= end) fail(at, end, "the call of 'round' has no closing ')'", false);
  const Nested nested(*this, at, close + 1);
  if (find(open + 1, close, ",") < close)
    fail(at, close + 1,
         "Python's round(x, n), to n decimals of x's exact binary value, has no cell-language counterpart; "
         "round(x * 10 ** n) / 10 ** n is near it");
  const std::string x = expression(open + 1, close);
  stop = close + 1;
  // Python 2 takes halves away from zero, as the cell language's round does.
  if (python2) return "round(" + x + ")";
  if (drawsRandom(x))
    fail(at, close + 1,
         "Python's round() of a value that draws a random number: Python 3 takes halves to the even "
         "neighbour, which writes the value three times, and the cell language would draw it anew each time; "
         "round a local holding the draw");
  // Python 3 takes halves to the even neighbour (round(2.5) is 2): x / 2 is then no half.
  return "if(fract(" + x + ") == 0.5, 2 * round((" + x + ") / 2), round(" + x + "))";
}

std::string ForeignSyntax::expression(uint32_t begin, uint32_t end) const {
  return expression(begin, end, nullptr);
}

std::string ForeignSyntax::condition(uint32_t begin, uint32_t end) const {
  truthNext_ = true;
  return expression(begin, end, nullptr);
}

std::string ForeignSyntax::expression(uint32_t begin, uint32_t end, std::vector<ExpressionToken>* raw) const {
  const bool truth = std::exchange(truthNext_, false);
  if (std::optional<std::string> chosen = conditional(begin, end)) {
    if (raw) *raw = {ExpressionToken{*chosen, begin, end, false}};
    return *chosen;
  }
  const bool python = dialect_ == Dialect::LPy;
  std::string out;
  // The tokens as written, for Python's operators the cell language spells otherwise.
  std::vector<ExpressionToken> tokens;
  uint32_t at = begin;
  auto emit = [&](std::string_view token, bool glueLeft = false, uint32_t length = 0) {
    tokens.push_back({std::string(token), at, at + (length ? length : static_cast<uint32_t>(token.size())), glueLeft});
    if (!out.empty() && !glueLeft && out.back() != '(' && out.back() != '!') out += ' ';
    out += token;
  };
  auto code = [&](uint32_t from, uint32_t stop, const std::string& what) {
    fail(from, stop,
         what + (python ? ": Python code, which ontogen convert does not translate (it reads L-Py's declarative "
                          "part: modules, productions with -->, conditions over arithmetic)"
                        : ": C code, which ontogen convert does not translate (it reads cpfg's productions, "
                          "conditions and expressions over arithmetic)"));
  };
  // Whether a conditional may stand inside parentheses here (looked for once).
  bool mayNestConditionals = false;
  for (uint32_t k = begin; k < end && !mayNestConditionals; ++k)
    mayNestConditionals = python ? text_.compare(k, 2, "if") == 0 && k + 2 <= end : text_[k] == '?';
  // Python's `not` binds looser than comparisons (`not x == 0` is `!(x == 0)`): its
  // operand runs to the next `and`, `or`, ',' or ')' at the same depth.
  std::vector<int> notDepths;
  int depth = 0;
  auto closeNots = [&] {
    while (!notDepths.empty() && notDepths.back() == depth) {
      tokens.push_back({")", at, at + 1, true});
      out += ")";
      notDepths.pop_back();
    }
  };
  while (at < end) {
    const char c = text_[at];
    if (isSpace(c)) {
      ++at;
      continue;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) ||
        (c == '.' && at + 1 < end && std::isdigit(static_cast<unsigned char>(text_[at + 1])))) {
      uint32_t stop = at;
      while (stop < end && (std::isdigit(static_cast<unsigned char>(text_[stop])) || text_[stop] == '.')) ++stop;
      if (stop < end && (text_[stop] == 'e' || text_[stop] == 'E')) {
        uint32_t exponent = stop + 1;
        if (exponent < end && (text_[exponent] == '+' || text_[exponent] == '-')) ++exponent;
        if (exponent < end && std::isdigit(static_cast<unsigned char>(text_[exponent]))) {
          stop = exponent;
          while (stop < end && std::isdigit(static_cast<unsigned char>(text_[stop]))) ++stop;
        }
      }
      emit(text_.substr(at, stop - at), false, stop - at);
      at = stop;
      continue;
    }
    if (isLetter(c)) {
      uint32_t stop = at;
      while (stop < end && (isNameChar(text_[stop]) || (python && text_[stop] == '.'))) ++stop;
      std::string name(text_.substr(at, stop - at));
      if (python) {
        // import random as rd: rd.uniform is random.uniform.
        if (const size_t dot = name.find('.'); dot != std::string::npos)
          if (auto alias = moduleAliases.find(std::string_view(name).substr(0, dot)); alias != moduleAliases.end())
            name = alias->second + name.substr(dot);
      }
      // cpfg's variables of the blocks around each step, unless a parameter hides one.
      if (auto variable = stepVariables.find(name); !python && variable != stepVariables.end() && !bound_.count(name)) {
        if (variable->second.stepEnd && inHomomorphism && !variable->second.afterStep.empty()) {
          emit("(" + variable->second.afterStep + ")", false, stop - at);
          at = stop;
          continue;
        }
        if (variable->second.stepEnd && inHomomorphism)
          fail(at, stop,
               "the variable '" + name +
                   "', which cpfg's EndEach: block changes after each step: after the last one, where the "
                   "homomorphism reads it, it is one step on, which the converter does not write");
        emit("(" + variable->second.value + ")", false, stop - at);
        at = stop;
        continue;
      }
      // cpfg's macro `#define X 1+2` among operators: its tokens, as C's replacement
      // reads them (2*X is 2*1+2).
      if (auto macro = macros.find(name); !python && macro != macros.end()) {
        const char before = previous(at, begin), after = following(stop, end);
        // In a macro's value being put in, "alone" is the place of the outer name.
        const bool alone = !raw && (before == '\0' || before == '(' || before == ',') &&
                           (after == '\0' || after == ')' || after == ',');
        const bool plain = plainMacro(macro->second);
        if (!macro->second.constant && (plain || alone)) {
          const Nested nested(*this, at, stop);
          const std::string value = "(" + expression(macro->second.begin, macro->second.end) + ")";
          countInlined(value.size(), at, stop);
          emit(value, false, stop - at);
          at = stop;
          continue;
        }
        if (!plain && !alone) {
          if (find(macro->second.begin, macro->second.end, "?") < macro->second.end)
            fail(at, stop,
                 "the macro '" + name +
                     "' is replaced as text by C: its value, a conditional c ? a : b, would take the operators "
                     "around it into its condition and branches; put the macro's value in parentheses");
          const Nested nested(*this, at, stop);
          std::vector<ExpressionToken> inner;
          expression(macro->second.begin, macro->second.end, &inner);
          size_t bytes = 0;
          for (const ExpressionToken& token : inner) bytes += token.text.size() + 1;
          countInlined(bytes, at, stop);
          for (const ExpressionToken& token : inner) {
            tokens.push_back({token.text, at, stop, token.glued});
            if (!out.empty() && !token.glued && out.back() != '(' && out.back() != '!') out += ' ';
            out += token.text;
          }
          at = stop;
          continue;
        }
      }
      if (auto vector = vectorNames.find(cellName(name)); vector != vectorNames.end()) {
        // L-Py's v[0] of a vector parameter: its component v_0.
        uint32_t open = stop;
        while (open < end && isSpace(text_[open])) ++open;
        const uint32_t close = open < end && text_[open] == '[' ? find(open, end, "]") : end;
        if (close < end) {
          uint32_t x = open + 1, y = close;
          trim(x, y);
          const std::string index(text_.substr(x, y - x));
          if (index.size() != 1 || index[0] < '0' || index[0] >= '0' + vector->second)
            fail(x, y, "an index of the vector " + shown(name) + " other than a written 0 to " +
                           std::to_string(vector->second - 1));
          emit(vector->first + "_" + index, false, close + 1 - at);
          at = close + 1;
          continue;
        }
      }
      if (auto array = arrays.find(name); array != arrays.end()) {
        uint32_t open = stop;
        while (open < end && isSpace(text_[open])) ++open;
        if (open < end && text_[open] == '[') {
          // A parameter or local of the same name is the one read, a number here.
          if (bound_.count(name) || bound_.count(cellName(name)))
            fail(at, stop,
                 "an element of " + shown(name) +
                     ", which here is a parameter or local (it hides the file's list or array of that name) and "
                     "holds one number in the cell language");
          emit(arrayElement(array->second, at, open, end, stop), false, stop - at);
          at = stop;
          continue;
        }
      }
      if (auto function = functions.find(name); function != functions.end()) {
        uint32_t open = stop;
        while (open < end && isSpace(text_[open])) ++open;
        if (open < end && text_[open] == '(') {
          uint32_t after = open;
          const std::string value = inlined(function->second, begin, at, open, end, after);
          emit(value, false, after - at);
          at = after;
          continue;
        }
      }
      if (!python) {
        uint32_t open = stop;
        while (open < end && isSpace(text_[open])) ++open;
        if (open < end && text_[open] == '(') {
          uint32_t after = open;
          if (std::optional<std::string> call = degreeCall(name, at, open, end, after)) {
            emit(*call, false, after - at);
            at = after;
            continue;
          }
          if (name == "func") {
            emit(splineCall(at, open, end, after), false, after - at);
            at = after;
            continue;
          }
          if (name == "fabs") name = "abs";
          if (name == "nran") name = "gaussian";  // cpfg's nran(mean, deviation)
          if (name == "bran" || name == "biran")
            fail(at, stop,
                 "cpfg's " + name + (name == "bran" ? "(a, b), a random number of the beta distribution" :
                                                      "(n, p), a random number of the binomial distribution") +
                     ": the cell language draws uniform, normal and Bernoulli numbers only");
        }
      }
      if (python) {
        const std::string_view head = std::string_view(name).substr(0, name.find('.'));
        if (auto object = editorObjects.find(head); object != editorObjects.end() && !bound_.count(head))
          fail(at, stop,
               shown(std::string(head)) + ", a " + object->second +
                   " of L-Py's editor (its INITIALISATION section), which the converter does not translate");
        if (name.rfind("math.", 0) == 0) name = name.substr(5);  // math.sqrt is sqrt
        if (name.rfind("random.", 0) == 0) name = name.substr(7);  // random.uniform is uniform
        uint32_t next = stop;
        while (next < end && isSpace(text_[next])) ++next;
        if (next < end && text_[next] == '(') {
          // Python's functions as the cell language names them; random ones draw from
          // ontogen's seeded streams (docs/LANGUAGE.md 4.12).
          static constexpr std::pair<std::string_view, std::string_view> kCalls[] = {
              {"random", "uniform"}, {"gauss", "gaussian"},  {"normalvariate", "gaussian"},
              {"normal", "gaussian"}, {"int", "trunc"},      {"radians", "rad"},
              {"degrees", "deg"},     {"fabs", "abs"},
          };
          for (const auto& [pythonName, cell] : kCalls)
            if (name == pythonName) name = std::string(cell);
          if (name == "round") {
            uint32_t after = next;
            const std::string value = pythonRound(at, next, end, after);
            emit(value, false, after - at);
            at = after;
            continue;
          }
          if (name == "getIterationNb") {
            uint32_t close = next + 1;
            while (close < end && isSpace(text_[close])) ++close;
            if (close == end || text_[close] != ')') code(at, close, "getIterationNb with arguments");
            if (inHomomorphism)
              fail(at, close + 1,
                   "getIterationNb() in the interpretation, which L-Py reads after the last step: the converter does "
                   "not write its value there");
            const bool single = iterationNumber.find(' ') == std::string::npos;
            emit(single ? iterationNumber : "(" + iterationNumber + ")", false, close + 1 - at);
            at = close + 1;
            continue;
          }
          if (name == "float") {  // float(x) is x
            at = stop;
            continue;
          }
          if (name == "randint" || name == "choice" || name == "randrange" || name == "shuffle" ||
              name == "sample" || name == "len" || name == "range" || name == "str")
            code(at, stop, "Python's " + shown(name));
        }
        if (name.find('.') != std::string::npos) code(at, stop, "the attribute " + shown(name));
        if (name == "and" || name == "or") {
          closeNots();
          name = name == "and" ? "&&" : "||";
        } else if (name == "not") {
          emit("!", false, 3);
          tokens.push_back({"(", at, at + 3, true});
          out += "(";
          notDepths.push_back(depth);
          at = stop;
          continue;
        } else if (name == "True")
          name = "1";
        else if (name == "False")
          name = "0";
        else if (name == "lambda" || name == "for" || name == "in" || name == "is")
          code(at, stop, "Python's " + shown(name));
      }
      {
        uint32_t next = stop;
        while (next < end && isSpace(text_[next])) ++next;
        if (next == end || text_[next] != '(') name = cellName(name);
      }
      emit(name, false, stop - at);
      at = stop;
      continue;
    }
    auto two = [&](std::string_view op) { return text_.compare(at, 2, op) == 0 && at + 1 < end; };
    if (two("**")) {
      if (!python) fail(at, at + 2, "'**' is no operator of cpfg's expressions", false);
      emit("^");
      at += 2;
    } else if (two("//")) {
      if (!python) code(at, at + 2, "'//'");
      emit("//");
      at += 2;
    } else if (two("<>")) {  // cpfg's and Python 2's other spelling of !=
      emit("!=", false, 2);
      at += 2;
    } else if (two("==") || two("!=") || two("<=") || two(">=") || two("&&") || two("||")) {
      emit(text_.substr(at, 2));
      at += 2;
    } else if (c == '=') {
      code(at, at + 1, "an assignment");
    } else if (c == '(') {
      // A call keeps its '(' on the name: f(x).
      const bool call = !out.empty() && (isNameChar(out.back()));
      // A conditional inside parentheses, (c ? a : b) or f(a if c else b, 2): each
      // argument read as an expression of its own, where conditionals are split off.
      if (depth >= kMaxConvertParentheses)
        fail(at, at + 1,
             "nested too deeply (more than " + std::to_string(kMaxConvertParentheses) + " parentheses)", false);
      int inner = 0;
      uint32_t close = at;
      if (mayNestConditionals)
        for (; close < end; ++close) {
          if (text_[close] == '(') ++inner;
          if (text_[close] == ')' && --inner == 0) break;
        }
      bool conditional = false;
      if (mayNestConditionals && close < end) {
        if (!python) {
          conditional = find(at + 1, close, "?") < close;
        } else {
          for (uint32_t k = find(at + 1, close, "if"); k < close && !conditional; k = find(k + 1, close, "if"))
            conditional = !isNameChar(text_[k - 1]) && k + 2 < close && !isNameChar(text_[k + 2]);
        }
      }
      if (conditional) {
        const Nested nested(*this, at, close + 1);
        std::string group = "(";
        for (uint32_t from = at + 1; from <= close;) {
          const uint32_t comma = find(from, close, ",");
          group += (from > at + 1 ? ", " : "") + expression(from, comma);
          from = comma + 1;
        }
        emit(group + ")", call, close + 1 - at);
        at = close + 1;
        continue;
      }
      emit("(", call);
      ++depth;
      ++at;
    } else if (c == ')' || c == ',') {
      closeNots();
      if (c == ')') --depth;
      emit(text_.substr(at, 1), true);
      ++at;
    } else if (std::string_view("+-*/%<>!^").find(c) != std::string_view::npos) {
      if (c == '^' && python) code(at, at + 1, "Python's '^' (exclusive or; a power is '**')");
      // Python 2 divides truly where an operand is a float: a float literal beside the '/'.
      auto floatLiteral = [](std::string_view token) {
        return !token.empty() && (std::isdigit(static_cast<unsigned char>(token[0])) || token[0] == '.') &&
               token.find_first_of(".eE") != std::string_view::npos;
      };
      auto literalAfter = [&] {
        uint32_t k = at + 1;
        while (k < end && isSpace(text_[k])) ++k;
        uint32_t stop = k;
        while (stop < end && (isNameChar(text_[stop]) || text_[stop] == '.')) ++stop;
        return floatLiteral(text_.substr(k, stop - k));
      };
      if (c == '/' && python && python2 && !futureDivision &&
          !(!tokens.empty() && floatLiteral(tokens.back().text)) && !literalAfter()) {
        uint32_t line = 1;
        for (uint32_t k = 0; k < *python2; ++k) line += text_[k] == '\n';
        fail(at, at + 1,
             "'/' in a file of Python 2 (line " + std::to_string(line) +
                 "), where it floors between integers, which the converter cannot tell from other numbers: "
                 "write '//' for a floor, or a float operand beside it (x / 2.0, x * 1.0 / y) for a quotient");
      }
      emit(text_.substr(at, 1));
      ++at;
    } else if (c == '?' || c == ':') {
      fail(at, at + 1, "unexpected " + shown(text_.substr(at, 1)) + " in an expression", false);
    } else if (c == '{' || c == '}' || c == ';') {
      code(at, at + 1, "a block or statement " + shown(text_.substr(at, 1)));
    } else if (c == '[' || c == ']' || c == '"' || c == '\'') {
      code(at, at + 1, python ? "a list, index or string" : "an array or string");
    } else {
      fail(at, at + 1, "unexpected " + shown(text_.substr(at, 1)) + " in an expression", false);
    }
  }
  depth = 0;
  closeNots();
  if (out.empty()) fail(begin, end, "expected an expression", false);
  if (raw) {
    *raw = std::move(tokens);
    return out;
  }
  if (std::optional<std::string> rewritten = foreignOperators(*this, tokens, dialect_, truth)) return *rewritten;
  return out;
}

// cpfg's `a[i]` of an array of a Define: block: C casts the index to int (towards 0).
// Python's `a[i]` of a list of constants: an index from the end is negative. The index
// is written once per element but the last, so it may not draw.
std::string ForeignSyntax::arrayElement(const std::vector<std::string>& elements, uint32_t at, uint32_t open,
                                        uint32_t end, uint32_t& stop) const {
  int depth = 0;
  uint32_t close = open;
  for (; close < end; ++close) {
    if (text_[close] == '[') ++depth;
    if (text_[close] == ']' && --depth == 0) break;
  }
  if (close == end) fail(open, open + 1, "a '[' without its ']'", false);
  if (close + 1 < end && text_[close + 1] == '[')
    fail(at, close + 2, "an array of two dimensions: C code, which ontogen convert does not translate");
  const std::string index = expression(open + 1, close);
  if (drawsRandom(index) && elements.size() > 1)
    fail(open + 1, close,
         "an index that draws a random number: the converter writes it once per element, so it would be drawn "
         "anew each time");
  stop = close + 1;
  std::string chain = elements.back();
  const bool python = dialect_ == Dialect::LPy;
  const std::string read = python ? "(" + index + ")" : "trunc(" + index + ")";
  for (size_t k = elements.size() - 1; k-- > 0;) {
    std::string test = read + " == " + std::to_string(k);
    if (python) test += " || " + read + " == " + std::to_string(static_cast<long>(k) - static_cast<long>(elements.size()));
    chain = "if(" + test + ", " + elements[k] + ", " + chain + ")";
  }
  return elements.size() > 1 ? chain : "(" + chain + ")";
}

}  // namespace ontogen::convert
