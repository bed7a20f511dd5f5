#include "lang/convert/python_operators.h"

#include <cctype>
#include <cstdlib>
#include <string_view>

#include "lang/convert/foreign_syntax.h"

namespace ontogen::convert {

namespace {

bool isComparison(std::string_view op) {
  return op == "<" || op == ">" || op == "<=" || op == ">=" || op == "==" || op == "!=";
}

// Whether text calls a function that draws a random number.
bool drawsRandom(std::string_view text) {
  for (std::string_view f : {"uniform(", "gaussian(", "ran(", "bernoulli("})
    for (size_t at = text.find(f); at != std::string_view::npos; at = text.find(f, at + 1))
      if (at == 0 || !(std::isalnum(static_cast<unsigned char>(text[at - 1])) || text[at - 1] == '_')) return true;
  return false;
}

// Whether text is a number other than 0.
bool nonzeroNumber(const std::string& text) {
  char* stop = nullptr;
  const double value = std::strtod(text.c_str(), &stop);
  return !text.empty() && stop == text.c_str() + text.size() && value != 0;
}

// A failed read: the expression is left to the compiler unless it holds an operator this
// file must rewrite.
struct Unreadable {};

// Recursive descent with Python's precedences (loosest first): or, and, not, comparisons
// (one level, chained), + -, * / // %, unary - + !, ** (written ^); or cpfg's: ||, &&,
// == !=, < <= > >=, + -, * / %, ^ (left-associative), unary - + !.
class Reader {
 public:
  Reader(const ForeignSyntax& syntax, const std::vector<ExpressionToken>& tokens, Dialect dialect)
      : syntax_(syntax), tokens_(tokens), cpfg_(dialect == Dialect::Cpfg) {}

  std::string all(bool truth) {
    std::string text = disjunction(truth);
    if (at_ != tokens_.size()) throw Unreadable{};
    return text;
  }
  bool changed() const { return changed_; }

 private:
  bool next(std::string_view text) const { return at_ < tokens_.size() && tokens_[at_].text == text; }
  const ExpressionToken& take() {
    if (at_ >= tokens_.size()) throw Unreadable{};
    return tokens_[at_++];
  }

  // Parentheses and unary operators read within one another; deeper is left to the
  // compiler, which refuses it at its place.
  struct Deeper {
    explicit Deeper(int& depth) : depth_(depth) {
      if (++depth_ > kMaxConvertParentheses + 8) {
        --depth_;
        throw Unreadable{};
      }
    }
    ~Deeper() { --depth_; }
    Deeper(const Deeper&) = delete;
    Deeper& operator=(const Deeper&) = delete;
    int& depth_;
  };

  // Python's `a or b` is a when a is true, else b; `a and b` is a when a is false (0),
  // else b: an operand, where the cell language's || and && give 0 or 1. They agree where
  // the operands are 0 or 1 (comparisons, not, True, False) or where only the truth of
  // the whole is read (a condition); elsewhere they become conditionals that choose the
  // operand, folded from the right so that each operand is written at most twice.
  std::string disjunction(bool truth = false) {
    const Deeper deeper(depth_);
    std::vector<std::pair<std::string, bool>> operands;
    std::vector<const ExpressionToken*> ops;
    operands.emplace_back(conjunction(truth), boolean_);
    while (next("||")) {
      ops.push_back(&take());
      operands.emplace_back(conjunction(truth), boolean_);
    }
    return logical(operands, ops, truth, true);
  }
  std::string conjunction(bool truth) {
    std::vector<std::pair<std::string, bool>> operands;
    std::vector<const ExpressionToken*> ops;
    operands.emplace_back(truthOperand(truth), boolean_);
    while (next("&&")) {
      ops.push_back(&take());
      operands.emplace_back(truthOperand(truth), boolean_);
    }
    return logical(operands, ops, truth, false);
  }
  // An operand of `and` or `or` whose truth alone is read: a parenthesis that is the
  // whole operand is read for its truth as well, (a or b) and c as (a || b) && c.
  std::string truthOperand(bool truth) {
    if (truth && next("(") && !tokens_[at_].glued) {
      size_t close = at_;
      for (int depth = 0; close < tokens_.size(); ++close) {
        if (tokens_[close].text == "(") ++depth;
        if (tokens_[close].text == ")" && --depth == 0) break;
      }
      if (close + 1 == tokens_.size() ||
          (close + 1 < tokens_.size() &&
           (tokens_[close + 1].text == "&&" || tokens_[close + 1].text == "||" || tokens_[close + 1].text == ")"))) {
        const Deeper deeper(depth_);
        ++at_;
        std::string inner = disjunction(true);
        if (!next(")")) throw Unreadable{};
        ++at_;
        return "(" + inner + ")";
      }
    }
    return comparison();
  }
  std::string logical(const std::vector<std::pair<std::string, bool>>& operands,
                      const std::vector<const ExpressionToken*>& ops, bool truth, bool disjunction) {
    const std::string_view op = disjunction ? " || " : " && ";
    if (operands.size() == 1) return operands[0].first;
    bool allBoolean = true;
    for (const auto& operand : operands) allBoolean = allBoolean && operand.second;
    if (cpfg_ || truth || allBoolean) {  // C's || and && give 0 or 1, as the cell language's
      std::string text = operands[0].first;
      for (size_t k = 1; k < operands.size(); ++k) text += std::string(op) + operands[k].first;
      boolean_ = true;
      return text;
    }
    std::string text = operands.back().first;
    bool boolean = operands.back().second;
    for (size_t k = operands.size() - 1; k-- > 0;) {
      const auto& [left, leftBoolean] = operands[k];
      if (disjunction && leftBoolean && boolean) {
        text = left + " || " + text;
      } else if (disjunction && leftBoolean) {
        text = "if(" + left + ", 1, " + text + ")";  // a true comparison is 1
        boolean = false;
      } else if (disjunction) {
        if (drawsRandom(left))
          syntax_.fail(ops[k]->begin, ops[k]->end,
                       "Python's 'or' of a left operand that draws a random number, used as a value: it is the "
                       "operand itself when true, which writes it twice, and the cell language would draw it anew; "
                       "use a local holding the draw");
        text = "if(" + left + ", " + left + ", " + text + ")";
        boolean = false;
      } else if (boolean) {
        text = left + " && " + text;  // a false left operand is 0, as && gives
      } else {
        text = "if(" + left + ", " + text + ", 0)";
        boolean = false;
      }
      bounded(text, *ops[k]);
    }
    changed_ = changed_ || !boolean;
    boolean_ = boolean;
    return text;
  }
  std::string comparison() {
    if (cpfg_) return cComparison();
    std::string left = sum();
    if (at_ >= tokens_.size() || !isComparison(tokens_[at_].text)) return left;
    std::string chain;
    size_t links = 0;
    while (at_ < tokens_.size() && isComparison(tokens_[at_].text)) {
      const ExpressionToken& op = take();
      std::string right = sum();
      // a < b < c is a < b and b < c: b is written twice.
      if (links > 0 && drawsRandom(left))
        syntax_.fail(op.begin, op.end,
                     "a chained comparison whose middle operand draws a random number: the cell language would "
                     "draw it twice; compare a local holding the draw");
      chain += (links ? " && " : "") + left + " " + op.text + " " + right;
      bounded(chain, op);
      left = std::move(right);
      ++links;
    }
    boolean_ = true;
    if (links == 1) return chain;
    changed_ = true;
    return "(" + chain + ")";
  }
  // C's comparisons: equality binds looser than order, each left-associative, as the
  // cell language reads them.
  std::string cComparison() {
    std::string text = cOrder();
    while (next("==") || next("!=")) {
      const std::string op = take().text;
      text += " " + op + " " + cOrder();
      boolean_ = true;
    }
    return text;
  }
  std::string cOrder() {
    std::string text = sum();
    while (next("<") || next("<=") || next(">") || next(">=")) {
      const std::string op = take().text;
      text += " " + op + " " + sum();
      boolean_ = true;
    }
    return text;
  }
  // cpfg's ^ is left-associative and binds looser than the unary operators.
  std::string cPower() {
    std::string text = unary();
    bool chained = false;
    while (next("^")) {
      ++at_;
      const std::string right = unary();
      boolean_ = false;
      const bool signed_ = text[0] == '-' || text[0] == '+' || text[0] == '!';
      if (signed_ || chained) {
        text = "(" + text + ")";
        changed_ = true;
      }
      text += " ^ " + right;
      chained = true;
    }
    return text;
  }
  std::string operand() { return cpfg_ ? cPower() : unary(); }

  // The operands the rewrite writes again make text grow; no model's expression comes
  // near the bound, and past it each step would copy more (a file of 1 MiB could take
  // minutes).
  void bounded(const std::string& text, const ExpressionToken& op) const {
    constexpr size_t kMaxBytes = size_t{256} << 10;
    if (text.size() > kMaxBytes)
      syntax_.fail(
          op.begin, op.end,
          "this expression grows past " + std::to_string(kMaxBytes >> 10) + " KiB as its operators are written out",
          false);
  }

  std::string sum() {
    std::string text = term();
    while (next("+") || next("-")) {
      const std::string op = take().text;
      text += " " + op + " " + term();
      boolean_ = false;
    }
    return text;
  }
  std::string term() {
    std::string text = operand();
    while (next("*") || next("/") || next("%") || next("//")) {
      const ExpressionToken& op = take();
      const std::string right = operand();
      boolean_ = false;
      if (op.text == "%" && cpfg_) {
        // cpfg computes (int)x % (int)y: C's remainder has the sign of x, as fmod's.
        text = "fmod(trunc(" + text + "), trunc(" + right + "))";
        changed_ = true;
      } else if (op.text == "%") {
        // Python's remainder has the sign of the divisor: fmod(fmod(x, y) + y, y).
        if (drawsRandom(right))
          syntax_.fail(op.begin, op.end,
                       "Python's '%' of a divisor that draws a random number: its remainder, which has the sign of "
                       "the divisor, writes the divisor three times and the cell language would draw it anew each "
                       "time; use a local holding the draw");
        text = "fmod(fmod(" + text + ", " + right + ") + " + right + ", " + right + ")";
        changed_ = true;
        bounded(text, op);
      } else if (op.text == "/" && cpfg_ && !nonzeroNumber(right)) {
        // cpfg divides by 1 where the divisor is 0 (generate.c, with a warning); the cell
        // language's quotient would not be finite.
        if (drawsRandom(right))
          syntax_.fail(op.begin, op.end,
                       "cpfg's '/' of a divisor that draws a random number: cpfg divides by 1 where the divisor is "
                       "0, which writes the divisor twice, and the cell language would draw it anew; use a "
                       "variable holding the draw");
        text += " / if(" + right + " == 0, 1, " + right + ")";
        changed_ = true;
        bounded(text, op);
      } else if (op.text == "//") {
        text = "floor(" + text + " / " + right + ")";
        changed_ = true;
      } else {
        text += " " + op.text + " " + right;
      }
    }
    return text;
  }
  std::string unary() {
    if (next("-") || next("+") || next("!")) {
      const Deeper deeper(depth_);
      const std::string op = take().text;
      // Python's not reads the truth of its operand: not (a or b) is !(a || b).
      std::string operand;
      if (op == "!" && next("(") && !tokens_[at_].glued) {
        ++at_;
        operand = "(" + disjunction(true) + ")";
        if (!next(")")) throw Unreadable{};
        ++at_;
      } else {
        operand = unary();
      }
      boolean_ = op == "!";
      return op + (operand[0] == '-' || operand[0] == '+' ? " " : "") + operand;
    }
    return cpfg_ ? primary() : power();
  }
  std::string power() {
    std::string base = primary();
    if (next("^")) {
      ++at_;
      base += " ^ " + unary();
      boolean_ = false;
    }
    return base;
  }
  std::string primary() {
    const ExpressionToken& token = take();
    const char c = token.text.empty() ? '\0' : token.text[0];
    boolean_ = token.text == "0" || token.text == "1";         // True and False are written 1 and 0
    if (c == '(' && token.text.size() > 1) return token.text;  // read on its own: an inlined value, conditionals
    if (c == '(') {
      std::string inner = disjunction();
      if (!next(")")) throw Unreadable{};
      ++at_;
      return "(" + inner + ")";  // as boolean as its inside
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return token.text;
    if (!(std::isalpha(static_cast<unsigned char>(c)) || c == '_')) throw Unreadable{};
    // A call whose arguments were read on their own (they hold conditionals).
    if (at_ < tokens_.size() && tokens_[at_].glued && tokens_[at_].text.size() > 1 && tokens_[at_].text[0] == '(')
      return token.text + tokens_[at_++].text;
    if (!(next("(") && tokens_[at_].glued)) return token.text;
    ++at_;
    std::string call = token.text + "(";
    if (next(")")) {
      ++at_;
      return call + ")";
    }
    for (;;) {
      call += disjunction();
      boolean_ = false;
      if (next(")")) break;
      if (!next(",")) throw Unreadable{};
      ++at_;
      call += ", ";
    }
    ++at_;
    return call + ")";
  }

  const ForeignSyntax& syntax_;
  const std::vector<ExpressionToken>& tokens_;
  const bool cpfg_;
  size_t at_ = 0;
  int depth_ = 0;
  bool changed_ = false;
  bool boolean_ = false;  // the operand read last is 0 or 1 whatever its operands' values
};

}  // namespace

std::optional<std::string> foreignOperators(const ForeignSyntax& syntax, const std::vector<ExpressionToken>& tokens,
                                            Dialect dialect, bool truth) {
  Reader reader(syntax, tokens, dialect);
  try {
    std::string text = reader.all(truth);
    if (reader.changed()) return text;
    return std::nullopt;
  } catch (const Unreadable&) {
    for (const ExpressionToken& token : tokens)
      if (token.text == "%" || token.text == "//" || (dialect == Dialect::Cpfg && token.text == "^") ||
          (dialect == Dialect::LPy && !truth && (token.text == "||" || token.text == "&&")))
        syntax.fail(token.begin, token.end,
                    std::string(dialect == Dialect::Cpfg ? "cpfg" : "Python") + "'s '" +
                        (token.text == "||"   ? "or"
                         : token.text == "&&" ? "and"
                                              : token.text) +
                        "' in an expression the converter cannot read around it (malformed, or nested more than " +
                        std::to_string(kMaxConvertParentheses) + " deep)",
                    false);
    return std::nullopt;
  }
}

}  // namespace ontogen::convert
