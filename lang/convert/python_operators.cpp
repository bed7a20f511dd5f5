#include "lang/convert/python_operators.h"

#include <cctype>
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

  std::string all() {
    std::string text = disjunction();
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

  std::string disjunction() {
    const Deeper deeper(depth_);
    std::string text = conjunction();
    while (next("||")) {
      ++at_;
      text += " || " + conjunction();
    }
    return text;
  }
  std::string conjunction() {
    std::string text = comparison();
    while (next("&&")) {
      ++at_;
      text += " && " + comparison();
    }
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
    }
    return text;
  }
  std::string cOrder() {
    std::string text = sum();
    while (next("<") || next("<=") || next(">") || next(">=")) {
      const std::string op = take().text;
      text += " " + op + " " + sum();
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
      syntax_.fail(op.begin, op.end,
                   "this expression grows past " + std::to_string(kMaxBytes >> 10) +
                       " KiB as Python's '%' and chained comparisons are written out",
                   false);
  }

  std::string sum() {
    std::string text = term();
    while (next("+") || next("-")) {
      const std::string op = take().text;
      text += " " + op + " " + term();
    }
    return text;
  }
  std::string term() {
    std::string text = operand();
    while (next("*") || next("/") || next("%") || next("//")) {
      const ExpressionToken& op = take();
      const std::string right = operand();
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
      std::string operand = unary();
      return op + (operand[0] == '-' || operand[0] == '+' ? " " : "") + operand;
    }
    return cpfg_ ? primary() : power();
  }
  std::string power() {
    std::string base = primary();
    if (next("^")) {
      ++at_;
      base += " ^ " + unary();
    }
    return base;
  }
  std::string primary() {
    const ExpressionToken& token = take();
    const char c = token.text.empty() ? '\0' : token.text[0];
    if (c == '(' && token.text.size() > 1) return token.text;  // read on its own: an inlined value, conditionals
    if (c == '(') {
      std::string inner = disjunction();
      if (!next(")")) throw Unreadable{};
      ++at_;
      return "(" + inner + ")";
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
};

}  // namespace

std::optional<std::string> foreignOperators(const ForeignSyntax& syntax, const std::vector<ExpressionToken>& tokens,
                                            Dialect dialect) {
  Reader reader(syntax, tokens, dialect);
  try {
    std::string text = reader.all();
    if (reader.changed()) return text;
    return std::nullopt;
  } catch (const Unreadable&) {
    for (const ExpressionToken& token : tokens)
      if (token.text == "%" || token.text == "//" || (dialect == Dialect::Cpfg && token.text == "^"))
        syntax.fail(token.begin, token.end,
                    std::string(dialect == Dialect::Cpfg ? "cpfg" : "Python") + "'s '" + token.text +
                        "' in an expression the converter cannot read around it (malformed, or nested more than " + std::to_string(kMaxConvertParentheses) + " deep)",
                    false);
    return std::nullopt;
  }
}

}  // namespace ontogen::convert
