#pragma once
// Compiled expressions: a compact stack bytecode over doubles. Names are resolved at
// compile time to slots of an evaluation frame (the cell's state, its age, context
// neighbours...), constants are folded, and nothing is parsed while a model runs.

#include <cstdint>
#include <span>
#include <vector>

#include "model/builtins.h"
#include "pools/value_operation.h"

namespace ontogen {

enum class OpCode : uint8_t {
  Const,  ///< push constants[operand]
  Load,   ///< push frame[operand]
  Neg,
  Not,
  Add,
  Sub,
  Mul,
  Div,
  Mod,
  Pow,
  Less,
  LessEqual,
  Greater,
  GreaterEqual,
  Equal,
  NotEqual,
  JumpIfFalse,   ///< pop; jump to operand if 0 (the result of && / || / if)
  Jump,          ///< jump to operand
  Truth,         ///< replace top with 0 or 1
  CallBuiltin,   ///< call builtinFunctions()[operand] with `count` arguments
  CallFunction,  ///< call the program's function[operand] with `count` arguments
  Aggregate,     ///< push the neighbour aggregate number `operand` of the rule being evaluated
  Ancestor,      ///< push the enclosing systems' value number `operand` (`parent.x`, `root.age`)
};

struct Bytecode {
  OpCode op;
  uint8_t count = 0;
  int32_t operand = 0;
};

class CompiledExpression;

/// The program's user functions (development functions), callable from expressions.
struct FunctionTable {
  std::span<const CompiledExpression> bodies;
};

/// Answers a rule's neighbour aggregates (`count(A)`, `sum(x)`, ...) for the cell being
/// evaluated; the engine implements it for each pool kind.
class NeighbourAggregates {
 public:
  virtual double aggregate(int query) const = 0;

 protected:
  ~NeighbourAggregates() = default;
};

/// What an evaluation reads besides the frame.
struct EvalContext {
  const double* frame = nullptr;
  EvalEnvironment environment;
  const FunctionTable* functions = nullptr;
  const NeighbourAggregates* neighbours = nullptr;  ///< set where the expression may aggregate
  /// Values of Program::ancestorRefs for the system the cell lives in (World::ancestorValues).
  const double* ancestors = nullptr;
};

class CompiledExpression {
 public:
  CompiledExpression() = default;
  static CompiledExpression constant(double value);

  /// Evaluates against a frame. Expressions are checked at compile time, so this cannot
  /// fail; arithmetic follows IEEE rules (1/0 is inf).
  double evaluate(const EvalContext& context) const {
    if (code_.size() == 1) {
      const Bytecode& only = code_[0];
      if (only.op == OpCode::Const) return constants_[only.operand];
      if (only.op == OpCode::Load) return context.frame[only.operand];
    }
    return run(context);
  }

  bool empty() const { return code_.empty(); }
  bool isConstant() const { return code_.size() == 1 && code_[0].op == OpCode::Const; }
  double constantValue() const { return constants_[code_[0].operand]; }
  /// True if evaluation may draw random numbers (directly or through functions).
  bool isStochastic() const { return stochastic_; }
  size_t instructionCount() const { return code_.size(); }
  /// Indices of the user functions this expression calls (for recursion checks).
  std::vector<int> calledFunctions() const;
  /// True if the expression reads neighbour aggregates.
  bool aggregates() const;

  /// Deepest stack the code needs; bounded by kMaxStack at compile time.
  static constexpr int kMaxStack = 64;  // nesting deeper than 64 operands is not a program people write

  /// Whether evaluateBatch can evaluate it: straight-line code (no `&&`, `||` or `if`),
  /// no user function, no random draw, and frame slots below `slots` only.
  bool batchable(int slots) const;
  /// Evaluates it for `lanes` (at most kBatchLanes) cells at once, each lane to the bits
  /// evaluate() gives: `load(lane, slot)` reads a frame slot of a lane's cell and
  /// `aggregate(lane, query)` its neighbour aggregate; out[lane] gets the value. One pass
  /// over the code for all lanes instead of one per cell (model/expression_batch.h).
  /// The expression as one operation on frame slot s below `slots` and a constant (`x`,
  /// `c`, `x + c`, `c / x` ...: pools/value_operation.h), whose apply() gives the bits
  /// evaluate() gives; false for any other expression.
  bool asValueOperation(int slots, ValueOperation& operation) const;
  template <typename Load, typename Aggregate>
  void evaluateBatch(int lanes, Load&& load, Aggregate&& aggregate, const EvalContext& context, double* out) const;
  static constexpr int kBatchLanes = 32;

 private:
  friend class ExpressionBuilder;
  friend class BatchCode;
  double run(const EvalContext& context) const;

  std::vector<Bytecode> code_;
  std::vector<double> constants_;
  bool stochastic_ = false;
};

/// Emits code for one expression; the expression compiler drives it.
class ExpressionBuilder {
 public:
  void emit(OpCode op, int32_t operand = 0, uint8_t count = 0);
  void emitConst(double value);
  size_t position() const { return expr_.code_.size(); }
  void patchJump(size_t at, size_t target) { expr_.code_[at].operand = static_cast<int32_t>(target); }
  void markStochastic() { expr_.stochastic_ = true; }
  /// Corrects the tracked depth where control flow joins (both branches push one value).
  void adjustDepth(int delta) { depth_ += delta; }
  /// Stack depth after the code so far (tracked as instructions are emitted).
  int depth() const { return depth_; }
  int maxDepth() const { return maxDepth_; }
  CompiledExpression finish() { return std::move(expr_); }

 private:
  CompiledExpression expr_;
  int depth_ = 0;
  int maxDepth_ = 0;
};

}  // namespace ontogen
