#include "interpreters/sweep/measure.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace ontogen {

namespace {

using Source = QuantitySource;

constexpr std::array kQuantities{
    QuantityInfo{"cells", Source::World, "cells in every pool at the end"},
    QuantityInfo{"time", Source::World, "the world's time at the end, seconds"},
    QuantityInfo{"steps", Source::World, "steps of the development"},
    QuantityInfo{"events", Source::World, "terminal-age events"},
    QuantityInfo{"born", Source::World, "cells born"},
    QuantityInfo{"firings", Source::World, "per-step rules that fired"},
    QuantityInfo{"min_x", Source::Scene, "the last frame's bounding box, model units (0 when nothing is drawn)"},
    QuantityInfo{"min_y", Source::Scene, "likewise"},
    QuantityInfo{"min_z", Source::Scene, "likewise"},
    QuantityInfo{"max_x", Source::Scene, "likewise"},
    QuantityInfo{"max_y", Source::Scene, "likewise"},
    QuantityInfo{"max_z", Source::Scene, "likewise"},
    QuantityInfo{"width", Source::Scene, "max_x - min_x"},
    QuantityInfo{"height", Source::Scene, "max_y - min_y (y is up)"},
    QuantityInfo{"depth", Source::Scene, "max_z - min_z"},
    QuantityInfo{"length", Source::Geometry, "length drawn by F and cC in the last frame, model units"},
    QuantityInfo{"rods", Source::Physics, "rods of the last frame"},
    QuantityInfo{"mass", Source::Physics, "their mass, kg"},
    QuantityInfo{"root_force", Source::Physics, "|F| at the base of the first root rod, N"},
    QuantityInfo{"root_moment", Source::Physics, "|M| about the base of the first root rod, N m"},
    QuantityInfo{"deflection", Source::Physics, "the largest distance of a rod's tip from its rest tip, m"},
    QuantityInfo{"distance", Source::Creature,
                 "walked by the last creature since time 0, model units (dynamics: the first root's travel along the "
                 "ground from the first frame to the last)"},
    QuantityInfo{"slip", Source::Creature,
                 "the farthest a foot moved while planted (on the ground in consecutive frames), model units "
                 "(dynamics: how far the points touching the ground slid along it in all)"},
    QuantityInfo{"fallen", Source::Dynamics,
                 "1 when the body's centre of mass ended below half its height at the first frame, else 0"},
    QuantityInfo{"energy", Source::Dynamics, "the servos' work, |torque x angular speed| over every step, summed"},
    QuantityInfo{"unstable", Source::Dynamics,
                 "steps at which MuJoCo found the simulation unstable (a position, speed or acceleration not "
                 "finite or past 1e10) and reset it; 0 for a steady run"},
};

// An expression deeper than this is no measure anyone writes; the bound keeps the
// recursive parser and evaluator off the end of the stack.
constexpr int kMaxDepth = 200;

enum class Op : uint8_t { Number, Quantity, Count, Negate, Add, Subtract, Multiply, Divide, Power, Call };

}  // namespace

struct Measure::Node {
  Op op = Op::Number;
  double number = 0;
  std::string name;  // quantity, label or function
  std::vector<std::shared_ptr<const Node>> args;
};

std::span<const QuantityInfo> quantities() { return kQuantities; }

std::string_view quantitySourceSet(QuantitySource source) {
  switch (source) {
    case Source::World: return "";
    case Source::Scene: return "a set that draws";
    case Source::Geometry: return "geometry";
    case Source::Physics: return "physics";
    case Source::Creature: return "creature";
    case Source::Dynamics: return "dynamics";
  }
  return "";
}

namespace {

using NodePtr = std::shared_ptr<const Measure::Node>;

struct Function {
  std::string_view name;
  int arity;
};
constexpr std::array kFunctions{Function{"abs", 1}, Function{"sqrt", 1}, Function{"exp", 1}, Function{"log", 1},
                                Function{"min", 2}, Function{"max", 2}};

bool nameStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool nameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Recursive descent over the expression text; every error names the measure and the
// column (1-based) where it is.
class Parser {
 public:
  Parser(std::string_view measure, std::string_view text, std::span<const std::string> extra)
      : measure_(measure), text_(text), extra_(extra) {}

  NodePtr parse() {
    NodePtr root = sum(0);
    skipSpaces();
    if (at_ < text_.size()) fail("unexpected '" + std::string(1, text_[at_]) + "'");
    return root;
  }
  std::vector<QuantitySource> sources;
  std::vector<std::string> labels;

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw MeasureError("--measure " + std::string(measure_) + ": " + what + " at column " + std::to_string(at_ + 1) +
                       " of '" + std::string(text_) + "'");
  }
  void skipSpaces() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) ++at_;
  }
  bool match(char c) {
    skipSpaces();
    if (at_ < text_.size() && text_[at_] == c) {
      ++at_;
      return true;
    }
    return false;
  }
  void expect(char c) {
    if (!match(c)) fail(std::string("expected '") + c + "'");
  }
  static NodePtr make(Op op, std::vector<NodePtr> args = {}, double number = 0, std::string name = {}) {
    auto node = std::make_shared<Measure::Node>();
    node->op = op;
    node->args = std::move(args);
    node->number = number;
    node->name = std::move(name);
    return node;
  }
  void deeper(int depth) const {
    if (depth > kMaxDepth) fail("expression too deep (more than " + std::to_string(kMaxDepth) + " levels)");
  }

  NodePtr sum(int depth) {
    deeper(depth);
    NodePtr left = product(depth + 1);
    for (;;) {
      if (match('+'))
        left = make(Op::Add, {left, product(depth + 1)});
      else if (match('-'))
        left = make(Op::Subtract, {left, product(depth + 1)});
      else
        return left;
    }
  }
  NodePtr product(int depth) {
    deeper(depth);
    NodePtr left = unary(depth + 1);
    for (;;) {
      if (match('*'))
        left = make(Op::Multiply, {left, unary(depth + 1)});
      else if (match('/'))
        left = make(Op::Divide, {left, unary(depth + 1)});
      else
        return left;
    }
  }
  NodePtr unary(int depth) {
    deeper(depth);
    if (match('-')) return make(Op::Negate, {unary(depth + 1)});
    if (match('+')) return unary(depth + 1);
    return power(depth + 1);
  }
  NodePtr power(int depth) {
    deeper(depth);
    NodePtr base = atom(depth + 1);
    if (match('^')) return make(Op::Power, {base, unary(depth + 1)});
    return base;
  }
  NodePtr atom(int depth) {
    deeper(depth);
    skipSpaces();
    if (at_ >= text_.size()) fail("expected a number, a quantity or '('");
    const char c = text_[at_];
    if (c == '(') {
      ++at_;
      NodePtr inner = sum(depth + 1);
      expect(')');
      return inner;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (nameStart(c)) return named(depth);
    fail("expected a number, a quantity or '(', not '" + std::string(1, c) + "'");
  }
  NodePtr number() {
    char* end = nullptr;
    const std::string copy(text_.substr(at_));
    const double value = std::strtod(copy.c_str(), &end);
    const size_t used = static_cast<size_t>(end - copy.c_str());
    if (used == 0 || !std::isfinite(value)) fail("not a finite number");
    at_ += used;
    return make(Op::Number, {}, value);
  }
  NodePtr named(int depth) {
    const size_t start = at_;
    while (at_ < text_.size() && nameChar(text_[at_])) ++at_;
    const std::string name(text_.substr(start, at_ - start));
    if (name == "count") {
      expect('(');
      skipSpaces();
      const size_t from = at_;
      while (at_ < text_.size() && text_[at_] != ')') ++at_;
      std::string label(text_.substr(from, at_ - from));
      while (!label.empty() && std::isspace(static_cast<unsigned char>(label.back()))) label.pop_back();
      if (label.empty()) fail("count() takes a cell's label, as in count(Apex)");
      expect(')');
      if (std::find(labels.begin(), labels.end(), label) == labels.end()) labels.push_back(label);
      return make(Op::Count, {}, 0, label);
    }
    for (const Function& function : kFunctions) {
      if (function.name != name) continue;
      expect('(');
      std::vector<NodePtr> args{sum(depth + 1)};
      while (static_cast<int>(args.size()) < function.arity) {
        expect(',');
        args.push_back(sum(depth + 1));
      }
      expect(')');
      return make(Op::Call, std::move(args), 0, name);
    }
    for (const QuantityInfo& quantity : kQuantities)
      if (quantity.name == name) {
        if (std::find(sources.begin(), sources.end(), quantity.source) == sources.end())
          sources.push_back(quantity.source);
        return make(Op::Quantity, {}, 0, name);
      }
    if (std::find(extra_.begin(), extra_.end(), name) != extra_.end()) return make(Op::Quantity, {}, 0, name);
    at_ = start;
    std::string known;
    for (const QuantityInfo& quantity : kQuantities) known += (known.empty() ? "" : ", ") + std::string(quantity.name);
    for (const std::string& other : extra_) known += ", " + other;
    fail("unknown quantity '" + name + "' (known: " + known + "; functions abs, sqrt, exp, log, min, max, count)");
  }

  std::string_view measure_, text_;
  std::span<const std::string> extra_;
  size_t at_ = 0;
};

double evaluateNode(const Measure::Node& node, const RunQuantities& quantities) {
  auto arg = [&](size_t i) { return evaluateNode(*node.args[i], quantities); };
  switch (node.op) {
    case Op::Number: return node.number;
    case Op::Quantity: {
      const auto found = quantities.values.find(node.name);
      return found == quantities.values.end() ? std::numeric_limits<double>::quiet_NaN() : found->second;
    }
    case Op::Count: {
      const auto found = quantities.labels.find(node.name);
      return found == quantities.labels.end() ? 0.0 : static_cast<double>(found->second);
    }
    case Op::Negate: return -arg(0);
    case Op::Add: return arg(0) + arg(1);
    case Op::Subtract: return arg(0) - arg(1);
    case Op::Multiply: return arg(0) * arg(1);
    case Op::Divide: return arg(0) / arg(1);
    case Op::Power: return std::pow(arg(0), arg(1));
    case Op::Call:
      if (node.name == "abs") return std::abs(arg(0));
      if (node.name == "sqrt") return std::sqrt(arg(0));
      if (node.name == "exp") return std::exp(arg(0));
      if (node.name == "log") return std::log(arg(0));
      if (node.name == "min") return std::min(arg(0), arg(1));
      if (node.name == "max") return std::max(arg(0), arg(1));
      break;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

double Measure::evaluate(const RunQuantities& quantities) const { return evaluateNode(*root_, quantities); }

Measure parseMeasure(std::string_view text, std::span<const std::string> extra) {
  const size_t equals = text.find('=');
  const std::string_view name = equals == std::string_view::npos ? std::string_view{} : text.substr(0, equals);
  const bool named = !name.empty() && nameStart(name[0]) && std::all_of(name.begin(), name.end(), nameChar);
  if (!named)
    throw MeasureError("--measure takes NAME=EXPR, a name of letters, digits and '_' and an expression, as in "
                       "--measure tall=height, not '" +
                       std::string(text) + "'");
  const std::string_view expression = text.substr(equals + 1);
  Parser parser(name, expression, extra);
  Measure measure;
  measure.name_ = std::string(name);
  measure.text_ = std::string(expression);
  measure.root_ = parser.parse();
  measure.sources_ = std::move(parser.sources);
  measure.labels_ = std::move(parser.labels);
  return measure;
}

}  // namespace ontogen
