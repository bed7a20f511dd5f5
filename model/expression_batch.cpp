#include "model/expression_batch.h"

#include <algorithm>
#include <cstring>

namespace ontogen {

namespace {

using Place = BatchCode::Place;
using Instruction = BatchCode::Instruction;
using Kernel = BatchCode::Kernel;

// Places an evaluation's table holds at most (results, output, slots, aggregates and
// constants); an expression that needs more takes the stack interpreter. Frames of
// hundreds of values are not what rates read.
constexpr int kMaxPlaces = 256;

// Two lanes as one vector of the compiler's (an SSE2 register): each is loaded before
// its result is stored, so a result may go where an operand was.
typedef double Pair __attribute__((vector_size(16)));

Pair load(const double* at) {
  Pair q;
  std::memcpy(&q, at, sizeof q);
  return q;
}

void store(double* at, Pair q) {
  std::memcpy(at, &q, sizeof q);
}

enum class Arithmetic : uint8_t { Add, Sub, Mul, Div };

bool arithmetic(OpCode op, Arithmetic& kind) {
  switch (op) {
    case OpCode::Add:
      kind = Arithmetic::Add;
      return true;
    case OpCode::Sub:
      kind = Arithmetic::Sub;
      return true;
    case OpCode::Mul:
      kind = Arithmetic::Mul;
      return true;
    case OpCode::Div:
      kind = Arithmetic::Div;
      return true;
    default:
      return false;
  }
}

template <Arithmetic op, typename T>
T apply(T a, T b) {
  if constexpr (op == Arithmetic::Add) return a + b;
  if constexpr (op == Arithmetic::Sub) return a - b;
  if constexpr (op == Arithmetic::Mul) return a * b;
  if constexpr (op == Arithmetic::Div) return a / b;
}

// The lanes a kernel made for N runs: N, or the evaluation's count where N is 0.
template <int N>
int lanesOf(int lanes) {
  if constexpr (N == 0) return lanes;
  return N;
}

template <int N, Arithmetic op>
void binary(const BatchCode&, const Instruction& in, double* const* results, const double* const* inputs, int lanes,
            const EvalContext&) {
  const int n = lanesOf<N>(lanes);
  const double* a = inputs[in.a];
  const double* b = inputs[in.b];
  double* r = results[in.result];
  int l = 0;
  for (; l + 2 <= n; l += 2) store(r + l, apply<op>(load(a + l), load(b + l)));
  for (; l < n; ++l) r[l] = apply<op>(a[l], b[l]);
}

// Two operations, the first's result only feeding the second: second(first(a, b), c), or
// second(c, first(a, b)). Each rounds as on its own (the file is built without contraction).
template <int N, Arithmetic first, Arithmetic second, bool resultFirst>
void fused(const BatchCode&, const Instruction& in, double* const* results, const double* const* inputs, int lanes,
           const EvalContext&) {
  const int n = lanesOf<N>(lanes);
  const double* a = inputs[in.a];
  const double* b = inputs[in.b];
  const double* c = inputs[in.c];
  double* r = results[in.result];
  auto both = [](auto x, auto y, auto z) {
    const auto inner = apply<first>(x, y);
    if constexpr (resultFirst)
      return apply<second>(inner, z);
    else
      return apply<second>(z, inner);
  };
  int l = 0;
  for (; l + 2 <= n; l += 2) store(r + l, both(load(a + l), load(b + l), load(c + l)));
  for (; l < n; ++l) r[l] = both(a[l], b[l], c[l]);
}

// Three operations in a chain, each result only feeding the next:
// third(second(first(a, b), c), d), each intermediate on either side.
template <int N, Arithmetic first, Arithmetic second, bool firstOnLeft, Arithmetic third, bool secondOnLeft>
void chained(const BatchCode&, const Instruction& in, double* const* results, const double* const* inputs, int lanes,
             const EvalContext&) {
  const int n = lanesOf<N>(lanes);
  const double* a = inputs[in.a];
  const double* b = inputs[in.b];
  const double* c = inputs[in.c];
  const double* d = inputs[in.d];
  double* r = results[in.result];
  auto all = [](auto w, auto x, auto y, auto z) {
    const auto inner = apply<first>(w, x);
    decltype(inner) middle = firstOnLeft ? apply<second>(inner, y) : apply<second>(y, inner);
    return secondOnLeft ? apply<third>(middle, z) : apply<third>(z, middle);
  };
  int l = 0;
  for (; l + 2 <= n; l += 2) store(r + l, all(load(a + l), load(b + l), load(c + l), load(d + l)));
  for (; l < n; ++l) r[l] = all(a[l], b[l], c[l], d[l]);
}

// The other operations of two operands, as run() computes them.
template <OpCode op>
double scalar(double a, double b) {
  if constexpr (op == OpCode::Mod) return std::fmod(a, b);
  if constexpr (op == OpCode::Pow) return std::pow(a, b);
  if constexpr (op == OpCode::Less) return a < b;
  if constexpr (op == OpCode::LessEqual) return a <= b;
  if constexpr (op == OpCode::Greater) return a > b;
  if constexpr (op == OpCode::GreaterEqual) return a >= b;
  if constexpr (op == OpCode::Equal) return a == b;
  if constexpr (op == OpCode::NotEqual) return a != b;
  if constexpr (op == OpCode::Neg) return -a;
  if constexpr (op == OpCode::Not) return a == 0.0 ? 1.0 : 0.0;
  if constexpr (op == OpCode::Truth) return a != 0.0 ? 1.0 : 0.0;
  if constexpr (op == OpCode::Load) return a;  // a copy
}

template <int N, OpCode op>
void other(const BatchCode&, const Instruction& in, double* const* results, const double* const* inputs, int lanes,
           const EvalContext&) {
  const int n = lanesOf<N>(lanes);
  const double* a = inputs[in.a];
  const double* b = inputs[in.b];  // the unary operations read their operand twice
  double* r = results[in.result];
  for (int l = 0; l < n; ++l) r[l] = scalar<op>(a[l], b[l]);
}

template <int N>
void ancestor(const BatchCode&, const Instruction& in, double* const* results, const double* const*, int lanes,
              const EvalContext& context) {
  const int n = lanesOf<N>(lanes);
  const double value = context.ancestors[in.operand];
  double* r = results[in.result];
  for (int l = 0; l < n; ++l) r[l] = value;
}

template <int N>
void builtin(const BatchCode& code, const Instruction& in, double* const* results, const double* const* inputs,
             int lanes, const EvalContext& context) {
  const int n = lanesOf<N>(lanes);
  const BuiltinFn fn = builtinFunctions()[in.operand].fn;
  const Place* places = code.argumentPlaces().data() + in.argumentsAt;
  double* r = results[in.result];
  for (int l = 0; l < n; ++l) {
    double arguments[CompiledExpression::kMaxStack];
    for (int a = 0; a < in.count; ++a) arguments[a] = inputs[places[a]][l];
    EvalEnvironment environment = context.environment;
    r[l] = fn(arguments, in.count, environment);
  }
}

template <int N, Arithmetic first>
Kernel fusedWith(Arithmetic second, bool resultFirst) {
  switch (second) {
    case Arithmetic::Add:
      return resultFirst ? fused<N, first, Arithmetic::Add, true> : fused<N, first, Arithmetic::Add, false>;
    case Arithmetic::Sub:
      return resultFirst ? fused<N, first, Arithmetic::Sub, true> : fused<N, first, Arithmetic::Sub, false>;
    case Arithmetic::Mul:
      return resultFirst ? fused<N, first, Arithmetic::Mul, true> : fused<N, first, Arithmetic::Mul, false>;
    case Arithmetic::Div:
      return resultFirst ? fused<N, first, Arithmetic::Div, true> : fused<N, first, Arithmetic::Div, false>;
  }
  return nullptr;
}

template <int N>
Kernel fusedKernel(Arithmetic first, Arithmetic second, bool resultFirst) {
  switch (first) {
    case Arithmetic::Add:
      return fusedWith<N, Arithmetic::Add>(second, resultFirst);
    case Arithmetic::Sub:
      return fusedWith<N, Arithmetic::Sub>(second, resultFirst);
    case Arithmetic::Mul:
      return fusedWith<N, Arithmetic::Mul>(second, resultFirst);
    case Arithmetic::Div:
      return fusedWith<N, Arithmetic::Div>(second, resultFirst);
  }
  return nullptr;
}

template <int N, Arithmetic first, Arithmetic second, bool firstOnLeft>
Kernel chainedWith(Arithmetic third, bool secondOnLeft) {
  switch (third) {
#define ONTOGEN_BATCH_THIRD(OP)                                                        \
  case Arithmetic::OP:                                                                 \
    return secondOnLeft ? chained<N, first, second, firstOnLeft, Arithmetic::OP, true> \
                        : chained<N, first, second, firstOnLeft, Arithmetic::OP, false>;
    ONTOGEN_BATCH_THIRD(Add)
    ONTOGEN_BATCH_THIRD(Sub)
    ONTOGEN_BATCH_THIRD(Mul)
    ONTOGEN_BATCH_THIRD(Div)
#undef ONTOGEN_BATCH_THIRD
  }
  return nullptr;
}

template <int N, Arithmetic first>
Kernel chainedFrom(Arithmetic second, bool firstOnLeft, Arithmetic third, bool secondOnLeft) {
  switch (second) {
#define ONTOGEN_BATCH_SECOND(OP)                                                          \
  case Arithmetic::OP:                                                                    \
    return firstOnLeft ? chainedWith<N, first, Arithmetic::OP, true>(third, secondOnLeft) \
                       : chainedWith<N, first, Arithmetic::OP, false>(third, secondOnLeft);
    ONTOGEN_BATCH_SECOND(Add)
    ONTOGEN_BATCH_SECOND(Sub)
    ONTOGEN_BATCH_SECOND(Mul)
    ONTOGEN_BATCH_SECOND(Div)
#undef ONTOGEN_BATCH_SECOND
  }
  return nullptr;
}

template <int N>
Kernel chainedKernel(Arithmetic first, Arithmetic second, bool firstOnLeft, Arithmetic third, bool secondOnLeft) {
  switch (first) {
    case Arithmetic::Add:
      return chainedFrom<N, Arithmetic::Add>(second, firstOnLeft, third, secondOnLeft);
    case Arithmetic::Sub:
      return chainedFrom<N, Arithmetic::Sub>(second, firstOnLeft, third, secondOnLeft);
    case Arithmetic::Mul:
      return chainedFrom<N, Arithmetic::Mul>(second, firstOnLeft, third, secondOnLeft);
    case Arithmetic::Div:
      return chainedFrom<N, Arithmetic::Div>(second, firstOnLeft, third, secondOnLeft);
  }
  return nullptr;
}

// The kernel of one bytecode instruction (Load standing for a copy of its operand).
template <int N>
Kernel kernelOf(OpCode op) {
  switch (op) {
    case OpCode::Add:
      return binary<N, Arithmetic::Add>;
    case OpCode::Sub:
      return binary<N, Arithmetic::Sub>;
    case OpCode::Mul:
      return binary<N, Arithmetic::Mul>;
    case OpCode::Div:
      return binary<N, Arithmetic::Div>;
#define ONTOGEN_BATCH_OTHER(OP) \
  case OpCode::OP:              \
    return other<N, OpCode::OP>;
      ONTOGEN_BATCH_OTHER(Mod)
      ONTOGEN_BATCH_OTHER(Pow)
      ONTOGEN_BATCH_OTHER(Less)
      ONTOGEN_BATCH_OTHER(LessEqual)
      ONTOGEN_BATCH_OTHER(Greater)
      ONTOGEN_BATCH_OTHER(GreaterEqual)
      ONTOGEN_BATCH_OTHER(Equal)
      ONTOGEN_BATCH_OTHER(NotEqual)
      ONTOGEN_BATCH_OTHER(Neg)
      ONTOGEN_BATCH_OTHER(Not)
      ONTOGEN_BATCH_OTHER(Truth)
      ONTOGEN_BATCH_OTHER(Load)
#undef ONTOGEN_BATCH_OTHER
    case OpCode::Ancestor:
      return ancestor<N>;
    case OpCode::CallBuiltin:
      return builtin<N>;
    default:
      return nullptr;
  }
}

// An instruction before fusion.
struct Step {
  OpCode op;
  Place result, a, b;
  uint8_t count = 0;
  int32_t operand = 0;
  uint32_t argumentsAt = 0;
};

}  // namespace

bool BatchCode::compile(const CompiledExpression& expression, int slots, int aggregates) {
  *this = BatchCode{};
  if (!expression.batchable(slots)) return false;
  const std::vector<Bytecode>& bytecode = expression.code_;
  // The deepest stack, and the constants, for the table's layout.
  int depth = 0, deepest = 0, constants = 0;
  for (const Bytecode& in : bytecode) {
    switch (in.op) {
      case OpCode::Const:
        ++constants;
        [[fallthrough]];
      case OpCode::Load:
      case OpCode::Ancestor:
        ++depth;
        break;
      case OpCode::Aggregate:
        if (in.operand < 0 || in.operand >= aggregates) return false;
        ++depth;
        break;
      case OpCode::Neg:
      case OpCode::Not:
      case OpCode::Truth:
        break;
      case OpCode::CallBuiltin:
        depth -= in.count - 1;
        break;
      default:
        --depth;
        break;
    }
    deepest = std::max(deepest, depth);
  }
  if (deepest > CompiledExpression::kMaxStack || deepest + 1 + slots + aggregates + constants > kMaxPlaces)
    return false;
  results_ = deepest;
  slots_ = slots;
  aggregates_ = aggregates;
  const Place output = static_cast<Place>(deepest);
  const Place firstSlot = output + 1;
  const Place firstAggregate = static_cast<Place>(firstSlot + slots);
  const Place firstConstant = static_cast<Place>(firstAggregate + aggregates);

  // The stack of places: a value pushed is read where it is, a result goes to the array
  // of its stack position.
  std::vector<Place> stack;
  std::vector<Step> steps;
  for (const Bytecode& in : bytecode) {
    const Place top = static_cast<Place>(stack.size());
    switch (in.op) {
      case OpCode::Const:
        stack.push_back(static_cast<Place>(firstConstant + constants_.size() / kLanes));
        constants_.insert(constants_.end(), kLanes, expression.constants_[static_cast<size_t>(in.operand)]);
        break;
      case OpCode::Load:
        stack.push_back(static_cast<Place>(firstSlot + in.operand));
        break;
      case OpCode::Aggregate:
        stack.push_back(static_cast<Place>(firstAggregate + in.operand));
        break;
      case OpCode::Ancestor:
        steps.push_back({in.op, top, 0, 0, 0, in.operand, 0});
        stack.push_back(top);
        break;
      case OpCode::Neg:
      case OpCode::Not:
      case OpCode::Truth: {
        const Place at = static_cast<Place>(top - 1);
        steps.push_back({in.op, at, stack[at], stack[at]});
        stack[at] = at;
        break;
      }
      case OpCode::CallBuiltin: {
        const Place at = static_cast<Place>(top - in.count);
        const uint32_t argumentsAt = static_cast<uint32_t>(arguments_.size());
        arguments_.insert(arguments_.end(), stack.begin() + at, stack.end());
        steps.push_back({in.op, at, 0, 0, in.count, in.operand, argumentsAt});
        stack.resize(at);
        stack.push_back(at);
        break;
      }
      default: {  // an operation of two operands
        const Place at = static_cast<Place>(top - 2);
        steps.push_back({in.op, at, stack[at], stack[at + 1u]});
        stack.resize(at);
        stack.push_back(at);
        break;
      }
    }
  }
  // The last result goes straight to the output; a lone operand is copied there.
  if (stack[0] == 0)
    steps.back().result = output;
  else
    steps.push_back({OpCode::Load, output, stack[0], stack[0]});

  for (size_t i = 0; i < steps.size(); ++i) {
    const Step& step = steps[i];
    Instruction in;
    in.result = step.result;
    in.a = step.a;
    in.b = step.b;
    in.count = step.count;
    in.operand = step.operand;
    in.argumentsAt = step.argumentsAt;
    // The next operation reads this one's result (a result's array is read once, by the
    // operation that pops it): fused, the result stays in registers.
    auto feeds = [&](const Step& from, const Step& into, bool& onLeft, Place& other) {
      Arithmetic kind;
      if (from.result >= output || !arithmetic(from.op, kind) || !arithmetic(into.op, kind)) return false;
      if ((into.a == from.result) == (into.b == from.result)) return false;
      onLeft = into.a == from.result;
      other = onLeft ? into.b : into.a;
      return true;
    };
    Arithmetic first, second, third;
    bool firstOnLeft, secondOnLeft;
    if (i + 1 < steps.size() && feeds(step, steps[i + 1], firstOnLeft, in.c)) {
      arithmetic(step.op, first);
      arithmetic(steps[i + 1].op, second);
      if (i + 2 < steps.size() && feeds(steps[i + 1], steps[i + 2], secondOnLeft, in.d) && in.d != step.result) {
        arithmetic(steps[i + 2].op, third);
        in.result = steps[i + 2].result;
        in.full = chainedKernel<kLanes>(first, second, firstOnLeft, third, secondOnLeft);
        in.partial = chainedKernel<0>(first, second, firstOnLeft, third, secondOnLeft);
        code_.push_back(in);
        i += 2;
        continue;
      }
      in.result = steps[i + 1].result;
      in.full = fusedKernel<kLanes>(first, second, firstOnLeft);
      in.partial = fusedKernel<0>(first, second, firstOnLeft);
      code_.push_back(in);
      ++i;
      continue;
    }
    in.full = kernelOf<kLanes>(step.op);
    in.partial = kernelOf<0>(step.op);
    code_.push_back(in);
  }
  return true;
}

void BatchCode::evaluate(int lanes, const double* const* slots, const double* const* aggregates,
                         const EvalContext& context, double* out) const {
  alignas(32) double stack[CompiledExpression::kMaxStack][kLanes];
  double* results[CompiledExpression::kMaxStack + 1];
  const double* inputs[kMaxPlaces];
  int place = 0;
  for (int r = 0; r < results_; ++r) inputs[place++] = results[r] = stack[r];
  inputs[place++] = results[results_] = out;
  for (int s = 0; s < slots_; ++s) inputs[place++] = slots[s];
  for (int q = 0; q < aggregates_; ++q) inputs[place++] = aggregates[q];
  for (size_t c = 0; c < constants_.size(); c += kLanes) inputs[place++] = constants_.data() + c;
  if (lanes == kLanes)
    for (const Instruction& in : code_) in.full(*this, in, results, inputs, lanes, context);
  else
    for (const Instruction& in : code_) in.partial(*this, in, results, inputs, lanes, context);
}

}  // namespace ontogen
