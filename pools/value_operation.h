#pragma once
// A state value computed from the values of the module it comes from by at most one
// arithmetic operation with a constant: `x`, `c`, `x + c`, `c - x`, `x * c`, `x / c` ...
// Most parametric L-systems' arguments are of this form (A(x) -> A(x + 1) B(x * 0.5)). A
// rewrite by a table (pools/table_rewrite.h) computes them in a loop over the word's values
// instead of running the expression interpreter (model/expression.h) for each module.
//
// apply() gives the bits the interpreter gives: the same IEEE operation, with the operands
// in the same order (NaN payloads follow the first operand), and nothing a compiler may
// contract into a fused multiply-add, since each is one operation.

#include <cstdint>

namespace ontogen {

struct ValueOperation {
  enum class Kind : uint8_t {
    Constant,   // c
    Copy,       // x
    Add,        // x + c
    AddTo,      // c + x
    Subtract,   // x - c
    SubtractFrom,  // c - x
    Multiply,   // x * c
    MultiplyBy,  // c * x
    Divide,     // x / c
    DivideInto,  // c / x
  };
  Kind kind = Kind::Constant;
  uint32_t slot = 0;  // x is values[slot] of the module it comes from
  double constant = 0;
  /// x * multiplier + addend gives the same bits for the kinds of one addition or one
  /// multiplication (affine): x * 1 and x * -1 are exact, so x * 1 + c rounds once as
  /// x + c, and x * -1 + c as c - x; x * c + -0 keeps the sign of a zero product; fused
  /// into one multiply-add, each rounds once the same. A constant that is a NaN is left
  /// to apply(), whose operand order decides which NaN comes out.
  bool affine = false;
  double multiplier = 1, addend = -0.0;

  static ValueOperation make(Kind kind, uint32_t slot, double constant) {
    ValueOperation operation{kind, slot, constant};
    const bool number = constant == constant;
    switch (kind) {
      case Kind::Copy:
        operation.affine = true;
        break;
      case Kind::Add:
      case Kind::AddTo:
        operation.affine = number;
        operation.addend = constant;
        break;
      case Kind::Subtract:
        operation.affine = number;
        operation.addend = -constant;
        break;
      case Kind::SubtractFrom:
        operation.affine = number;
        operation.multiplier = -1;
        operation.addend = constant;
        break;
      case Kind::Multiply:
      case Kind::MultiplyBy:
        operation.affine = number;
        operation.multiplier = constant;
        break;
      default:
        break;
    }
    return operation;
  }
  static ValueOperation copy(uint32_t slot) { return make(Kind::Copy, slot, 0); }

  /// apply(), with one multiply-add for the affine kinds: a branch the loops predict
  /// rather than a jump through a table.
  double applyQuickly(const double* values) const {
    if (affine) [[likely]]
      return values[slot] * multiplier + addend;
    return apply(values);
  }

  double apply(const double* values) const {
    if (kind == Kind::Constant) return constant;  // the module it comes from may have no values
    const double x = values[slot];
    switch (kind) {
      case Kind::Constant:
        return constant;
      case Kind::Copy:
        return x;
      case Kind::Add:
        return x + constant;
      case Kind::AddTo:
        return constant + x;
      case Kind::Subtract:
        return x - constant;
      case Kind::SubtractFrom:
        return constant - x;
      case Kind::Multiply:
        return x * constant;
      case Kind::MultiplyBy:
        return constant * x;
      case Kind::Divide:
        return x / constant;
      case Kind::DivideInto:
        return constant / x;
    }
    return x;
  }
};

}  // namespace ontogen
