#pragma once
// Two ways to run the bytecode of model/expression.cpp for many cells at once.
//
// CompiledExpression::evaluateBatch runs the stack code an instruction at a time over
// every lane before the next, reading frame slots and aggregates through callbacks.
//
// BatchCode is the same expression as three-address code for callers that hold each
// variable's lanes and each aggregate's lanes in arrays (a variable at a time): an
// instruction reads its operands where they are (a variable's lanes, an aggregate's, a
// constant's, an earlier result) instead of pushing copies, and an arithmetic operation
// whose result only feeds the next one is fused with it (two or three in a chain), so the
// intermediates never go to memory. Lanes run two at a time, as vectors.
//
// Either way the arithmetic of each lane is the one run() does, operation for operation
// and rounding for rounding, so each lane's value is the bits a one-cell evaluation
// gives, except for the sign and payload of a NaN: once the lanes are vectorised, which
// operand's NaN an instruction passes on is the compiler's choice (outputs write every
// NaN as null). What they save is the dispatch of every instruction per cell.

#include <cmath>
#include <cstdint>
#include <vector>

#include "model/builtins.h"
#include "model/expression.h"

namespace ontogen {

class BatchCode {
 public:
  /// Lanes an evaluation takes at most.
  static constexpr int kLanes = 64;

  /// Compiles `expression`; false (and empty) unless expression.batchable(slots) and its
  /// aggregates are numbered below `aggregates`.
  bool compile(const CompiledExpression& expression, int slots, int aggregates);
  bool empty() const { return code_.empty(); }
  /// Instructions after fusion (what an evaluation dispatches).
  size_t instructionCount() const { return code_.size(); }

  /// Evaluates the expression for `lanes` (1 .. kLanes) cells: slots[s][lane] is frame
  /// slot s of a lane's cell, aggregates[q][lane] its neighbour aggregate q, and
  /// out[lane] gets the value evaluate() gives for that cell. `out` may not be one of the
  /// inputs.
  void evaluate(int lanes, const double* const* slots, const double* const* aggregates, const EvalContext& context,
                double* out) const;

  /// Where an instruction's operand or result is: an index into an evaluation's table of
  /// lane arrays (its results first, then the output, the slots, the aggregates and the
  /// constants).
  using Place = uint16_t;
  struct Instruction;
  /// Runs one instruction over `lanes` lanes (kLanes where the kernel was made for full batches).
  using Kernel = void (*)(const BatchCode& code, const Instruction& in, double* const* results,
                          const double* const* inputs, int lanes, const EvalContext& context);
  struct Instruction {
    Kernel full = nullptr;     ///< for lanes == kLanes
    Kernel partial = nullptr;  ///< for fewer
    Place result = 0;          ///< into the writable part of the table
    Place a = 0, b = 0, c = 0, d = 0;  ///< operands; a fused pair reads a, b, c and a fused three d too
    uint8_t count = 0;         ///< a built-in's arguments
    int32_t operand = 0;       ///< a built-in's number, an ancestor's value
    uint32_t argumentsAt = 0;  ///< where a built-in's argument places start in argumentPlaces()
  };
  const std::vector<Place>& argumentPlaces() const { return arguments_; }

 private:
  std::vector<Instruction> code_;
  std::vector<Place> arguments_;
  std::vector<double> constants_;  // kLanes copies of each
  int results_ = 0;                // stack depth: the intermediate results' arrays
  int slots_ = 0, aggregates_ = 0;
};

template <typename Load, typename Aggregate>
void CompiledExpression::evaluateBatch(int lanes, Load&& load, Aggregate&& aggregate, const EvalContext& context,
                                       double* out) const {
  double stack[kMaxStack][kBatchLanes];
  int top = -1;
  for (const Bytecode& in : code_) {
    switch (in.op) {
      case OpCode::Const: {
        const double value = constants_[in.operand];
        ++top;
        for (int l = 0; l < lanes; ++l) stack[top][l] = value;
        break;
      }
      case OpCode::Load:
        ++top;
        for (int l = 0; l < lanes; ++l) stack[top][l] = load(l, in.operand);
        break;
      case OpCode::Neg:
        for (int l = 0; l < lanes; ++l) stack[top][l] = -stack[top][l];
        break;
      case OpCode::Not:
        for (int l = 0; l < lanes; ++l) stack[top][l] = stack[top][l] == 0.0 ? 1.0 : 0.0;
        break;
      case OpCode::Truth:
        for (int l = 0; l < lanes; ++l) stack[top][l] = stack[top][l] != 0.0 ? 1.0 : 0.0;
        break;
#define ONTOGEN_BATCH_BINARY(OP, EXPRESSION)                                               \
  case OpCode::OP: {                                                                       \
    --top;                                                                                 \
    double* a = stack[top];                                                                \
    const double* b = stack[top + 1];                                                      \
    for (int l = 0; l < lanes; ++l) a[l] = EXPRESSION;                                     \
    break;                                                                                 \
  }
        ONTOGEN_BATCH_BINARY(Add, a[l] + b[l])
        ONTOGEN_BATCH_BINARY(Sub, a[l] - b[l])
        ONTOGEN_BATCH_BINARY(Mul, a[l] * b[l])
        ONTOGEN_BATCH_BINARY(Div, a[l] / b[l])
        ONTOGEN_BATCH_BINARY(Mod, std::fmod(a[l], b[l]))
        ONTOGEN_BATCH_BINARY(Pow, std::pow(a[l], b[l]))
        ONTOGEN_BATCH_BINARY(Less, a[l] < b[l])
        ONTOGEN_BATCH_BINARY(LessEqual, a[l] <= b[l])
        ONTOGEN_BATCH_BINARY(Greater, a[l] > b[l])
        ONTOGEN_BATCH_BINARY(GreaterEqual, a[l] >= b[l])
        ONTOGEN_BATCH_BINARY(Equal, a[l] == b[l])
        ONTOGEN_BATCH_BINARY(NotEqual, a[l] != b[l])
#undef ONTOGEN_BATCH_BINARY
      case OpCode::CallBuiltin: {
        top -= in.count - 1;
        const BuiltinFn fn = builtinFunctions()[in.operand].fn;
        for (int l = 0; l < lanes; ++l) {
          double arguments[kMaxStack];
          for (int a = 0; a < in.count; ++a) arguments[a] = stack[top + a][l];
          EvalEnvironment environment = context.environment;
          stack[top][l] = fn(arguments, in.count, environment);
        }
        break;
      }
      case OpCode::Aggregate:
        ++top;
        for (int l = 0; l < lanes; ++l) stack[top][l] = aggregate(l, in.operand);
        break;
      case OpCode::Ancestor: {
        const double value = context.ancestors[in.operand];
        ++top;
        for (int l = 0; l < lanes; ++l) stack[top][l] = value;
        break;
      }
      case OpCode::JumpIfFalse:
      case OpCode::Jump:
      case OpCode::CallFunction:
        break;  // not batchable(): never here
    }
  }
  for (int l = 0; l < lanes; ++l) out[l] = stack[top][l];
}

}  // namespace ontogen
