#include "lang/convert/python_body.h"

#include <cctype>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace ontogen::convert {

namespace {

bool isNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}
bool isSpace(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}

// One statement of a body.
struct Stmt;
using Block = std::vector<std::unique_ptr<Stmt>>;

struct Branch {
  uint32_t condBegin = 0, condEnd = 0;  // empty: `else`
  Block body;
};

enum class StmtKind { Produce, NProduce, Assign, If, Pass, Return };

struct Stmt {
  StmtKind kind = StmtKind::Pass;
  uint32_t begin = 0, end = 0;          // the whole statement's line
  uint32_t argBegin = 0, argEnd = 0;    // Produce, NProduce: the word; Assign: the value
  std::string name;                     // Assign: the local
  char op = '=';                        // Assign: '=', or '+' '-' '*' '/' of an augmented one
  std::vector<Branch> branches;         // If
};

// A local's value as cell-language text, and whether it holds a random draw.
struct Value {
  std::string text;
  bool random = false;
};

// One way through a body being followed.
struct Way {
  std::vector<std::string> conditions;
  std::vector<std::string> weights;
  std::vector<ModuleText> produced;  // what `nproduce` gave so far
  std::map<std::string, Value> locals;
  std::map<std::string, int> randomUses;
};

bool holdsRandom(std::string_view text) {
  for (std::string_view f : {"uniform(", "gaussian(", "ran(", "bernoulli("}) {
    for (size_t at = text.find(f); at != std::string_view::npos; at = text.find(f, at + 1))
      if (at == 0 || !isNameChar(text[at - 1])) return true;
  }
  return false;
}

// Text without the spaces at its ends and without parentheses that enclose all of it.
std::string_view bare(std::string_view text) {
  for (;;) {
    while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
    while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
    if (text.size() < 2 || text.front() != '(' || text.back() != ')') return text;
    int depth = 0;
    for (size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '(') ++depth;
      if (text[i] == ')' && --depth == 0 && i + 1 < text.size()) return text;
    }
    text = text.substr(1, text.size() - 2);
  }
}

bool isUniformDraw(std::string_view text) {
  const std::string_view b = bare(text);
  return b == "uniform()" || b == "uniform(1)" || b == "uniform(0, 1)";
}

// `u < p`, `u <= p`, `p > u`, `p >= u` with u a uniform draw in [0, 1): p, the chance
// the test holds; `u > p`, `p < u`: 1 - p.
std::optional<std::string> chanceOf(std::string_view condition) {
  const std::string_view text = bare(condition);
  int depth = 0;
  size_t at = std::string_view::npos, size = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if (depth != 0) continue;
    if ((c == '&' || c == '|') && i + 1 < text.size() && text[i + 1] == c) return std::nullopt;
    if (c == '<' || c == '>') {
      if (at != std::string_view::npos) return std::nullopt;
      at = i;
      size = i + 1 < text.size() && text[i + 1] == '=' ? 2 : 1;
    }
  }
  if (at == std::string_view::npos) return std::nullopt;
  const std::string_view left = text.substr(0, at), right = text.substr(at + size);
  const bool less = text[at] == '<';
  std::string_view chance;
  bool complement = false;  // u > p holds with chance 1 - p
  if (isUniformDraw(left) && !holdsRandom(right)) {
    chance = right;
    complement = !less;
  } else if (isUniformDraw(right) && !holdsRandom(left)) {
    chance = left;
    complement = less;
  } else {
    return std::nullopt;
  }
  chance = bare(chance);
  if (complement) return "(1 - clamp(" + std::string(chance) + ", 0, 1))";
  // A chance written as a number from 0 to 1 stands as it is.
  char* stop = nullptr;
  const std::string number(chance);
  const double value = std::strtod(number.c_str(), &stop);
  if (!number.empty() && stop == number.c_str() + number.size() && value >= 0 && value <= 1) return number;
  return "clamp(" + number + ", 0, 1)";
}

class BodyTranslator {
 public:
  BodyTranslator(const ForeignSyntax& syntax, std::string_view text, const Statement& head)
      : syntax_(syntax), text_(text), head_(head) {}

  std::vector<Statement> run(const std::vector<BodyLine>& lines) {
    size_t at = 0;
    Block body = block(lines, at, lines.empty() ? 0 : lines.front().indent);
    if (at < lines.size()) syntax_.fail(lines[at].begin, lines[at].end, "unexpected indentation", false);
    std::vector<Frame> frames{{&body, 0}};
    follow(frames, Way{});
    return std::move(out_);
  }

 private:
  struct Frame {
    const Block* block;
    size_t next;
  };

  bool startsWith(uint32_t begin, uint32_t end, std::string_view word) const {
    if (end - begin < word.size() || text_.compare(begin, word.size(), word) != 0) return false;
    return begin + word.size() == end || !isNameChar(text_[begin + word.size()]);
  }

  [[noreturn]] void python(uint32_t begin, uint32_t end, const std::string& what) const {
    syntax_.fail(begin, end,
                 what +
                     ": Python which ontogen convert does not translate (it reads production bodies of if/elif/"
                     "else, produce, nproduce, assignments to locals, arithmetic, math and random functions)");
  }

  // The statements of lines at `indent`, from `at`.
  Block block(const std::vector<BodyLine>& lines, size_t& at, int indent) {
    Block result;
    while (at < lines.size() && lines[at].indent >= indent) {
      if (lines[at].indent > indent) syntax_.fail(lines[at].begin, lines[at].end, "unexpected indentation", false);
      const BodyLine line = lines[at++];
      uint32_t b = line.begin, e = line.end;
      syntax_.trim(b, e);
      if (startsWith(b, e, "elif") || startsWith(b, e, "else")) {
        if (result.empty() || result.back()->kind != StmtKind::If || !result.back()->branches.back().condEnd)
          syntax_.fail(b, e, "'elif' or 'else' without its 'if'", false);
        Branch branch;
        if (startsWith(b, e, "elif")) compound(b + 4, e, branch, lines, at, indent);
        else compound(b + 4, e, branch, lines, at, indent, true);
        result.back()->branches.push_back(std::move(branch));
        continue;
      }
      auto stmt = std::make_unique<Stmt>();
      stmt->begin = b;
      stmt->end = e;
      if (startsWith(b, e, "if")) {
        stmt->kind = StmtKind::If;
        Branch branch;
        compound(b + 2, e, branch, lines, at, indent);
        stmt->branches.push_back(std::move(branch));
      } else {
        simple(*stmt, b, e);
      }
      result.push_back(std::move(stmt));
    }
    return result;
  }

  // `COND: statement` or `COND:` and an indented block; `otherwise`: an `else`.
  void compound(uint32_t b, uint32_t e, Branch& branch, const std::vector<BodyLine>& lines, size_t& at, int indent,
                bool otherwise = false) {
    const uint32_t colon = syntax_.find(b, e, ":");
    if (colon == e) syntax_.fail(b, e, "expected ':' after the test", false);
    if (!otherwise) {
      uint32_t cb = b, ce = colon;
      syntax_.trim(cb, ce);
      if (cb == ce) syntax_.fail(b, colon + 1, "expected a test before ':'", false);
      branch.condBegin = cb;
      branch.condEnd = ce;
    } else {
      uint32_t cb = b, ce = colon;
      syntax_.trim(cb, ce);
      if (cb != ce) syntax_.fail(cb, ce, "expected ':' after 'else'", false);
    }
    uint32_t sb = colon + 1, se = e;
    syntax_.trim(sb, se);
    if (sb < se) {
      auto stmt = std::make_unique<Stmt>();
      stmt->begin = sb;
      stmt->end = se;
      if (startsWith(sb, se, "if")) python(sb, se, "an 'if' on the line of a test");
      simple(*stmt, sb, se);
      branch.body.push_back(std::move(stmt));
      return;
    }
    if (at >= lines.size() || lines[at].indent <= indent) syntax_.fail(b, e, "a test without a body", false);
    branch.body = block(lines, at, lines[at].indent);
  }

  void simple(Stmt& stmt, uint32_t b, uint32_t e) {
    auto leading = [&](std::string_view keyword, StmtKind kind) {
      if (!startsWith(b, e, keyword)) return false;
      stmt.kind = kind;
      stmt.argBegin = b + static_cast<uint32_t>(keyword.size());
      stmt.argEnd = e;
      syntax_.trim(stmt.argBegin, stmt.argEnd);
      // produce (A B C): a word in parentheses, to write it over several lines.
      if (stmt.argEnd - stmt.argBegin >= 2 && text_[stmt.argBegin] == '(' &&
          bare(text_.substr(stmt.argBegin, stmt.argEnd - stmt.argBegin)).size() < stmt.argEnd - stmt.argBegin) {
        ++stmt.argBegin;
        --stmt.argEnd;
      }
      return true;
    };
    if (leading("produce", StmtKind::Produce) || leading("nproduce", StmtKind::NProduce)) return;
    // print(...) writes to the terminal, which changes no word.
    if (startsWith(b, e, "print")) {
      stmt.kind = StmtKind::Pass;
      return;
    }
    if (startsWith(b, e, "pass")) {
      if (e != b + 4) python(b, e, "this line");
      stmt.kind = StmtKind::Pass;
      return;
    }
    if (startsWith(b, e, "return")) {
      uint32_t rb = b + 6, re = e;
      syntax_.trim(rb, re);
      if (rb != re && text_.substr(rb, re - rb) != "None") python(b, e, "a 'return' of a value");
      stmt.kind = StmtKind::Return;
      return;
    }
    // NAME = EXPR, NAME += EXPR ...
    uint32_t at = b;
    while (at < e && isNameChar(text_[at])) ++at;
    if (at > b && !std::isdigit(static_cast<unsigned char>(text_[b]))) {
      uint32_t op = at;
      while (op < e && isSpace(text_[op])) ++op;
      char kind = 0;
      if (op < e && text_[op] == '=' && (op + 1 >= e || text_[op + 1] != '='))
        kind = '=';
      else if (op + 1 < e && text_[op + 1] == '=' && std::string_view("+-*/").find(text_[op]) != std::string_view::npos &&
               !(text_[op] == '/' && op > 0 && text_[op - 1] == '/'))
        kind = text_[op];
      if (kind) {
        stmt.kind = StmtKind::Assign;
        stmt.name = std::string(text_.substr(b, at - b));
        stmt.op = kind;
        stmt.argBegin = op + (kind == '=' ? 1 : 2);
        stmt.argEnd = e;
        return;
      }
    }
    uint32_t stop = b;
    while (stop < e && isNameChar(text_[stop])) ++stop;
    python(b, e, stop > b ? "'" + std::string(text_.substr(b, stop - b)) + "'" : std::string("this line"));
  }

  // A cell-language expression with the way's locals put in.
  std::string substitute(const std::string& expr, Way& way, const Stmt& where) const {
    if (auto whole = way.locals.find(expr); whole != way.locals.end()) {
      // An argument that is a local alone takes its value without parentheses.
      std::string value = substitute(" " + expr, way, where);
      return std::string(bare(value));
    }
    std::string result;
    for (size_t i = 0; i < expr.size();) {
      const char c = expr[i];
      const bool starts = (std::isalpha(static_cast<unsigned char>(c)) || c == '_') &&
                          (i == 0 || !(isNameChar(expr[i - 1]) || expr[i - 1] == '.'));
      if (!starts) {
        result += c;
        ++i;
        continue;
      }
      size_t stop = i;
      while (stop < expr.size() && isNameChar(expr[stop])) ++stop;
      const std::string name = expr.substr(i, stop - i);
      const bool call = stop < expr.size() && expr[stop] == '(';
      auto local = way.locals.find(name);
      if (local == way.locals.end() || call) {
        result += name;
      } else {
        if (local->second.random && ++way.randomUses[name] > 1)
          syntax_.fail(where.begin, where.end,
                       "the random value '" + name +
                           "' used a second time: the cell language draws anew where it is written, so the values "
                           "would differ");
        result += local->second.text;
      }
      i = stop;
    }
    return result;
  }

  std::vector<ModuleText> word(const Stmt& stmt, Way& way) const {
    std::vector<ModuleText> modules;
    if (stmt.argBegin < stmt.argEnd && !(stmt.argEnd == stmt.argBegin + 1 && text_[stmt.argBegin] == '*'))
      modules = syntax_.modules(stmt.argBegin, stmt.argEnd, false);
    for (ModuleText& module : modules)
      for (std::string& arg : module.args) arg = substitute(arg, way, stmt);
    return modules;
  }

  void emit(const Way& way, std::vector<ModuleText> successors, bool keeps) {
    if (out_.size() >= kMaxBodyProductions)
      syntax_.fail(head_.origin.begin, head_.origin.end,
                   "this body has more than " + std::to_string(kMaxBodyProductions) +
                       " ways through its tests; write it as several productions",
                   false);
    Statement s = head_;
    std::string condition;
    for (const std::string& c : way.conditions) condition += (condition.empty() ? "" : " && ") + c;
    if (!head_.condition.empty()) condition = condition.empty() ? head_.condition : "(" + head_.condition + ") && " + condition;
    s.condition = condition;
    std::string weight;
    for (const std::string& w : way.weights) weight += (weight.empty() ? "" : " * ") + w;
    s.probability = weight;
    s.successors = way.produced;
    for (ModuleText& m : successors) s.successors.push_back(std::move(m));
    s.keepsModule = keeps;
    out_.push_back(std::move(s));
  }

  void follow(std::vector<Frame> frames, Way way) {
    while (!frames.empty()) {
      Frame& frame = frames.back();
      if (frame.next >= frame.block->size()) {
        frames.pop_back();
        continue;
      }
      const Stmt& stmt = *(*frame.block)[frame.next++];
      switch (stmt.kind) {
        case StmtKind::Pass:
          break;
        case StmtKind::Return:
          frames.clear();
          break;
        case StmtKind::Produce:
          emit(way, word(stmt, way), false);
          return;
        case StmtKind::NProduce:
          for (ModuleText& m : word(stmt, way)) way.produced.push_back(std::move(m));
          break;
        case StmtKind::Assign: {
          std::string value = substitute(syntax_.expression(stmt.argBegin, stmt.argEnd), way, stmt);
          if (stmt.op != '=') {
            auto old = way.locals.find(stmt.name);
            const std::string before = old != way.locals.end() ? old->second.text : stmt.name;
            value = before + " " + stmt.op + " (" + value + ")";
          }
          way.locals[stmt.name] = Value{"(" + value + ")", holdsRandom(value)};
          way.randomUses.erase(stmt.name);
          break;
        }
        case StmtKind::If: {
          // Each branch continues with what follows the `if`. A random value is counted once
          // per test it appears in: two tests of one draw are not independent choices.
          std::vector<std::string> tests;
          for (const Branch& branch : stmt.branches)
            if (branch.condEnd)
              tests.push_back(substitute(syntax_.condition(branch.condBegin, branch.condEnd), way, stmt));
          for (size_t k = 0; k < stmt.branches.size(); ++k) {
            const Branch& branch = stmt.branches[k];
            Way next = way;
            for (size_t j = 0; j < k; ++j) negate(next, tests[j]);
            if (branch.condEnd) holds(next, tests[k], branch);
            std::vector<Frame> more = frames;
            more.push_back({&branch.body, 0});
            follow(std::move(more), std::move(next));
            if (!branch.condEnd) return;
          }
          // No `else`: the way where every test fails goes on after the `if`.
          for (const std::string& t : tests) negate(way, t);
          break;
        }
      }
    }
    // The end of the body without `produce`: what was `nproduce`d, else nothing (L-Py
    // tries the next production), unless a random choice was made on the way.
    if (!way.produced.empty())
      emit(way, {}, false);
    else if (!way.weights.empty()) {
      ModuleText self = head_.predecessor;
      emit(way, {self}, true);
    }
  }

  void holds(Way& way, const std::string& test, const Branch& branch) const {
    if (!holdsRandom(test)) {
      way.conditions.push_back(test);
      return;
    }
    std::optional<std::string> chance = chanceOf(test);
    if (!chance)
      syntax_.fail(branch.condBegin, branch.condEnd,
                   "a test of a random value other than a uniform draw compared with a chance (random() < p): the "
                   "cell language draws anew where a value is written, so it cannot follow this test");
    way.weights.push_back(*chance);
  }

  void negate(Way& way, const std::string& test) const {
    if (std::optional<std::string> chance = chanceOf(test); chance && holdsRandom(test))
      way.weights.push_back(*chance == "0" ? "1" : *chance == "1" ? "0" : "(1 - " + *chance + ")");
    else
      way.conditions.push_back("!(" + test + ")");
  }

  const ForeignSyntax& syntax_;
  std::string_view text_;
  const Statement& head_;
  std::vector<Statement> out_;
};

}  // namespace

std::vector<BodyLine> logicalLines(std::string_view text, uint32_t begin, uint32_t end) {
  std::vector<BodyLine> lines;
  uint32_t at = begin;
  while (at < end) {
    uint32_t lineEnd = at;
    while (lineEnd < end && text[lineEnd] != '\n') ++lineEnd;
    uint32_t first = at;
    int indent = 0;
    while (first < lineEnd && (text[first] == ' ' || text[first] == '\t' || text[first] == '\r')) {
      indent += text[first] == '\t' ? 8 - indent % 8 : text[first] == ' ' ? 1 : 0;
      ++first;
    }
    if (first == lineEnd) {
      at = lineEnd + 1;
      continue;
    }
    // Continue while a parenthesis is open (brackets and braces are modules of a word).
    int depth = 0;
    uint32_t stop = first;
    for (;;) {
      for (; stop < end && text[stop] != '\n'; ++stop) {
        if (text[stop] == '(') ++depth;
        if (text[stop] == ')') --depth;
      }
      if (depth <= 0 || stop >= end) break;
      ++stop;
    }
    lines.push_back({first, stop, indent});
    at = stop + 1;
  }
  return lines;
}

std::vector<Statement> translatePythonBody(const ForeignSyntax& syntax, std::string_view text,
                                           const Statement& head, const std::vector<BodyLine>& lines) {
  return BodyTranslator(syntax, text, head).run(lines);
}

}  // namespace ontogen::convert
