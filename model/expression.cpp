#include "model/expression.h"

#include <cmath>

namespace ontogen {

CompiledExpression CompiledExpression::constant(double value) {
  ExpressionBuilder builder;
  builder.emitConst(value);
  return builder.finish();
}

std::vector<int> CompiledExpression::calledFunctions() const {
  std::vector<int> called;
  for (const Bytecode& in : code_)
    if (in.op == OpCode::CallFunction) called.push_back(in.operand);
  return called;
}

bool CompiledExpression::batchable(int slots) const {
  if (stochastic_ || code_.empty()) return false;
  for (const Bytecode& in : code_) {
    if (in.op == OpCode::Jump || in.op == OpCode::JumpIfFalse || in.op == OpCode::CallFunction) return false;
    if (in.op == OpCode::Load && (in.operand < 0 || in.operand >= slots)) return false;
    if (in.op == OpCode::CallBuiltin && builtinFunctions()[in.operand].kind == BuiltinKind::Stochastic) return false;
  }
  return true;
}

bool CompiledExpression::asValueOperation(int slots, ValueOperation& operation) const {
  using Kind = ValueOperation::Kind;
  if (stochastic_) return false;
  auto slot = [&](const Bytecode& in) { return in.op == OpCode::Load && in.operand >= 0 && in.operand < slots; };
  if (code_.size() == 1) {
    if (code_[0].op == OpCode::Const) {
      operation = ValueOperation::make(Kind::Constant, 0, constants_[code_[0].operand]);
      return true;
    }
    if (!slot(code_[0])) return false;
    operation = ValueOperation::copy(static_cast<uint32_t>(code_[0].operand));
    return true;
  }
  if (code_.size() != 3) return false;
  // x op c, or c op x: the operands in the interpreter's order.
  const bool slotFirst = slot(code_[0]) && code_[1].op == OpCode::Const;
  const bool slotSecond = code_[0].op == OpCode::Const && slot(code_[1]);
  if (!slotFirst && !slotSecond) return false;
  Kind kind;
  switch (code_[2].op) {
    case OpCode::Add:
      kind = slotFirst ? Kind::Add : Kind::AddTo;
      break;
    case OpCode::Sub:
      kind = slotFirst ? Kind::Subtract : Kind::SubtractFrom;
      break;
    case OpCode::Mul:
      kind = slotFirst ? Kind::Multiply : Kind::MultiplyBy;
      break;
    case OpCode::Div:
      kind = slotFirst ? Kind::Divide : Kind::DivideInto;
      break;
    default:
      return false;
  }
  const Bytecode& value = slotFirst ? code_[0] : code_[1];
  const Bytecode& constant = slotFirst ? code_[1] : code_[0];
  operation = ValueOperation::make(kind, static_cast<uint32_t>(value.operand), constants_[constant.operand]);
  return true;
}

bool CompiledExpression::aggregates() const {
  for (const Bytecode& in : code_)
    if (in.op == OpCode::Aggregate) return true;
  return false;
}

void ExpressionBuilder::emitConst(double value) {
  expr_.constants_.push_back(value);
  emit(OpCode::Const, static_cast<int32_t>(expr_.constants_.size() - 1));
}

void ExpressionBuilder::emit(OpCode op, int32_t operand, uint8_t count) {
  expr_.code_.push_back({op, count, operand});
  switch (op) {
    case OpCode::Const:
    case OpCode::Load:
    case OpCode::Aggregate:
    case OpCode::Ancestor:
      ++depth_;
      break;
    case OpCode::Add:
    case OpCode::Sub:
    case OpCode::Mul:
    case OpCode::Div:
    case OpCode::Mod:
    case OpCode::Pow:
    case OpCode::Less:
    case OpCode::LessEqual:
    case OpCode::Greater:
    case OpCode::GreaterEqual:
    case OpCode::Equal:
    case OpCode::NotEqual:
    case OpCode::JumpIfFalse:
      --depth_;
      break;
    case OpCode::CallBuiltin:
    case OpCode::CallFunction:
      depth_ -= count - 1;
      break;
    default:
      break;
  }
  if (depth_ > maxDepth_) maxDepth_ = depth_;
}

double CompiledExpression::run(const EvalContext& context) const {
  double stack[kMaxStack];
  int top = -1;
  const Bytecode* code = code_.data();
  const size_t size = code_.size();
  for (size_t pc = 0; pc < size; ++pc) {
    const Bytecode& in = code[pc];
    switch (in.op) {
      case OpCode::Const:
        stack[++top] = constants_[in.operand];
        break;
      case OpCode::Load:
        stack[++top] = context.frame[in.operand];
        break;
      case OpCode::Neg:
        stack[top] = -stack[top];
        break;
      case OpCode::Not:
        stack[top] = stack[top] == 0.0 ? 1.0 : 0.0;
        break;
      case OpCode::Truth:
        stack[top] = stack[top] != 0.0 ? 1.0 : 0.0;
        break;
      case OpCode::Add:
        --top;
        stack[top] += stack[top + 1];
        break;
      case OpCode::Sub:
        --top;
        stack[top] -= stack[top + 1];
        break;
      case OpCode::Mul:
        --top;
        stack[top] *= stack[top + 1];
        break;
      case OpCode::Div:
        --top;
        stack[top] /= stack[top + 1];
        break;
      case OpCode::Mod:
        --top;
        stack[top] = std::fmod(stack[top], stack[top + 1]);
        break;
      case OpCode::Pow:
        --top;
        stack[top] = std::pow(stack[top], stack[top + 1]);
        break;
      case OpCode::Less:
        --top;
        stack[top] = stack[top] < stack[top + 1];
        break;
      case OpCode::LessEqual:
        --top;
        stack[top] = stack[top] <= stack[top + 1];
        break;
      case OpCode::Greater:
        --top;
        stack[top] = stack[top] > stack[top + 1];
        break;
      case OpCode::GreaterEqual:
        --top;
        stack[top] = stack[top] >= stack[top + 1];
        break;
      case OpCode::Equal:
        --top;
        stack[top] = stack[top] == stack[top + 1];
        break;
      case OpCode::NotEqual:
        --top;
        stack[top] = stack[top] != stack[top + 1];
        break;
      case OpCode::JumpIfFalse:
        if (stack[top--] == 0.0) pc = static_cast<size_t>(in.operand) - 1;
        break;
      case OpCode::Jump:
        pc = static_cast<size_t>(in.operand) - 1;
        break;
      case OpCode::CallBuiltin: {
        top -= in.count - 1;
        EvalEnvironment environment = context.environment;
        stack[top] = builtinFunctions()[in.operand].fn(&stack[top], in.count, environment);
        break;
      }
      case OpCode::Aggregate:
        stack[++top] = context.neighbours->aggregate(in.operand);
        break;
      case OpCode::Ancestor:
        stack[++top] = context.ancestors[in.operand];
        break;
      case OpCode::CallFunction: {
        top -= in.count - 1;
        EvalContext inner = context;
        inner.frame = &stack[top];
        stack[top] = context.functions->bodies[in.operand].evaluate(inner);
        break;
      }
    }
  }
  return stack[top];
}

}  // namespace ontogen
