#include "lang/convert/lpy_hooks.h"

#include <set>
#include <utility>

#include "lang/convert/foreign_text.h"

namespace ontogen::convert {

namespace {

using chars::isLetter;
using chars::isNameChar;
using chars::isSpace;
using chars::shown;

// What a simple statement of a hook does.
enum class HookStmt { Global, Assign, UseGroup, Seed, Backward, Forward, Nothing };

// A simple statement of a hook as the reader reads it.
struct Simple {
  HookStmt kind = HookStmt::Nothing;
  uint32_t argBegin = 0, argEnd = 0;  // Assign: the value; UseGroup, Seed: the argument
  std::string name;                   // Assign: the name assigned
  char op = '=';                      // Assign: '=', or '+' '-' '*' '/' of an augmented one
  std::vector<std::string> names;     // Global
};

// The values a hook has set so far, on one way through it.
struct State {
  std::map<std::string, std::string> values;  // by the name as the block spells it
  std::map<std::string, SourceRange> origins;
  std::optional<std::string> group;
  SourceRange groupOrigin;
};

// Whether `text` (cell-language) names `name` as a whole word.
bool mentions(std::string_view text, std::string_view name) {
  for (size_t at = text.find(name); at != std::string_view::npos; at = text.find(name, at + 1)) {
    const bool starts = at == 0 || !(isNameChar(text[at - 1]) || text[at - 1] == '.');
    const bool ends = at + name.size() >= text.size() || !isNameChar(text[at + name.size()]);
    if (starts && ends) return true;
  }
  return false;
}

// Text without parentheses that enclose all of it.
std::string bare(std::string text) {
  while (text.size() >= 2 && text.front() == '(' && text.back() == ')') {
    int depth = 0;
    for (size_t i = 0; i + 1 < text.size(); ++i) {
      depth += text[i] == '(' ? 1 : text[i] == ')' ? -1 : 0;
      if (depth == 0) return text;
    }
    text = text.substr(1, text.size() - 2);
  }
  return text;
}

class HookReader {
 public:
  HookReader(ForeignSyntax& syntax, std::string_view text, const HookText& hook)
      : syntax_(syntax), text_(text), hook_(hook), body_(readPythonBlock(syntax_, text_, hook.body)) {
    check(body_);
  }

  /// The state after the hook, `iteration` being what getIterationNb() reads as.
  State run(const std::string& iteration, std::optional<std::string> groupBefore) {
    const std::string saved = syntax_.iterationNumber;
    syntax_.iterationNumber = iteration;
    State state;
    groupBefore_ = std::move(groupBefore);
    follow(body_, state, 0);
    syntax_.iterationNumber = saved;
    return state;
  }

  const std::set<std::string>& globals() const { return globals_; }
  /// StartEach's `g += D` at the top level: the increment of each counter.
  struct Counter {
    char op;
    std::string step;
    std::string after;  // the value the statement leaves, to tell it was the last
    SourceRange origin;
  };
  const std::map<std::string, Counter>& counters() const { return counters_; }
  const std::optional<std::pair<bool, SourceRange>>& direction() const { return direction_; }
  const std::optional<HookValue>& seed() const { return seed_; }

 private:
  bool startsWith(uint32_t b, uint32_t e, std::string_view word) const { return startsWithKeyword(text_, b, e, word); }

  [[noreturn]] void refuse(uint32_t b, uint32_t e, const std::string& what) const {
    syntax_.fail(b, e,
                 what + " in L-Py's " + hook_.name +
                     "(): the converter translates of the hooks global values set once or as values of "
                     "getIterationNb(), counters, useGroup, seed in Start, backward and forward on every step "
                     "(docs/LANGUAGE.md, Coming from cpfg, lpfg and L-Py)");
  }

  // Every statement is read before any is followed, so that one no way reaches is refused
  // too; an `assert` is a warning at its place, once.
  void check(const std::vector<PythonStatement>& statements) const {
    for (const PythonStatement& stmt : statements) {
      if (!stmt.isIf()) {
        if (startsWith(stmt.begin, stmt.end, "assert"))
          syntax_.warnings.push_back({SourceRange{stmt.begin, stmt.end},
                                      "'assert' in L-Py's " + hook_.name +
                                          "() is not checked: the converted block runs on where L-Py stops at an "
                                          "assertion that fails"});
        simple(stmt);
        continue;
      }
      for (const PythonBranch& branch : stmt.branches) check(branch.body);
    }
  }

  // The argument of NAME(...) filling the statement [b, e), or false.
  bool call(Simple& stmt, uint32_t b, uint32_t e, std::string_view name) const {
    if (!startsWith(b, e, name)) return false;
    uint32_t open = b + static_cast<uint32_t>(name.size());
    while (open < e && isSpace(text_[open])) ++open;
    if (open >= e || text_[open] != '(' || text_[e - 1] != ')') return false;
    int depth = 0;  // the last ')' closes this '('
    for (uint32_t k = open; k + 1 < e; ++k) {
      depth += text_[k] == '(' ? 1 : text_[k] == ')' ? -1 : 0;
      if (depth == 0) return false;
    }
    stmt.argBegin = open + 1;
    stmt.argEnd = e - 1;
    syntax_.trim(stmt.argBegin, stmt.argEnd);
    return true;
  }

  Simple simple(const PythonStatement& read) const {
    const uint32_t b = read.begin, e = read.end;
    if (startsWith(b, e, "if")) refuse(b, e, "an 'if' on the line of a test");
    Simple stmt;
    // What changes no word: the terminal, checks, the viewer's frames.
    for (std::string_view word : {"pass", "print", "assert", "frameDisplay"})
      if (startsWith(b, e, word)) return stmt;
    if (startsWith(b, e, "global")) {
      stmt.kind = HookStmt::Global;
      for (uint32_t at = b + 6; at < e;) {
        while (at < e && !isNameChar(text_[at])) ++at;
        uint32_t stop = at;
        while (stop < e && isNameChar(text_[stop])) ++stop;
        if (stop > at) stmt.names.emplace_back(text_.substr(at, stop - at));
        at = stop;
      }
      return stmt;
    }
    if (call(stmt, b, e, "useGroup")) {
      stmt.kind = HookStmt::UseGroup;
      return stmt;
    }
    if (call(stmt, b, e, "seed") || call(stmt, b, e, "random.seed")) {
      stmt.kind = HookStmt::Seed;
      return stmt;
    }
    if (call(stmt, b, e, "backward") || call(stmt, b, e, "forward")) {
      stmt.kind = startsWith(b, e, "backward") ? HookStmt::Backward : HookStmt::Forward;
      if (stmt.argBegin != stmt.argEnd) refuse(b, e, "a direction with an argument");
      return stmt;
    }
    if (startsWith(b, e, "return")) refuse(b, e, "'return', which gives L-Py a new word,");
    if (std::optional<PythonAssignment> assignment = readAssignment(text_, b, e)) {
      stmt.kind = HookStmt::Assign;
      stmt.name = std::move(assignment->name);
      stmt.op = assignment->op;
      stmt.argBegin = assignment->valueBegin;
      stmt.argEnd = e;
      syntax_.trim(stmt.argBegin, stmt.argEnd);
      return stmt;
    }
    uint32_t stop = b;
    while (stop < e && (isNameChar(text_[stop]) || text_[stop] == '.')) ++stop;
    refuse(b, e, stop > b ? shown(text_.substr(b, stop - b)) : std::string("this line"));
  }

  // A cell-language expression of [b, e) with the values the way has set put in.
  std::string value(uint32_t b, uint32_t e, const State& state, bool truth = false) const {
    const std::string text = truth ? syntax_.condition(b, e) : syntax_.expression(b, e);
    for (const std::string& parameter : hook_.parameters)
      if (mentions(text, cellName(parameter)))
        refuse(b, e, "the word or scene '" + parameter + "' read");
    if (mentions(text, "getGroup")) refuse(b, e, "getGroup(), the group of the step before,");
    std::map<std::string, HookValue, std::less<>> values;
    for (const auto& [name, v] : state.values) values[name] = {v, {}};
    return withHookValues(text, values, {});
  }

  void follow(const std::vector<PythonStatement>& block, State& state, int depth) {
    for (const PythonStatement& read : block) {
      const SourceRange at{read.begin, read.end};
      if (read.isIf()) {
        std::vector<std::string> tests;
        std::vector<State> ways;
        for (const PythonBranch& branch : read.branches) {
          if (branch.testEnd) tests.push_back(value(branch.testBegin, branch.testEnd, state, true));
          State way = state;
          follow(branch.body, way, depth + 1);
          ways.push_back(std::move(way));
        }
        // Without `else`, the way where every test fails keeps the state as it was.
        State merged = read.branches.back().testEnd ? state : ways.back();
        for (size_t k = tests.size(); k-- > 0;) {
          const State& taken = ways[k];
          for (const auto& [name, v] : taken.values) {
            const auto other = merged.values.find(name);
            const std::string otherwise = other != merged.values.end() ? other->second : name;
            if (otherwise != v) merged.values[name] = "if(" + tests[k] + ", " + v + ", " + otherwise + ")";
            merged.origins[name] = taken.origins.at(name);
          }
          for (const auto& [name, v] : merged.values)
            if (!taken.values.count(name)) merged.values[name] = "if(" + tests[k] + ", " + name + ", " + v + ")";
          if (taken.group || merged.group) {
            std::optional<std::string> before = state.group ? state.group : groupBefore_;
            const std::optional<std::string> yes = taken.group ? taken.group : before;
            const std::optional<std::string> no = merged.group ? merged.group : before;
            if (!yes || !no)
              refuse(read.begin, read.end,
                     "a way through the test that calls no useGroup, keeping the group of the step before "
                     "(the block's use group: is a value of the step alone; call useGroup on every way),");
            merged.group = *yes == *no ? *yes : "if(" + tests[k] + ", " + *yes + ", " + *no + ")";
            merged.groupOrigin = at;
          }
        }
        state = std::move(merged);
        continue;
      }
      const Simple stmt = simple(read);
      switch (stmt.kind) {
        case HookStmt::Nothing:
          break;
        case HookStmt::Global:
          globals_.insert(stmt.names.begin(), stmt.names.end());
          break;
        case HookStmt::UseGroup:
          state.group = value(stmt.argBegin, stmt.argEnd, state);
          state.groupOrigin = at;
          break;
        case HookStmt::Seed:
          if (hook_.name != "Start") refuse(read.begin, read.end, "a seed set again at each step");
          if (depth > 0) refuse(read.begin, read.end, "a seed set on one way of a test");
          seed_ = HookValue{value(stmt.argBegin, stmt.argEnd, state), at};
          break;
        case HookStmt::Backward:
        case HookStmt::Forward:
          if (depth > 0) refuse(read.begin, read.end, "a direction of derivation switched on one way of a test");
          direction_ = std::make_pair(stmt.kind == HookStmt::Backward, at);
          break;
        case HookStmt::Assign: {
          const std::string name = cellName(stmt.name);
          std::string v = value(stmt.argBegin, stmt.argEnd, state);
          if (stmt.op != '=') {
            const auto old = state.values.find(name);
            const bool first = old == state.values.end();
            const std::string before = first ? name : old->second;
            const std::string step = "(" + v + ")";
            v = before + " " + stmt.op + " " + step;
            if (first && depth == 0 && (stmt.op == '+' || stmt.op == '-') && globals_.count(stmt.name))
              counters_[stmt.name] = {stmt.op, step, "(" + v + ")", at};
          }
          state.values[name] = "(" + v + ")";
          state.origins[name] = at;
          break;
        }
      }
    }
  }

  ForeignSyntax& syntax_;
  std::string_view text_;
  const HookText& hook_;
  std::vector<PythonStatement> body_;
  std::set<std::string> globals_;
  std::map<std::string, Counter> counters_;
  std::optional<std::pair<bool, SourceRange>> direction_;
  std::optional<HookValue> seed_;
  std::optional<std::string> groupBefore_;
};

// Whether the hook declares `name` (as the block spells it) global.
bool declaresGlobal(const std::set<std::string>& globals, const std::string& name) {
  for (const std::string& g : globals)
    if (cellName(g) == name) return true;
  return false;
}

// A hook that may only pass, print, assert or declare: no value it sets is read after it.
void readOver(HookReader& reader, const HookText& hook, ForeignSyntax& syntax) {
  const State state = reader.run("time", std::nullopt);
  for (const auto& [name, origin] : state.origins) {
    if (!declaresGlobal(reader.globals(), name)) continue;  // a local of the hook, read by nothing after it
    syntax.fail(origin.begin, origin.end,
                "'" + name + "' set in L-Py's " + hook.name + "(), " +
                    (hook.name == "EndEach" ? "after each step: state carried to the next step, "
                                            : "after the derivation or around the drawing, ") +
                    "which the converter does not write");
  }
  if (state.group)
    syntax.fail(state.groupOrigin.begin, state.groupOrigin.end,
                "useGroup in L-Py's " + hook.name + "(): the converter writes the group StartEach or Start chooses");
  if (reader.direction() || reader.seed()) {
    const SourceRange at = reader.direction() ? reader.direction()->second : reader.seed()->origin;
    syntax.fail(at.begin, at.end, "a direction or seed set in L-Py's " + hook.name + "(), which the converter does not write");
  }
}

}  // namespace

bool isLPyHook(std::string_view name) {
  for (std::string_view hook : {"Start", "End", "StartEach", "EndEach", "StartInterpretation", "EndInterpretation",
                                "PostDraw", "__initialiseContext__"})
    if (name == hook) return true;
  return false;
}

std::string withHookValues(const std::string& text, const std::map<std::string, HookValue, std::less<>>& values,
                           const std::vector<std::string>& bound, bool* replaced) {
  std::string result;
  for (size_t i = 0; i < text.size();) {
    const bool starts = isLetter(text[i]) && (i == 0 || !(isNameChar(text[i - 1]) || text[i - 1] == '.'));
    if (!starts) {
      result += text[i++];
      continue;
    }
    size_t stop = i;
    while (stop < text.size() && isNameChar(text[stop])) ++stop;
    const std::string_view name = std::string_view(text).substr(i, stop - i);
    const bool call = stop < text.size() && text[stop] == '(';
    const auto value = values.find(name);
    bool isBound = false;
    for (const std::string& b : bound) isBound = isBound || b == name;
    if (value == values.end() || call || isBound) {
      result += name;
    } else {
      result += value->second.value.front() == '(' ? value->second.value : "(" + value->second.value + ")";
      if (replaced) *replaced = true;
    }
    i = stop;
  }
  return result;
}

HookEffects translateHooks(ForeignSyntax& syntax, std::string_view text, const std::vector<HookText>& hooks,
                           const std::map<std::string, std::string, std::less<>>& initial) {
  HookEffects effects;
  const HookText* start = nullptr;
  const HookText* each = nullptr;
  for (const HookText& hook : hooks) {
    if (hook.name == "Start") start = &hook;
    else if (hook.name == "StartEach") each = &hook;
    else {
      HookReader reader(syntax, text, hook);
      readOver(reader, hook, syntax);
    }
  }
  std::map<std::string, std::string, std::less<>> startValues = initial;
  if (start) {
    HookReader reader(syntax, text, *start);
    // Start runs before the first step: getIterationNb() is 0.
    const State state = reader.run("0", std::string("0"));
    for (const auto& [name, value] : state.values) {
      if (!declaresGlobal(reader.globals(), name)) continue;
      effects.defines[name] = {bare(value), state.origins.at(name)};
      startValues[name] = bare(value);
    }
    if (state.group) effects.useGroup = HookValue{bare(*state.group), state.groupOrigin};
    effects.seed = reader.seed();
    effects.backward = reader.direction();
  }
  if (!each) return effects;
  HookReader reader(syntax, text, *each);
  // The group: StartEach runs at the start of each step, where use group: reads time as
  // getIterationNb(); a way that calls no useGroup keeps the step before's group.
  const State forGroup = reader.run("time", std::nullopt);
  if (forGroup.group) effects.useGroup = HookValue{bare(*forGroup.group), forGroup.groupOrigin};
  // The values, as productions read them (their time is one more).
  const State state = reader.run("time - 1", std::nullopt);
  std::set<std::string> assigned;
  for (const auto& [name, value] : state.values)
    if (declaresGlobal(reader.globals(), name)) assigned.insert(name);
  for (const std::string& name : assigned) {
    const std::string& value = state.values.at(name);
    const SourceRange origin = state.origins.at(name);
    // A counter, `k += D` once on every step from the value Start or the file gives.
    for (const auto& [global, counter] : reader.counters()) {
      if (cellName(global) != name || counter.after != value) continue;
      bool constant = !mentions(counter.step, "time");
      for (const std::string& other : assigned) constant = constant && !mentions(counter.step, other);
      const auto from = startValues.find(name);
      if (!constant || from == startValues.end()) break;
      effects.stepValues[name] = {"(" + from->second + ") " + counter.op + " " + counter.step + " * time", origin};
      effects.defines.erase(name);
      break;
    }
    if (effects.stepValues.count(name)) continue;
    for (const std::string& other : assigned)
      if (mentions(value, other))
        syntax.fail(origin.begin, origin.end,
                    "'" + name + "' set in L-Py's StartEach() from " +
                        (other == name ? std::string("its own value") : "'" + other + "'") +
                        " of the step before: state carried from step to step, which the converter writes only for "
                        "a counter (global k; k += D, with k's value given by Start or the file)");
    if (mentions(value, "time")) {
      effects.stepValues[name] = {value, origin};
      effects.defines.erase(name);
    } else {
      effects.defines[name] = {bare(value), origin};
    }
  }
  if (reader.direction()) effects.backward = reader.direction();
  return effects;
}

}  // namespace ontogen::convert
