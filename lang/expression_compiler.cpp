#include "lang/expression_compiler.h"

#include <cmath>

namespace ontogen {
namespace {

using ast::Expr;

class ExpressionCompiler {
 public:
  ExpressionCompiler(const NameLookup& names, DiagnosticSink& sink) : names_(names), sink_(sink) {}

  CompiledExpression run(const Expr& expr) {
    int errorsBefore = sink_.errorsReported();
    check(expr);
    if (sink_.errorsReported() > errorsBefore) return {};
    emit(expr);
    if (builder_.maxDepth() > CompiledExpression::kMaxStack) {
      sink_.error(expr.span, "expression is too deeply nested (more than " +
                                 std::to_string(CompiledExpression::kMaxStack) + " pending operands)");
      return {};
    }
    return builder_.finish();
  }

 private:
  // Pass 1: report every unknown name and bad call in the expression.
  void check(const Expr& expr) {
    switch (expr.kind) {
      case Expr::Kind::Number:
        return;
      case Expr::Kind::Name: {
        if (names_.slot && names_.slot(expr.name) >= 0) return;
        if (names_.constant && names_.constant(expr.name)) return;
        if (statusValue(expr.name)) return;
        if (readsStatus(expr)) return;
        std::string message = "unknown name '" + expr.name + "'";
        if (names_.unknownHint) {
          std::string hint = names_.unknownHint(expr.name);
          if (!hint.empty()) message += "; " + hint;
        }
        sink_.error(expr.span, message);
        return;
      }
      case Expr::Kind::Member: {
        std::string path = memberPath(expr);
        if (names_.slot && !path.empty() && names_.slot(path) >= 0) return;
        std::string base = path.substr(0, path.find('.'));
        if ((base == "parent" || base == "root") && names_.ancestor) {
          names_.ancestor(path, expr.span);
          return;
        }
        if (base == "me")
          sink_.error(expr.span, "'" + path +
                                     "' is not internal state of a cell (known: me.age, me.id, me.x, "
                                     "me.y, me.z)");
        else if (base == "parent" || base == "root")
          sink_.error(expr.span, "'" + path +
                                     "' reads an enclosing system's state, which rules and interpretation "
                                     "blocks can do, not constants or axioms");
        else
          sink_.error(expr.span, "unknown name '" + path + "' (a member is read from 'me', 'parent' or 'root')");
        return;
      }
      case Expr::Kind::Unary:
      case Expr::Kind::Binary:
        for (const auto& arg : expr.args) check(*arg);
        return;
      case Expr::Kind::Call: {
        if (isAggregateCall(expr)) {
          if (!names_.aggregate)
            sink_.error(expr.span, "'" + expr.name + "(...)' aggregates over neighbours and is read in rules only");
          else
            names_.aggregate(expr, sink_);
          return;
        }
        for (const auto& arg : expr.args) check(*arg);
        int count = static_cast<int>(expr.args.size());
        if (expr.name == "if") {
          if (count != 3)
            sink_.error(expr.span,
                        "'if' takes 3 arguments (if(condition, then, else)), given " + std::to_string(count));
          return;
        }
        if (names_.function) {
          int index = names_.function(expr.name);
          if (index >= 0) {
            int arity = names_.functionArity(index);
            if (arity != count)
              sink_.error(expr.span, "'" + expr.name + "' takes " + std::to_string(arity) + " argument" +
                                         (arity == 1 ? "" : "s") + ", given " + std::to_string(count));
            return;
          }
        }
        const BuiltinFunction* builtin = findBuiltin(expr.name);
        if (!builtin) {
          sink_.error(expr.span, "unknown function '" + expr.name + "'");
          return;
        }
        if (count < builtin->minArity || (builtin->maxArity >= 0 && count > builtin->maxArity)) {
          std::string expected = builtin->minArity == builtin->maxArity ? std::to_string(builtin->minArity)
                                 : builtin->maxArity < 0
                                     ? "at least " + std::to_string(builtin->minArity)
                                     : std::to_string(builtin->minArity) + " to " + std::to_string(builtin->maxArity);
          sink_.error(expr.span, "'" + expr.name + "' takes " + expected + " argument" + (expected == "1" ? "" : "s") +
                                     " (" + std::string(builtin->signature) + "), given " + std::to_string(count));
        }
        return;
      }
    }
  }

  // `status` (paper 002's internal status) where the frame has an age and no user
  // variable takes the name.
  bool readsStatus(const Expr& expr) const {
    return expr.name == "status" && names_.slot && names_.slot("status") < 0 && names_.slot("age") >= 0;
  }

  // The status names, below every user name and #define: dormant 0, birth 1, alive 2, dead 3.
  static std::optional<double> statusValue(std::string_view name) {
    if (name == "dormant") return 0.0;
    if (name == "birth") return 1.0;
    if (name == "alive") return kStatusAlive;
    if (name == "dead") return 3.0;
    return std::nullopt;
  }
  static constexpr double kStatusAlive = 2;

  // The value of a subtree that depends on no frame slot and draws no random number.
  std::optional<double> fold(const Expr& expr) {
    switch (expr.kind) {
      case Expr::Kind::Number:
        return expr.number;
      case Expr::Kind::Name: {
        if (names_.slot && names_.slot(expr.name) >= 0) return std::nullopt;
        if (auto value = names_.constant(expr.name)) return value;
        return statusValue(expr.name);
      }
      case Expr::Kind::Member:
        return std::nullopt;
      case Expr::Kind::Unary: {
        auto value = fold(*expr.args[0]);
        if (!value) return std::nullopt;
        return expr.op == TokenKind::Minus ? -*value : (*value == 0.0 ? 1.0 : 0.0);
      }
      case Expr::Kind::Binary: {
        auto left = fold(*expr.args[0]);
        if (!left) return std::nullopt;
        if (expr.op == TokenKind::AmpAmp && *left == 0.0) return 0.0;
        if (expr.op == TokenKind::PipePipe && *left != 0.0) return 1.0;
        auto right = fold(*expr.args[1]);
        if (!right) return std::nullopt;
        return binaryValue(expr.op, *left, *right);
      }
      case Expr::Kind::Call: {
        if (isAggregateCall(expr)) return std::nullopt;
        if (expr.name == "if") {
          auto condition = fold(*expr.args[0]);
          if (!condition) return std::nullopt;
          return fold(*expr.args[*condition != 0.0 ? 1 : 2]);
        }
        if (names_.function && names_.function(expr.name) >= 0) return std::nullopt;
        const BuiltinFunction* builtin = findBuiltin(expr.name);
        if (!builtin || builtin->kind != BuiltinKind::Pure) return std::nullopt;
        std::vector<double> args;
        for (const auto& arg : expr.args) {
          auto value = fold(*arg);
          if (!value) return std::nullopt;
          args.push_back(*value);
        }
        EvalEnvironment environment;
        return builtin->fn(args.data(), static_cast<int>(args.size()), environment);
      }
    }
    return std::nullopt;
  }

  static double binaryValue(TokenKind op, double a, double b) {
    switch (op) {
      case TokenKind::Plus:
        return a + b;
      case TokenKind::Minus:
        return a - b;
      case TokenKind::Star:
        return a * b;
      case TokenKind::Slash:
        return a / b;
      case TokenKind::Percent:
        return std::fmod(a, b);
      case TokenKind::Caret:
        return std::pow(a, b);
      case TokenKind::Less:
        return a < b;
      case TokenKind::LessEqual:
        return a <= b;
      case TokenKind::Greater:
        return a > b;
      case TokenKind::GreaterEqual:
        return a >= b;
      case TokenKind::EqualEqual:
        return a == b;
      case TokenKind::BangEqual:
        return a != b;
      case TokenKind::AmpAmp:
        return (a != 0.0 && b != 0.0) ? 1.0 : 0.0;
      case TokenKind::PipePipe:
        return (a != 0.0 || b != 0.0) ? 1.0 : 0.0;
      default:
        return 0.0;
    }
  }

  static OpCode opcodeOf(TokenKind op) {
    switch (op) {
      case TokenKind::Plus:
        return OpCode::Add;
      case TokenKind::Minus:
        return OpCode::Sub;
      case TokenKind::Star:
        return OpCode::Mul;
      case TokenKind::Slash:
        return OpCode::Div;
      case TokenKind::Percent:
        return OpCode::Mod;
      case TokenKind::Caret:
        return OpCode::Pow;
      case TokenKind::Less:
        return OpCode::Less;
      case TokenKind::LessEqual:
        return OpCode::LessEqual;
      case TokenKind::Greater:
        return OpCode::Greater;
      case TokenKind::GreaterEqual:
        return OpCode::GreaterEqual;
      case TokenKind::EqualEqual:
        return OpCode::Equal;
      case TokenKind::BangEqual:
        return OpCode::NotEqual;
      default:
        return OpCode::Add;
    }
  }

  // Pass 2: emit code, folding constant subtrees.
  void emit(const Expr& expr) {
    if (auto value = fold(expr)) {
      builder_.emitConst(*value);
      return;
    }
    switch (expr.kind) {
      case Expr::Kind::Number:
        builder_.emitConst(expr.number);
        return;
      case Expr::Kind::Name:
        if (readsStatus(expr)) {
          // status = alive - (age <= 0): a cell is in its birth instant until it ages.
          builder_.emitConst(kStatusAlive);
          builder_.emit(OpCode::Load, names_.slot("age"));
          builder_.emitConst(0);
          builder_.emit(OpCode::LessEqual);
          builder_.emit(OpCode::Sub);
          return;
        }
        builder_.emit(OpCode::Load, names_.slot(expr.name));
        return;
      case Expr::Kind::Member: {
        const std::string path = memberPath(expr);
        const int slot = names_.slot ? names_.slot(path) : -1;
        if (slot >= 0)
          builder_.emit(OpCode::Load, slot);
        else
          builder_.emit(OpCode::Ancestor, names_.ancestor(path, expr.span));
        return;
      }
      case Expr::Kind::Unary:
        emit(*expr.args[0]);
        builder_.emit(expr.op == TokenKind::Minus ? OpCode::Neg : OpCode::Not);
        return;
      case Expr::Kind::Binary:
        if (expr.op == TokenKind::AmpAmp || expr.op == TokenKind::PipePipe) {
          emitShortCircuit(expr);
          return;
        }
        emit(*expr.args[0]);
        emit(*expr.args[1]);
        builder_.emit(opcodeOf(expr.op));
        return;
      case Expr::Kind::Call:
        emitCall(expr);
        return;
    }
  }

  // a && b:  a; JumpIfFalse F; b; Truth; Jump E; F: Const 0; E:
  // a || b:  a; Not; JumpIfFalse T; b; Truth; Jump E; T: Const 1; E:
  void emitShortCircuit(const Expr& expr) {
    bool isAnd = expr.op == TokenKind::AmpAmp;
    emit(*expr.args[0]);
    if (!isAnd) builder_.emit(OpCode::Not);
    size_t skip = builder_.position();
    builder_.emit(OpCode::JumpIfFalse);
    emit(*expr.args[1]);
    builder_.emit(OpCode::Truth);
    size_t end = builder_.position();
    builder_.emit(OpCode::Jump);
    builder_.patchJump(skip, builder_.position());
    builder_.adjustDepth(-1);  // the other branch starts from the depth before `b`
    builder_.emitConst(isAnd ? 0.0 : 1.0);
    builder_.patchJump(end, builder_.position());
  }

  void emitCall(const Expr& expr) {
    if (isAggregateCall(expr)) {
      builder_.emit(OpCode::Aggregate, names_.aggregate(expr, sink_));
      return;
    }
    if (expr.name == "if") {
      emit(*expr.args[0]);
      size_t toElse = builder_.position();
      builder_.emit(OpCode::JumpIfFalse);
      emit(*expr.args[1]);
      size_t toEnd = builder_.position();
      builder_.emit(OpCode::Jump);
      builder_.patchJump(toElse, builder_.position());
      builder_.adjustDepth(-1);
      emit(*expr.args[2]);
      builder_.patchJump(toEnd, builder_.position());
      return;
    }
    for (const auto& arg : expr.args) emit(*arg);
    auto count = static_cast<uint8_t>(expr.args.size());
    if (names_.function) {
      int index = names_.function(expr.name);
      if (index >= 0) {
        builder_.emit(OpCode::CallFunction, index, count);
        builder_.markStochastic();  // conservative: the function body may draw numbers
        return;
      }
    }
    const BuiltinFunction* builtin = findBuiltin(expr.name);
    int index = static_cast<int>(builtin - builtinFunctions().data());
    if (builtin->kind == BuiltinKind::Stochastic) builder_.markStochastic();
    builder_.emit(OpCode::CallBuiltin, index, count);
  }

  const NameLookup& names_;
  DiagnosticSink& sink_;
  ExpressionBuilder builder_;
};

}  // namespace

bool isAggregateCall(const ast::Expr& call) {
  if (call.kind != Expr::Kind::Call) return false;
  const size_t count = call.args.size();
  if (call.name == "count") return count <= 1;
  if (call.name == "sum" || call.name == "mean") return count == 1;
  // min(x) / max(x) over neighbours name a variable; min(1) is the two-argument function
  // called wrongly, and gets that message.
  if (call.name == "min" || call.name == "max")
    return count == 1 && (call.args[0]->kind == Expr::Kind::Name || call.args[0]->kind == Expr::Kind::Member);
  return false;
}

std::string memberPath(const ast::Expr& member) {
  if (member.kind != Expr::Kind::Member || member.args.empty()) return "";
  const Expr& base = *member.args[0];
  if (base.kind == Expr::Kind::Name) return base.name + "." + member.name;
  std::string inner = memberPath(base);
  return inner.empty() ? "" : inner + "." + member.name;
}

CompiledExpression compileExpression(const ast::Expr& expr, const NameLookup& names, DiagnosticSink& sink) {
  return ExpressionCompiler(names, sink).run(expr);
}

std::optional<double> evaluateConstant(const ast::Expr& expr, const NameLookup& names, DiagnosticSink& sink,
                                       std::string_view what) {
  int errorsBefore = sink.errorsReported();
  CompiledExpression compiled = compileExpression(expr, names, sink);
  if (sink.errorsReported() > errorsBefore) return std::nullopt;
  if (!compiled.isConstant()) {
    sink.error(expr.span, std::string(what) + " must be a constant (numbers, #define names and pure functions)");
    return std::nullopt;
  }
  return compiled.constantValue();
}

}  // namespace ontogen
