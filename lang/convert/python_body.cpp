#include "lang/convert/python_body.h"

#include <algorithm>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <string>

#include "lang/convert/foreign_text.h"
#include "lang/convert/python_loop.h"
#include "lang/convert/written_number.h"

namespace ontogen::convert {

namespace {

bool isNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}
bool isSpace(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}

// What a simple statement of a body does.
enum class StmtKind { Produce, NProduce, Assign, Pass, Return };

// A simple statement of a body as the translator reads it.
struct Simple {
  StmtKind kind = StmtKind::Pass;
  uint32_t argBegin = 0, argEnd = 0;  // Produce, NProduce: the word; Assign: the value
  std::string name;                   // Assign: the local
  char op = '=';                      // Assign: '=', or '+' '-' '*' '/' of an augmented one
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
    const std::vector<PythonStatement> body = readPythonBlock(syntax_, text_, lines);
    // The head's parameters and the body's locals hide the file's globals of their names.
    assigned_ = assignedNames(text_, body);
    std::set<std::string, std::less<>> names = parametersOf(head_);
    names.insert(assigned_.begin(), assigned_.end());
    const ForeignSyntax::Scope scope(syntax_, std::move(names));
    // Every statement is read before any is followed, so Python after a `produce` is
    // refused like Python before it.
    check(body);
    std::vector<Frame> frames{{&body, 0}};
    follow(frames, Way{});
    return std::move(out_);
  }

 private:
  struct Frame {
    const std::vector<PythonStatement>* block;
    size_t next;
    const PythonStatement* loop = nullptr;  // the `for` whose body this is
    size_t turn = 0;
    std::vector<std::string> values = {};  // the values its variable takes
  };

  bool startsWith(uint32_t begin, uint32_t end, std::string_view word) const {
    return startsWithKeyword(text_, begin, end, word);
  }

  [[noreturn]] void python(uint32_t begin, uint32_t end, const std::string& what) const {
    syntax_.fail(begin, end,
                 what +
                     ": Python which ontogen convert does not translate (it reads production bodies of if/elif/"
                     "else, produce, nproduce, assignments to locals, arithmetic, math and random functions)");
  }

  void check(const std::vector<PythonStatement>& statements) {
    for (const PythonStatement& stmt : statements) {
      if (stmt.isFor()) loops_.emplace(&stmt, readRangeLoop(syntax_, text_, stmt));
      if (!stmt.isIf() && !stmt.isFor()) {
        simple(stmt);
        continue;
      }
      for (const PythonBranch& branch : stmt.branches) check(branch.body);
    }
  }

  // The loop's variable takes its value of the frame's turn.
  void startTurn(Way& way, const Frame& frame) {
    if (++turns_ > kMaxLoopTurns)
      syntax_.fail(frame.loop->begin, frame.loop->branches.front().testEnd,
                   "the loops of this body turn more than " + std::to_string(kMaxLoopTurns) +
                       " times in all (over every way through its tests); write it as several productions");
    const std::string& name = loops_.at(frame.loop).name;
    const std::string& value = frame.values[frame.turn];
    way.locals[name] = Value{value.front() == '-' ? "(" + value + ")" : value, false};
    way.randomUses.erase(name);
  }

  Simple simple(const PythonStatement& read) const {
    const uint32_t b = read.begin, e = read.end;
    if (startsWith(b, e, "if")) python(b, e, "an 'if' on the line of a test");
    Simple stmt;
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
    if (leading("produce", StmtKind::Produce) || leading("nproduce", StmtKind::NProduce)) return stmt;
    // print(...) writes to the terminal, which changes no word.
    if (startsWith(b, e, "print")) return stmt;
    // An assert changes no word either, but L-Py stops where it fails: a warning, once.
    if (startsWith(b, e, "assert")) {
      const bool warned = std::any_of(syntax_.warnings.begin(), syntax_.warnings.end(),
                                      [&](const ConvertWarning& w) { return w.at.begin == b && w.at.end == e; });
      if (!warned)
        syntax_.warnings.push_back({SourceRange{b, e},
                                    "'assert' in a production body is not checked: the converted block runs on where "
                                    "L-Py stops at an assertion that fails"});
      return stmt;
    }
    // `global n` where the body only reads n: Python reads the global anyway. One the
    // body sets is a local of the body here, and must be read by nothing else (checked
    // when the whole file is read: lpy_globals.h).
    if (startsWith(b, e, "global")) {
      for (uint32_t at = b + 6; at < e;) {
        while (at < e && !isNameChar(text_[at])) ++at;
        uint32_t stop = at;
        while (stop < e && isNameChar(text_[stop])) ++stop;
        const std::string_view name = text_.substr(at, stop - at);
        if (!name.empty() && assigned_.count(name)) syntax_.bodyGlobals.emplace(name, SourceRange{b, e});
        at = stop;
      }
      return stmt;
    }
    // A string alone, as a comment: Python evaluates it and drops it.
    if (chars::isStringLiteral(text_.substr(b, e - b))) return stmt;
    if (startsWith(b, e, "pass")) {
      if (e != b + 4) python(b, e, "this line");
      return stmt;
    }
    if (startsWith(b, e, "return")) {
      uint32_t rb = b + 6, re = e;
      syntax_.trim(rb, re);
      if (rb != re && text_.substr(rb, re - rb) != "None") python(b, e, "a 'return' of a value");
      stmt.kind = StmtKind::Return;
      return stmt;
    }
    if (std::optional<PythonAssignment> assignment = readAssignment(text_, b, e)) {
      stmt.kind = StmtKind::Assign;
      stmt.name = std::move(assignment->name);
      stmt.op = assignment->op;
      stmt.argBegin = assignment->valueBegin;
      stmt.argEnd = e;
      return stmt;
    }
    uint32_t stop = b;
    while (stop < e && isNameChar(text_[stop])) ++stop;
    python(b, e, stop > b ? "'" + std::string(text_.substr(b, stop - b)) + "'" : std::string("this line"));
  }

  // A cell-language expression with the way's locals put in.
  std::string substitute(const std::string& expr, Way& way, const PythonStatement& where) const {
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
        syntax_.fits(result.size());
      }
      i = stop;
    }
    return result;
  }

  std::vector<ModuleText> word(const Simple& stmt, const PythonStatement& where, Way& way) const {
    std::vector<ModuleText> modules;
    if (stmt.argBegin < stmt.argEnd && !(stmt.argEnd == stmt.argBegin + 1 && text_[stmt.argBegin] == '*'))
      modules = syntax_.modules(stmt.argBegin, stmt.argEnd, false);
    for (ModuleText& module : modules)
      for (std::string& arg : module.args) arg = substitute(arg, way, where);
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
    for (const std::string& c : way.conditions) {
      condition += (condition.empty() ? "" : " && ") + c;
      syntax_.fits(condition.size());
    }
    if (!head_.condition.empty()) condition = condition.empty() ? head_.condition : "(" + head_.condition + ") && " + condition;
    s.condition = condition;
    std::string weight;
    for (const std::string& w : way.weights) weight += (weight.empty() ? "" : " * ") + w;
    s.probability = weight;
    s.successors = way.produced;
    for (ModuleText& m : successors) s.successors.push_back(std::move(m));
    s.keepsModule = keeps;
    syntax_.written(statementLineBytes(s));
    out_.push_back(std::move(s));
  }

  void follow(std::vector<Frame> frames, Way way) {
    // Ways that produce nothing give no production, so the bound on productions does not
    // bound them: tests in a row double the ways with or without a production.
    if (++ways_ > kMaxBodyWays)
      syntax_.fail(head_.origin.begin, head_.origin.end,
                   "this body has more than " + std::to_string(kMaxBodyWays) +
                       " ways through its tests; write it as several productions",
                   false);
    while (!frames.empty()) {
      Frame& frame = frames.back();
      if (frame.next >= frame.block->size()) {
        if (frame.loop && frame.turn + 1 < frame.values.size()) {
          frame.next = 0;
          ++frame.turn;
          startTurn(way, frame);
          continue;
        }
        frames.pop_back();
        continue;
      }
      const PythonStatement& read = (*frame.block)[frame.next++];
      if (read.isFor()) {
        // The range's arguments with the way's locals put in: a local or an outer loop's
        // variable holding a written number is one.
        const RangeLoop& loop = loops_.at(&read);
        std::vector<std::string> arguments;
        for (const auto& [x, y] : loop.arguments) arguments.push_back(substitute(syntax_.expression(x, y), way, read));
        std::vector<std::string> values = loopTurns(syntax_, loop, arguments);
        if (values.empty()) continue;
        frames.push_back({&read.branches.front().body, 0, &read, 0, std::move(values)});
        startTurn(way, frames.back());
        continue;
      }
      if (read.isIf()) {
        if (std::optional<std::vector<std::string>> weights = drawnChoice(read, way)) {
          // One draw against rising thresholds: each branch a choice of its own chance.
          bool otherwise = false;
          for (size_t k = 0; k < read.branches.size(); ++k) {
            Way chosen = way;
            chosen.weights.push_back((*weights)[k]);
            std::vector<Frame> more = frames;
            more.push_back({&read.branches[k].body, 0});
            follow(std::move(more), std::move(chosen));
            otherwise = otherwise || !read.branches[k].testEnd;
          }
          if (otherwise) return;
          way.weights.push_back(weights->back());  // no `else`: every test failed
          continue;
        }
        // Each branch continues with what follows the `if`. A random value is counted once
        // per test it appears in: two tests of one draw are not independent choices. A test
        // of written numbers alone (a loop's turn, `i == 0`) is decided here.
        std::vector<std::string> tests;
        std::vector<std::optional<bool>> decided;
        for (const PythonBranch& branch : read.branches) {
          if (!branch.testEnd) continue;
          tests.push_back(substitute(syntax_.condition(branch.testBegin, branch.testEnd), way, read));
          std::optional<double> value = holdsRandom(tests.back()) ? std::nullopt : writtenNumber(tests.back());
          decided.push_back(value ? std::optional<bool>(*value != 0) : std::nullopt);
        }
        for (size_t k = 0; k < read.branches.size(); ++k) {
          const PythonBranch& branch = read.branches[k];
          if (branch.testEnd && decided[k] == false) continue;
          Way next = way;
          for (size_t j = 0; j < k; ++j)
            if (!decided[j]) negate(next, tests[j]);
          if (branch.testEnd && !decided[k]) holds(next, tests[k], branch);
          std::vector<Frame> more = frames;
          more.push_back({&branch.body, 0});
          follow(std::move(more), std::move(next));
          if (!branch.testEnd || decided[k] == true) return;
        }
        // No `else`: the way where every test fails goes on after the `if`.
        for (size_t j = 0; j < tests.size(); ++j)
          if (!decided[j]) negate(way, tests[j]);
        continue;
      }
      const Simple stmt = simple(read);
      switch (stmt.kind) {
        case StmtKind::Pass:
          break;
        case StmtKind::Return:
          frames.clear();
          break;
        case StmtKind::Produce:
          emit(way, word(stmt, read, way), false);
          return;
        case StmtKind::NProduce:
          for (ModuleText& m : word(stmt, read, way)) way.produced.push_back(std::move(m));
          break;
        case StmtKind::Assign: {
          if (std::optional<std::pair<long long, long long>> range = randint(stmt, read, way)) {
            // Each whole number of the range a way of its own, chosen with an equal chance.
            const long long count = range->second - range->first + 1;
            for (long long k = range->first; k <= range->second; ++k) {
              Way chosen = way;
              if (count > 1) chosen.weights.push_back("1 / " + std::to_string(count));
              chosen.locals[stmt.name] = Value{std::to_string(k), false};
              chosen.randomUses.erase(stmt.name);
              follow(frames, std::move(chosen));
            }
            return;
          }
          std::string value = substitute(syntax_.expression(stmt.argBegin, stmt.argEnd), way, read);
          if (stmt.op != '=') {
            auto old = way.locals.find(stmt.name);
            const std::string before = old != way.locals.end() ? old->second.text : stmt.name;
            value = before + " " + stmt.op + " (" + value + ")";
          }
          syntax_.written(value.size());
          way.locals[stmt.name] = Value{"(" + value + ")", holdsRandom(value)};
          way.randomUses.erase(stmt.name);
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

  // `r = random()` tested in `if r <= p1: ... elif r <= p2: ... else: ...`, one uniform
  // draw against thresholds (`<` or `<=`, the draw on the left), read nowhere before: the
  // chance of each branch, max(0, p_k - max(p_1 .. p_k-1)) with each p clamped to [0, 1],
  // and last that of the way where every test fails, 1 - max(p_1 .. p_n). nullopt for
  // any other `if`.
  std::optional<std::vector<std::string>> drawnChoice(const PythonStatement& read, Way& way) const {
    std::string draw;
    std::vector<std::string> thresholds;
    for (const PythonBranch& branch : read.branches) {
      if (!branch.testEnd) continue;
      const std::string test(bare(syntax_.condition(branch.testBegin, branch.testEnd)));
      size_t stop = 0;
      while (stop < test.size() && isNameChar(test[stop])) ++stop;
      const std::string name = test.substr(0, stop);
      size_t op = stop;
      while (op < test.size() && isSpace(test[op])) ++op;
      if (name.empty() || (!draw.empty() && name != draw) || test.compare(op, 1, "<") != 0 ||
          test.compare(op, 2, "<<") == 0)
        return std::nullopt;
      const auto local = way.locals.find(name);
      if (local == way.locals.end() || !isUniformDraw(local->second.text) || way.randomUses.count(name))
        return std::nullopt;
      draw = name;
      const size_t value = op + (test.compare(op, 2, "<=") == 0 ? 2 : 1);
      const std::string threshold(bare(substitute(test.substr(value), way, read)));
      // `r <= p and x > 1` is (r <= p) and (x > 1): a threshold holds no other operator of truth.
      if (threshold.empty() || holdsRandom(threshold) || threshold.find_first_of("&|<>=!?") != std::string::npos)
        return std::nullopt;
      for (size_t at = threshold.find(name); at != std::string::npos; at = threshold.find(name, at + 1))
        if ((at == 0 || !isNameChar(threshold[at - 1])) &&
            (at + name.size() == threshold.size() || !isNameChar(threshold[at + name.size()])))
          return std::nullopt;
      char* end = nullptr;
      const double number = std::strtod(threshold.c_str(), &end);
      thresholds.push_back(end == threshold.c_str() + threshold.size() && number >= 0 && number <= 1
                               ? threshold
                               : "clamp(" + threshold + ", 0, 1)");
    }
    if (thresholds.size() < 2) return std::nullopt;
    std::vector<std::string> weights{thresholds[0]};
    std::string below = thresholds[0];  // the largest threshold before
    for (size_t k = 1; k < thresholds.size(); ++k) {
      weights.push_back("max(0, " + thresholds[k] + " - " + below + ")");
      below = "max(" + below + ", " + thresholds[k] + ")";
    }
    weights.push_back("1 - " + below);
    way.randomUses[draw] = 1;
    return weights;
  }

  // `n = randint(a, b)` (also `random.randint`, or through `import random as rd`) with
  // bounds of written numbers or constants: [a, b], Python's whole numbers from a to b.
  std::optional<std::pair<long long, long long>> randint(const Simple& stmt, const PythonStatement& where,
                                                         Way& way) const {
    if (stmt.op != '=') return std::nullopt;
    uint32_t b = stmt.argBegin, e = stmt.argEnd;
    syntax_.trim(b, e);
    uint32_t open = b;
    while (open < e && (isNameChar(text_[open]) || text_[open] == '.')) ++open;
    const std::string_view call = text_.substr(b, open - b);
    const size_t dot = call.rfind('.');
    const std::string_view module = dot == std::string_view::npos ? "" : call.substr(0, dot);
    const auto alias = syntax_.moduleAliases.find(module);
    const bool fromRandom = module.empty() || module == "random" ||
                            (alias != syntax_.moduleAliases.end() && alias->second == "random");
    if (call.substr(dot == std::string_view::npos ? 0 : dot + 1) != "randint" || !fromRandom || open >= e ||
        text_[open] != '(' || syntax_.find(open, e, ")") != e - 1)
      return std::nullopt;
    std::vector<long long> bounds;
    for (uint32_t from = open + 1; from < e;) {
      const uint32_t comma = syntax_.find(from, e - 1, ",");
      uint32_t x = from, y = comma;
      syntax_.trim(x, y);
      const std::string value = substitute(syntax_.expression(x, y), way, where);
      const std::optional<double> number = syntax_.fixedNumber(value, x, y);
      if (!number || *number != std::floor(*number) || std::fabs(*number) > 1e15)
        syntax_.fail(x, y,
                     "a bound of randint that is no whole number written in the file or a constant of one: the "
                     "converter writes one random choice per number of the range");
      bounds.push_back(static_cast<long long>(*number));
      from = comma + 1;
    }
    if (bounds.size() != 2) syntax_.fail(b, e, "randint of other than two bounds");
    if (bounds[1] < bounds[0]) syntax_.fail(b, e, "randint(a, b) with b below a (Python refuses it)");
    if (bounds[1] - bounds[0] >= static_cast<long long>(kMaxRandintChoices))
      syntax_.fail(b, e,
                   "randint over more than " + std::to_string(kMaxRandintChoices) +
                       " numbers: the converter writes one random choice per number");
    return std::pair{bounds[0], bounds[1]};
  }

  void holds(Way& way, const std::string& test, const PythonBranch& branch) const {
    if (!holdsRandom(test)) {
      way.conditions.push_back(test);
      return;
    }
    std::optional<std::string> chance = chanceOf(test);
    if (!chance)
      syntax_.fail(branch.testBegin, branch.testEnd,
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
  std::map<const PythonStatement*, RangeLoop> loops_;  // each `for` as check() read it
  size_t turns_ = 0;                                   // turns of loops followed so far
  size_t ways_ = 0;                                    // ways followed so far
  std::set<std::string, std::less<>> assigned_;        // the names the body sets
};

// A helper function's body followed way by way to the value it returns.
class FunctionTranslator {
 public:
  FunctionTranslator(const ForeignSyntax& syntax, std::string_view text) : syntax_(syntax), text_(text) {}

  std::string run(const std::vector<std::string>& parameters, const std::vector<BodyLine>& lines) {
    const std::vector<PythonStatement> body = readPythonBlock(syntax_, text_, lines);
    if (body.empty()) return "0";
    // Its parameters and locals hide the file's globals of their names.
    std::set<std::string, std::less<>> names = assignedNames(text_, body);
    names.insert(parameters.begin(), parameters.end());
    const ForeignSyntax::Scope scope(syntax_, std::move(names));
    parameters_.insert(parameters.begin(), parameters.end());
    last_ = body.back();
    return value({{&body, 0}}, {});
  }

 private:
  struct Frame {
    const std::vector<PythonStatement>* block;
    size_t next;
    const PythonStatement* loop = nullptr;  // the `for` whose body this is
    size_t turn = 0;
    std::vector<std::string> values = {};  // the values its variable takes
  };
  using Frames = std::vector<Frame>;
  struct Local {
    std::string text;
    bool random = false;
    int reads = 0;
  };
  using Locals = std::map<std::string, Local>;

  bool starts(const PythonStatement& s, std::string_view word) const {
    return startsWithKeyword(text_, s.begin, s.end, word);
  }

  [[noreturn]] void python(const PythonStatement& s, const std::string& what) const {
    syntax_.fail(s.begin, s.end,
                 what +
                     " in a helper function: Python which ontogen convert does not translate (it reads functions of "
                     "if/elif/else, assignments to locals, loops over ranges of written numbers and return of a "
                     "value)");
  }

  // The cell-language expression [b, e) with the locals put in.
  std::string expression(uint32_t b, uint32_t e, Locals& locals, const PythonStatement& where, bool truth = false) const {
    const std::string text = truth ? syntax_.condition(b, e) : syntax_.expression(b, e);
    std::string result;
    for (size_t i = 0; i < text.size();) {
      const bool begins = (std::isalpha(static_cast<unsigned char>(text[i])) || text[i] == '_') &&
                          (i == 0 || !(isNameChar(text[i - 1]) || text[i - 1] == '.'));
      if (!begins) {
        result += text[i++];
        continue;
      }
      size_t stop = i;
      while (stop < text.size() && isNameChar(text[stop])) ++stop;
      const std::string name = text.substr(i, stop - i);
      auto local = locals.find(name);
      if (local == locals.end() || (stop < text.size() && text[stop] == '(')) {
        result += name;
      } else {
        if (local->second.random && ++local->second.reads > 1)
          syntax_.fail(where.begin, where.end,
                       "the random value '" + name +
                           "' read a second time: the cell language draws anew where it is written, so the values "
                           "would differ");
        result += local->second.text;
        syntax_.fits(result.size());
      }
      i = stop;
    }
    return result;
  }

  // The value returned from the statement `frames` stand at.
  std::string value(Frames frames, Locals locals) {
    if (++ways_ > kMaxBodyProductions)
      syntax_.fail(last_.begin, last_.end,
                   "this function has more than " + std::to_string(kMaxBodyProductions) + " ways through its tests",
                   false);
    while (!frames.empty()) {
      Frame& frame = frames.back();
      if (frame.next >= frame.block->size()) {
        if (frame.loop && frame.turn + 1 < frame.values.size()) {
          frame.next = 0;
          ++frame.turn;
          startTurn(locals, frame);
          continue;
        }
        frames.pop_back();
        continue;
      }
      const PythonStatement& s = (*frame.block)[frame.next++];
      if (s.isFor()) {
        // Written out turn by turn, as in a production body (python_loop.h).
        const RangeLoop loop = readRangeLoop(syntax_, text_, s);
        std::vector<std::string> arguments;
        for (const auto& [x, y] : loop.arguments) arguments.push_back(expression(x, y, locals, s));
        std::vector<std::string> values = loopTurns(syntax_, loop, arguments);
        if (values.empty()) continue;
        frames.push_back({&s.branches.front().body, 0, &s, 0, std::move(values)});
        startTurn(locals, frames.back());
        continue;
      }
      if (s.isIf()) {
        std::vector<std::string> tests;
        for (const PythonBranch& branch : s.branches)
          if (branch.testEnd) tests.push_back(expression(branch.testBegin, branch.testEnd, locals, s, true));
        const bool otherwise = !s.branches.back().testEnd;
        std::string result = otherwise ? "" : value(frames, locals);
        for (size_t k = s.branches.size(); k-- > 0;) {
          Frames way = frames;
          way.push_back({&s.branches[k].body, 0});
          std::string taken = value(way, locals);
          result = s.branches[k].testEnd ? "if(" + tests[k] + ", " + taken + ", " + result + ")" : taken;
        }
        return result;
      }
      const char first = text_[s.begin];
      if (first == '"' || first == '\'' || starts(s, "pass") || starts(s, "print")) continue;
      if (starts(s, "return")) {
        uint32_t b = s.begin + 6, e = s.end;
        syntax_.trim(b, e);
        if (b == e || text_.substr(b, e - b) == "None") python(s, "a 'return' of no value");
        return "(" + expression(b, e, locals, s) + ")";
      }
      const std::optional<PythonAssignment> assignment = readAssignment(text_, s.begin, s.end);
      if (!assignment) {
        uint32_t stop = s.begin;
        while (stop < s.end && isNameChar(text_[stop])) ++stop;
        python(s, stop > s.begin ? "'" + std::string(text_.substr(s.begin, stop - s.begin)) + "'" : "this line");
      }
      const std::string& name = assignment->name;
      const char kind = assignment->op;
      std::string v = expression(assignment->valueBegin, s.end, locals, s);
      if (kind != '=') {
        auto old = locals.find(name);
        if (old == locals.end() && !parameters_.count(name)) python(s, "'" + name + "' changed before it is set");
        v = (old == locals.end() ? name : old->second.text) + " " + kind + " (" + v + ")";
      }
      syntax_.written(v.size());
      locals[name] = Local{"(" + v + ")", holdsRandom(v), 0};
    }
    syntax_.fail(last_.begin, last_.end, "a way through this helper function ends here and returns no value (None)");
  }

  // The loop's variable takes its value of the frame's turn.
  void startTurn(Locals& locals, const Frame& frame) {
    if (++turns_ > kMaxLoopTurns)
      syntax_.fail(frame.loop->begin, frame.loop->branches.front().testEnd,
                   "the loops of this function turn more than " + std::to_string(kMaxLoopTurns) +
                       " times in all (over every way through its tests)");
    std::string name = readRangeLoop(syntax_, text_, *frame.loop).name;
    const std::string& value = frame.values[frame.turn];
    locals[std::move(name)] = Local{value.front() == '-' ? "(" + value + ")" : value, false, 0};
  }

  const ForeignSyntax& syntax_;
  std::string_view text_;
  PythonStatement last_;  // the body's last statement, where a way without return ends
  size_t ways_ = 0;
  size_t turns_ = 0;  // turns of loops followed so far
  std::set<std::string, std::less<>> parameters_;
};

}  // namespace

std::string translatePythonFunction(const ForeignSyntax& syntax, std::string_view text,
                                    const std::vector<std::string>& parameters, const std::vector<BodyLine>& lines) {
  return FunctionTranslator(syntax, text).run(parameters, lines);
}

std::vector<Statement> translatePythonBody(const ForeignSyntax& syntax, std::string_view text,
                                           const Statement& head, const std::vector<BodyLine>& lines) {
  return BodyTranslator(syntax, text, head).run(lines);
}

}  // namespace ontogen::convert
