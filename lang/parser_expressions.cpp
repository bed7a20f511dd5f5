// The parser of expressions (lang/parser_internal.h), C precedence, '^' a power that binds
// tighter than unary minus.

#include <algorithm>
#include <cmath>
#include <string>

#include "lang/parser_internal.h"

namespace ontogen::detail {

[[nodiscard]] Parser::Nested Parser::nest(const SourceSpan& at, std::string_view what) {
  if (nesting_ >= kMaxNesting)
    fail(at, std::string(what) + " nested too deeply (more than " + std::to_string(kMaxNesting) + " levels)");
  ++nesting_;
  return Nested{nesting_};
}

ExprPtr Parser::measured(ExprPtr node) {
  for (const ExprPtr& arg : node->args) node->height = std::max(node->height, arg->height + 1);
  if (node->height > kMaxHeight)
    fail(node->span, "expression too deep: more than " + std::to_string(kMaxHeight) +
                         " operators inside each other (split it with #define or a function)");
  return node;
}

ExprPtr Parser::binary(TokenKind op, ExprPtr left, ExprPtr right) {
  auto node = std::make_unique<Expr>();
  node->kind = Expr::Kind::Binary;
  node->op = op;
  node->span = left->span.to(right->span);
  node->args.push_back(std::move(left));
  node->args.push_back(std::move(right));
  return measured(std::move(node));
}

bool Parser::operatorAhead(std::initializer_list<TokenKind> kinds) const {
  if (atStatementEnd()) return false;
  for (TokenKind kind : kinds)
    if (check(kind)) return true;
  return false;
}

ExprPtr Parser::logicalOr() {
  ExprPtr left = logicalAnd();
  while (operatorAhead({TokenKind::PipePipe, TokenKind::Pipe})) {
    advance();
    left = binary(TokenKind::PipePipe, std::move(left), logicalAnd());
  }
  return left;
}

ExprPtr Parser::logicalAnd() {
  ExprPtr left = equality();
  while (operatorAhead({TokenKind::AmpAmp, TokenKind::Amp})) {
    advance();
    left = binary(TokenKind::AmpAmp, std::move(left), equality());
  }
  return left;
}

ExprPtr Parser::equality() {
  ExprPtr left = relational();
  for (;;) {
    if (operatorAhead({TokenKind::EqualEqual, TokenKind::BangEqual})) {
      TokenKind op = advance().kind;
      left = binary(op, std::move(left), relational());
    } else if (depth_ > 0 && check(TokenKind::Equal)) {
      fail(peek().span, "'=' assigns; compare with '=='");
    } else {
      return left;
    }
  }
}

ExprPtr Parser::relational() {
  ExprPtr left = additive();
  while (operatorAhead({TokenKind::Less, TokenKind::LessEqual, TokenKind::Greater, TokenKind::GreaterEqual})) {
    TokenKind op = advance().kind;
    left = binary(op, std::move(left), additive());
  }
  return left;
}

ExprPtr Parser::additive() {
  ExprPtr left = multiplicative();
  while (operatorAhead({TokenKind::Plus, TokenKind::Minus})) {
    TokenKind op = advance().kind;
    left = binary(op, std::move(left), multiplicative());
  }
  return left;
}

ExprPtr Parser::multiplicative() {
  ExprPtr left = unary();
  while (operatorAhead({TokenKind::Star, TokenKind::Slash, TokenKind::Percent})) {
    TokenKind op = advance().kind;
    left = binary(op, std::move(left), unary());
  }
  return left;
}

ExprPtr Parser::unary() {
  if (check(TokenKind::Minus) || check(TokenKind::Plus) || check(TokenKind::Bang)) {
    const Token& op = advance();
    Nested nested = nest(op.span, "expression");
    ExprPtr operand = unary();
    if (op.kind == TokenKind::Plus) return operand;
    auto node = std::make_unique<Expr>();
    node->kind = Expr::Kind::Unary;
    node->op = op.kind;
    node->span = op.span.to(operand->span);
    node->args.push_back(std::move(operand));
    return measured(std::move(node));
  }
  return power();
}

ExprPtr Parser::power() {
  ExprPtr base = postfix();
  if (operatorAhead({TokenKind::Caret})) {
    Nested nested = nest(advance().span, "expression");
    ExprPtr exponent = unary();  // right-associative; allows 2^-1
    return binary(TokenKind::Caret, std::move(base), std::move(exponent));
  }
  return base;
}

ExprPtr Parser::postfix() {
  ExprPtr node = primary();
  while (check(TokenKind::Dot) && !atStatementEnd()) {
    advance();
    const Token& field = expect(TokenKind::Identifier, " (a state variable after '.')");
    auto member = std::make_unique<Expr>();
    member->kind = Expr::Kind::Member;
    member->name = field.text;
    member->span = node->span.to(field.span);
    member->args.push_back(std::move(node));
    node = measured(std::move(member));
  }
  return node;
}

ExprPtr Parser::primary() {
  const Token& token = peek();
  if (token.kind == TokenKind::Number) {
    advance();
    auto node = std::make_unique<Expr>();
    node->kind = Expr::Kind::Number;
    node->number = token.number;
    node->span = token.span;
    return node;
  }
  if (token.kind == TokenKind::Identifier) {
    advance();
    auto node = std::make_unique<Expr>();
    node->name = token.text;
    node->span = token.span;
    if (check(TokenKind::LParen)) {
      advance();
      ++depth_;
      node->kind = Expr::Kind::Call;
      if (!check(TokenKind::RParen)) {
        do node->args.push_back(expression());
        while (match(TokenKind::Comma));
      }
      --depth_;
      const Token& close = expect(TokenKind::RParen, " to close the call of '" + token.text + "'");
      node->span = token.span.to(close.span);
      return measured(std::move(node));
    }
    node->kind = Expr::Kind::Name;
    return node;
  }
  if (token.kind == TokenKind::LParen) {
    advance();
    ++depth_;
    ExprPtr inner = expression();
    --depth_;
    expect(TokenKind::RParen, " to close the parenthesis");
    return inner;
  }
  failHere("an expression");
}

}  // namespace ontogen::detail
