// The parser of cells (lang/parser_internal.h): a cell's items, interpretation blocks,
// rules and their contexts, assignments, successors and modules.

#include <array>
#include <cctype>
#include <string>

#include "lang/parser_internal.h"

namespace ontogen::detail {

Cell Parser::cell() {
  Cell result;
  const Token& keyword = advance();
  const Token& name = expect(TokenKind::Identifier, " (the cell's label)");
  result.name = name.text;
  result.nameSpan = name.span;
  if (check(TokenKind::LParen)) result.state = parameters();
  expect(TokenKind::LBrace, " to open the cell's body");
  while (!check(TokenKind::RBrace) && !check(TokenKind::EndOfFile)) {
    size_t before = pos_;
    try {
      cellItem(result);
    } catch (const SyntaxError&) {
      synchronize();
    }
    if (pos_ == before) advance();
  }
  const Token& close = expect(TokenKind::RBrace, " to close the cell");
  result.span = keyword.span.to(close.span);
  return result;
}

void Parser::cellItem(Cell& cell) {
  statement_ = Statement{};
  depth_ = 0;
  if (checkWord("rules")) {
    advance();
    expect(TokenKind::LBrace, " after 'rules'");
    while (!check(TokenKind::RBrace) && !check(TokenKind::EndOfFile)) {
      size_t before = pos_;
      try {
        depth_ = 0;
        cell.rules.push_back(cellRule());
      } catch (const SyntaxError&) {
        synchronize();
      }
      if (pos_ == before) advance();
    }
    expect(TokenKind::RBrace, " to close 'rules'");
    return;
  }
  if (checkWord("interpret")) {
    const Token& keyword = advance();
    const Token& name = expect(TokenKind::Identifier, " (the interpretation set, e.g. 'geometry')");
    cell.interpretations.push_back(interpretationBlock(keyword, name.text));
    return;
  }
  if (checkWord("lifetime")) {
    const Token& keyword = advance();
    cell.lifetime = expression();
    cell.lifetimeSpan = keyword.span.to(previous().span);
    endStatement();
    return;
  }
  failHere("'rules', 'interpret', 'lifetime' or '}' in the cell");
}

Interpretation Parser::interpretationBlock(const Token& keyword, const std::string& setName) {
  {
    Interpretation interpretation;
    interpretation.setName = setName;
    expect(TokenKind::LBrace, " to open the interpretation block");
    try {
      while (!check(TokenKind::RBrace) && !check(TokenKind::EndOfFile)) {
        if (match(TokenKind::Semicolon)) continue;
        if (!canStartModule()) failHere("an instruction such as 'F(1)' or '}'");
        interpretation.instructions.push_back(module(ModuleUse::Instruction));
      }
    } catch (const SyntaxError&) {
      // Skip to the block's own '}' so that the cell goes on.
      int parens = 0;
      while (!check(TokenKind::EndOfFile) && !(parens == 0 && check(TokenKind::RBrace))) {
        if (check(TokenKind::LParen)) ++parens;
        if (check(TokenKind::RParen) && parens > 0) --parens;
        if (check(TokenKind::LBrace)) break;
        advance();
      }
    }
    const Token& close = expect(TokenKind::RBrace, " to close the interpretation block");
    interpretation.span = keyword.span.to(close.span);
    return interpretation;
  }
}

void Parser::symbolInterpretation(System& system) {
  SymbolInterpretation result;
  const Token& keyword = advance();
  const Token& set = expect(TokenKind::Identifier, " (the interpretation set, e.g. 'music')");
  const Token& symbol = peek();
  if (symbol.kind != TokenKind::Identifier && !isSymbolToken(symbol.kind))
    failHere("the symbol to interpret after 'interpret " + set.text + "', as in 'interpret music F { note }'");
  advance();
  result.symbol = symbolSpelling(symbol);
  result.symbolSpan = symbol.span;
  if (check(TokenKind::LParen))
    for (const auto& param : parameters()) {
      if (param.defaultValue) fail(param.span, "the parameters of an interpreted symbol take no default values");
      result.params.push_back(param.name);
    }
  result.block = interpretationBlock(keyword, set.text);
  system.interpretations.push_back(std::move(result));
  endStatement();
}

std::vector<Parameter> Parser::parameters() {
  std::vector<Parameter> result;
  expect(TokenKind::LParen, "");
  ++depth_;
  if (!check(TokenKind::RParen)) {
    do {
      Parameter parameter;
      const Token& name = expect(TokenKind::Identifier, " (a parameter name)");
      parameter.name = name.text;
      parameter.span = name.span;
      if (match(TokenKind::Equal)) {
        parameter.defaultValue = expression();
        parameter.span = name.span.to(previous().span);
      }
      result.push_back(std::move(parameter));
    } while (match(TokenKind::Comma));
  }
  --depth_;
  expect(TokenKind::RParen, " to close the parameter list");
  return result;
}

Rule Parser::cellRule() {
  Rule rule;
  const Token& first = peek();
  if (checkWord("terminal") && peek(1).kind == TokenKind::Colon) {
    advance();
    advance();
    rule.terminal = true;
  }
  int colons = 0;
  bool contextFirst = false;
  {
    int depth = 0;
    bool seenColon = false;
    for (size_t i = pos_; i < tokens_.size(); ++i) {
      const Token& token = tokens_[i];
      if (token.kind == TokenKind::LParen) ++depth;
      if (token.kind == TokenKind::RParen) --depth;
      if (depth > 0) continue;
      if (token.kind == TokenKind::Semicolon || token.kind == TokenKind::RBrace ||
          token.kind == TokenKind::EndOfFile || token.kind == TokenKind::Arrow)
        break;
      if (token.kind == TokenKind::Colon) {
        ++colons;
        seenColon = true;
      }
      if (!seenColon && token.kind == TokenKind::Identifier && token.text == "me") contextFirst = true;
    }
    // A context of several dimensions opens with '(' and holds 'me' inside parentheses.
    if (check(TokenKind::LParen))
      for (size_t i = pos_; i < tokens_.size(); ++i) {
        const Token& token = tokens_[i];
        if (token.kind == TokenKind::Colon || token.kind == TokenKind::Semicolon || token.kind == TokenKind::Arrow ||
            token.kind == TokenKind::RBrace || token.kind == TokenKind::EndOfFile)
          break;
        if (token.kind == TokenKind::Identifier && token.text == "me") contextFirst = true;
      }
  }
  if (colons > 2)
    fail(peek().span, "a rule has at most three parts ({context} : predicate : body), found " +
                          std::to_string(colons + 1));
  if (colons >= 1 && (contextFirst || colons == 2)) {
    context(rule, /*lsystem=*/false);
    expect(TokenKind::Colon, " after the context");
    --colons;
  }
  if (colons == 1) {
    rule.predicate = expression();
    expect(TokenKind::Colon, " after the predicate");
  }
  ruleBody(rule);
  rule.span = first.span.to(previous().span);
  endStatement();
  return rule;
}

Parser::ContextGroup Parser::contextGroup() {
  ContextGroup group;
  Nested nested = nest(peek().span, "context");
  const Token& open = expect(TokenKind::LParen, "");
  ++depth_;
  if (check(TokenKind::LParen)) {
    group.isRow = false;
    while (check(TokenKind::LParen)) group.groups.push_back(contextGroup());
    for (const ContextGroup& inner : group.groups)
      if (inner.dimensions() != group.groups.front().dimensions())
        fail(inner.span, "the parts of a context have the same number of dimensions (parentheses)");
  } else {
    while (!check(TokenKind::RParen) && !atStatementEnd()) {
      if (match(TokenKind::Star)) {
        group.items.emplace_back();
        continue;
      }
      if (!canStartModule()) failHere("a module, 'me' or '*' in the context row");
      group.items.emplace_back(module(ModuleUse::Pattern));
    }
  }
  --depth_;
  const Token& close = expect(TokenKind::RParen, " to close the context's parenthesis");
  group.span = open.span.to(close.span);
  return group;
}

void Parser::placeContext(ContextGroup& group, int axis, std::array<int, 3> base, Rule& rule) {
  const size_t n = group.isRow ? group.items.size() : group.groups.size();
  int first = 0;
  if (group.holdsMe()) {
    for (size_t k = 0; k < n; ++k)
      if (group.isRow ? (group.items[k] && group.items[k]->isMe) : group.groups[k].holdsMe()) first = -static_cast<int>(k);
  } else {
    if (n % 2 == 0)
      fail(group.span, "a part of the context without 'me' is centred on it, so it needs an odd number of " +
                           std::string(group.isRow ? "items" : "parts") + " (use '*' to hold a place)");
    first = -static_cast<int>(n / 2);
  }
  for (size_t k = 0; k < n; ++k) {
    std::array<int, 3> at = base;
    at[axis] += first + static_cast<int>(k);
    if (!group.isRow) {
      placeContext(group.groups[k], axis - 1, at, rule);
      continue;
    }
    if (!group.items[k]) continue;  // `*`
    if (group.items[k]->isMe) {
      if (at != std::array<int, 3>{0, 0, 0}) fail(group.items[k]->span, "'me' appears twice in the context");
      rule.predecessor = std::move(*group.items[k]);
      continue;
    }
    rule.right.push_back(std::move(*group.items[k]));
    rule.offsets.push_back(at);
  }
}

void Parser::gridContext(Rule& rule) {
  ContextGroup top;
  top.isRow = false;
  const Token& start = peek();
  while (check(TokenKind::LParen)) top.groups.push_back(contextGroup());
  top.span = start.span.to(previous().span);
  for (const ContextGroup& inner : top.groups)
    if (inner.dimensions() != top.groups.front().dimensions())
      fail(inner.span, "the parts of a context have the same number of dimensions (parentheses)");
  rule.contextDimensions = top.dimensions();
  if (rule.contextDimensions > 3) fail(top.span, "a context has at most 3 dimensions");
  int mes = 0;
  std::function<void(const ContextGroup&)> countMe = [&](const ContextGroup& g) {
    for (const auto& item : g.items) mes += item && item->isMe;
    for (const auto& inner : g.groups) countMe(inner);
  };
  countMe(top);
  if (mes != 1)
    fail(top.span, mes == 0 ? "a context names the current cell with 'me', as in '(A) (B me C) (D)'"
                            : "'me' appears twice in the context");
  placeContext(top, rule.contextDimensions - 1, {0, 0, 0}, rule);
}

void Parser::context(Rule& rule, bool lsystem) {
  (void)lsystem;
  rule.hasContext = true;
  if (check(TokenKind::LParen)) return gridContext(rule);
  bool seenMe = false;
  while (canStartModule() || check(TokenKind::Star)) {
    Module item = check(TokenKind::Star) ? contextModule(/*lsystem=*/false) : module(ModuleUse::Pattern);
    if (item.isMe) {
      if (seenMe) fail(item.span, "'me' appears twice in the context");
      seenMe = true;
      rule.predecessor = std::move(item);
    } else if (seenMe) {
      rule.right.push_back(std::move(item));
    } else {
      rule.left.push_back(std::move(item));
    }
  }
  if (!seenMe) fail(peek().span, "a context names the current cell with 'me', as in 'A(y) me B(z)'");
}

void Parser::ruleBody(Rule& rule) {
  while (!check(TokenKind::Arrow) && !atStatementEnd() && !check(TokenKind::Colon)) {
    rule.calculations.push_back(assignment());
    if (!match(TokenKind::Comma)) break;
  }
  if (match(TokenKind::Arrow)) {
    rule.hasAction = true;
    successors(rule);
  }
}

Assignment Parser::assignment() {
  Assignment result;
  const Token& first = peek();
  if (checkWord("rate") && peek(1).kind == TokenKind::LParen) {
    advance();
    advance();
    const Token& target = expect(TokenKind::Identifier, " (the state variable of 'rate')");
    expect(TokenKind::RParen, " after the variable of 'rate'");
    result.isRate = true;
    result.target = target.text;
    result.targetSpan = target.span;
  } else {
    if (!check(TokenKind::Identifier)) failHere("a state calculation such as 'x = x + 1' or '->'");
    const Token& target = advance();
    result.target = target.text;
    result.targetSpan = target.span;
    if (check(TokenKind::Dot) && (target.text == "parent" || target.text == "root" || target.text == "me")) {
      std::string path = target.text;
      SourceSpan span = target.span;
      while (match(TokenKind::Dot) && check(TokenKind::Identifier)) {
        path += "." + peek().text;
        span = span.to(advance().span);
      }
      fail(span, target.text == "me" ? "'" + path + "' is the cell's read-only internal state; it cannot be assigned"
                                     : "'" + path + "' is an enclosing system's state: cells read it, never write it");
    }
  }
  switch (peek().kind) {
    case TokenKind::Equal: case TokenKind::PlusEqual: case TokenKind::MinusEqual:
    case TokenKind::StarEqual: case TokenKind::SlashEqual:
      result.op = advance().kind;
      break;
    default:
      failHere("'=' in the state calculation of '" + result.target + "'");
  }
  if (result.isRate && result.op != TokenKind::Equal) fail(previous().span, "'rate(x)' is set with '='");
  result.value = expression();
  result.span = first.span.to(previous().span);
  return result;
}

void Parser::successors(Rule& rule) {
  if (match(TokenKind::EmptySet)) {
  } else {
    while (!atStatementEnd() && (canStartModule() || check(TokenKind::Equal)))
      rule.successors.push_back(module(ModuleUse::Successor));
    if (!atStatementEnd()) failOnDigitModule();
  }
  if (match(TokenKind::Colon)) rule.probability = expression();
}

bool Parser::canStartModule() const {
  const Token& token = peek();
  if (token.kind == TokenKind::Identifier || token.kind == TokenKind::LParen) return true;
  if (letters_ &&
      (token.kind == TokenKind::Number || token.kind == TokenKind::AmpAmp || token.kind == TokenKind::PipePipe))
    return true;
  return isSymbolToken(token.kind);
}

void Parser::notation() {
  if (inLSystem_)
    letters_ = true;
  else
    lettersEverywhere_ = true;
}

void Parser::splitLetterRun() {
  const Token token = peek();
  std::vector<Token> pieces;
  // The pieces copy the token but for its text, which may be long (a run of 32,000
  // letters copied into each of its pieces took 1 GB).
  const Token shape{token.kind, {}, token.number, token.span, token.line, token.column};
  auto piece = [&](uint32_t begin, uint32_t end, TokenKind kind) {
    Token part = shape;
    part.kind = kind;
    part.text = kind == TokenKind::Identifier ? token.span.file->text().substr(begin, end - begin) : std::string();
    part.span.begin = begin;
    part.span.end = end;
    part.column = token.column + static_cast<int>(begin - token.span.begin);
    pieces.push_back(std::move(part));
  };
  if (token.kind == TokenKind::AmpAmp || token.kind == TokenKind::PipePipe) {
    const TokenKind one = token.kind == TokenKind::AmpAmp ? TokenKind::Amp : TokenKind::Pipe;
    piece(token.span.begin, token.span.begin + 1, one);
    piece(token.span.begin + 1, token.span.end, one);
  } else if ((token.kind == TokenKind::Identifier && codePoints(token.text) > 1) || token.kind == TokenKind::Number) {
    const std::string& text = token.span.file->text();
    for (uint32_t at = token.span.begin; at < token.span.end;) {
      uint32_t end = at + 1;
      while (end < token.span.end && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80) ++end;
      const unsigned char c = static_cast<unsigned char>(text[at]);
      if (!std::isalnum(c) && c != '_' && c < 0x80)
        fail(token.span, "under #letters every digit is a module, so '" + token.text +
                             "' cannot stand here; write a number inside a module's parentheses, as in F(" +
                             token.text + ")");
      piece(at, end, TokenKind::Identifier);
      at = end;
    }
    if (pieces.size() == 1 && token.kind == TokenKind::Identifier) return;
  } else {
    return;
  }
  tokens_.split(pos_, pieces);
}

void Parser::failOnDigitModule() {
  if (!inLSystem_ || !check(TokenKind::Number)) return;
  const Token& number = peek();
  fail(number.span, "'" + number.text + "' is a number, not a module: a label starts with a letter (write 'A" +
                        number.text +
                        "'), or put #letters in the block, under which every letter and digit is a module, as in "
                        "ABOP's 0 -> 1[0]0");
}

Module Parser::module(ModuleUse use) {
  const Token& equal = peek();
  if (use == ModuleUse::Successor && match(TokenKind::Equal)) {
    Module kept = module(use);
    if (kept.keepsIdentity) fail(equal.span, "one '=' keeps the identity");
    if (kept.isMe) fail(equal.span, "'me' keeps its identity already; write 'me'");
    kept.keepsIdentity = true;
    kept.span = equal.span.to(kept.span);
    return kept;
  }
  const Token& first = peek();
  if (check(TokenKind::LParen)) {
    advance();
    ++depth_;
    const bool keeps = use == ModuleUse::Successor && match(TokenKind::Equal);
    Module inner = bareModule(use);
    inner.keepsIdentity = keeps;
    if (use == ModuleUse::Instruction || use == ModuleUse::Pattern)
      fail(first.span, "a timed module '(X, age)' cannot stand here");
    if (inner.isMe) fail(first.span, "'me' keeps its own age; it takes no birth age");
    expect(TokenKind::Comma, " and an age, as in '(A(x), 0.5)'");
    inner.age = expression();
    --depth_;
    const Token& close = expect(TokenKind::RParen, " to close the timed module");
    inner.span = first.span.to(close.span);
    return inner;
  }
  return bareModule(use);
}

Module Parser::bareModule(ModuleUse use) {
  Module result;
  if (letters_ && use != ModuleUse::Instruction) splitLetterRun();
  const Token& label = peek();
  if (label.kind != TokenKind::Identifier && !isSymbolToken(label.kind)) failHere("a module such as 'A' or 'F(1)'");
  advance();
  result.label = symbolSpelling(label);
  result.span = label.span;
  if (label.kind == TokenKind::Identifier && label.text == "me") {
    if (use == ModuleUse::Axiom || use == ModuleUse::Instruction || use == ModuleUse::Predecessor)
      fail(label.span, "'me' names the current cell and can only stand in a rule");
    result.isMe = true;
  }
  if (check(TokenKind::LParen) && peek().span.begin == label.span.end) {
    patternArguments(result, use);
    result.span = label.span.to(previous().span);
  }
  return result;
}

void Parser::patternArguments(Module& result, ModuleUse use) {
  advance();
  ++depth_;
  result.hasArgs = true;
  if (!check(TokenKind::RParen)) {
    do {
      if ((use == ModuleUse::Pattern || use == ModuleUse::Predecessor) &&
          (check(TokenKind::Number) || (check(TokenKind::Minus) && peek(1).kind == TokenKind::Number))) {
        // A value pattern, `A(3)`: the module matches only with that value there.
        const Token& sign = peek();
        const bool negative = match(TokenKind::Minus);
        const Token& value = advance();
        auto expr = std::make_unique<Expr>();
        expr->kind = Expr::Kind::Number;
        expr->number = negative ? -value.number : value.number;
        expr->span = sign.span.to(value.span);
        result.args.push_back(std::move(expr));
      } else if (use == ModuleUse::Pattern || use == ModuleUse::Predecessor) {
        const Token& name = peek();
        if (name.kind != TokenKind::Identifier)
          failHere("a parameter name or a number (patterns bind names, as in 'A(x)', or test values, as in 'A(3)')");
        advance();
        auto expr = std::make_unique<Expr>();
        expr->kind = Expr::Kind::Name;
        expr->name = name.text;
        expr->span = name.span;
        result.args.push_back(std::move(expr));
      } else {
        result.args.push_back(expression());
      }
    } while (match(TokenKind::Comma));
  }
  --depth_;
  expect(TokenKind::RParen, " to close the arguments of '" + result.label + "'");
}

}  // namespace ontogen::detail
