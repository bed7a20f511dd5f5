#pragma once
// CompiledExpression::evaluateBatch: the bytecode of model/expression.cpp run for many
// cells at once, each instruction over every lane before the next. The arithmetic of each
// lane is the one run() does, operation for operation, so each lane's value is the bits
// a one-cell evaluation gives, except for the sign and payload of a NaN: once the lanes
// are vectorised, which operand's NaN an instruction passes on is the compiler's choice
// (outputs write every NaN as null). What it saves is the dispatch of every instruction
// per cell.

#include <cmath>

#include "model/builtins.h"
#include "model/expression.h"

namespace ontogen {

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
