// The parser of systems and L-systems (lang/parser_internal.h): their items, axioms,
// symbol lists, groups, sections, functions and productions.

#include <string>

#include "lang/parser_internal.h"

namespace ontogen::detail {

System Parser::system() {
  System result;
  const Token& keyword = advance();
  const Token& name = expect(TokenKind::Identifier, " (the system's name)");
  result.name = name.text;
  result.nameSpan = name.span;
  if (check(TokenKind::LParen)) result.state = parameters();
  expect(TokenKind::LBrace, " to open the system");
  while (!check(TokenKind::RBrace) && !check(TokenKind::EndOfFile)) {
    size_t before = pos_;
    try {
      statement_ = Statement{};
      depth_ = 0;
      systemItem(result);
    } catch (const SyntaxError&) {
      synchronize();
    }
    if (pos_ == before) advance();
  }
  const Token& close = expect(TokenKind::RBrace, " to close the system");
  result.span = keyword.span.to(close.span);
  return result;
}

void Parser::systemItem(System& system) {
  if (match(TokenKind::Semicolon)) return;
  if (check(TokenKind::Directive) && peek().text == "letters")
    fail(peek().span, "#letters reads ABOP's strings in lsystem blocks; a system's cells keep their names");
  if (check(TokenKind::Directive)) return directive(system.defines, system.settings);
  if (checkWord("equiv")) return system.equivs.push_back(equiv(Statement{}));
  if (checkWord("pool")) {
    const Token& keyword = advance();
    const Token& kind = expect(TokenKind::Identifier, " (the pool kind: linear, grid or spatial)");
    system.poolKind = kind.text;
    // `pool grid(64, 64) wrap moore;`: sizes or a radius, then option words.
    if (check(TokenKind::LParen) && peek().span.begin == kind.span.end) {
      advance();
      ++depth_;
      if (!check(TokenKind::RParen)) {
        do system.poolArgs.push_back(expression());
        while (match(TokenKind::Comma));
      }
      --depth_;
      expect(TokenKind::RParen, " to close the pool's arguments");
    }
    while (check(TokenKind::Identifier) && !atStatementEnd()) system.poolOptions.push_back(advance().text);
    system.poolSpan = keyword.span.to(previous().span);
    endStatement();
    return;
  }
  if (checkWord("axiom")) return axiom(system);
  if (checkWord("fill") || (checkWord("at") && peek(1).kind == TokenKind::LParen)) return placement(system);
  if (checkWord("ignore") || checkWord("consider")) return symbolList(system);
  failHere("'pool', 'axiom', 'fill', 'at', 'ignore', 'consider', 'equiv', a directive or '}' in the system");
}

void Parser::placement(System& system) {
  Placement result;
  const Token& keyword = advance();
  result.fill = keyword.text == "fill";
  if (!result.fill) {
    expect(TokenKind::LParen, " after 'at'");
    ++depth_;
    do result.at.push_back(expression());
    while (match(TokenKind::Comma));
    --depth_;
    expect(TokenKind::RParen, " to close the site's coordinates");
  }
  if (!canStartModule()) failHere("a cell, as in '" + std::string(result.fill ? "fill A(0)" : "at(1, 2) A(0)") + "'");
  result.module = module(ModuleUse::Axiom);
  result.span = keyword.span.to(previous().span);
  system.placements.push_back(std::move(result));
  endStatement();
}

void Parser::axiom(System& system) {
  const Token& keyword = advance();
  match(TokenKind::Colon);
  if (!system.axiom.empty()) fail(keyword.span, "the system already has an axiom");
  while (!atStatementEnd() && canStartModule()) system.axiom.push_back(module(ModuleUse::Axiom));
  if (!atStatementEnd()) failOnDigitModule();
  system.axiomSpan = keyword.span.to(previous().span);
  if (system.axiom.empty()) fail(keyword.span, "the axiom is empty: give at least one cell, as in 'axiom A(1)'");
  endStatement();
}

void Parser::symbolList(System& system) {
  const Token& keyword = advance();
  match(TokenKind::Colon);
  SymbolList list;
  while (!atStatementEnd()) {
    if (letters_) splitLetterRun();  // only within the statement: the next line's keyword stays whole
    if (!check(TokenKind::Identifier) && !isSymbolToken(peek().kind)) break;
    if (check(TokenKind::LBracket) || check(TokenKind::RBracket))
      fail(peek().span, "brackets delimit branches and cannot be ignored");
    list.symbols.push_back(symbolSpelling(advance()));
  }
  list.span = keyword.span.to(previous().span);
  list.consider = keyword.text == "consider";
  if (system.isLSystem) {
    filter_ = static_cast<int>(system.filters.size());
    system.filters.push_back(list);
  }
  (keyword.text == "ignore" ? system.ignore : system.consider).push_back(std::move(list));
  endStatement();
}

System Parser::lsystem() {
  System result;
  result.isLSystem = true;
  section_ = RuleKind::Production;
  group_ = 0;
  filter_ = -1;
  const Token& keyword = advance();
  const Token& name = expect(TokenKind::Identifier, " (the L-system's name)");
  result.name = name.text;
  result.nameSpan = name.span;
  expect(TokenKind::LBrace, " to open the L-system");
  inLSystem_ = true;
  letters_ = lettersEverywhere_;
  while (!check(TokenKind::RBrace) && !check(TokenKind::EndOfFile)) {
    size_t before = pos_;
    Statement line{true, peek().column};
    statement_ = line;
    try {
      inStatement(line, [&] { lsystemItem(result); });
    } catch (const SyntaxError&) {
      // Line-based recovery: the statement ends at the next line that starts at or
      // left of its first column, even if an open '(' swallowed line breaks.
      pos_ = before;
      int startLine = peek().line;
      advance();
      while (!check(TokenKind::EndOfFile) && !check(TokenKind::RBrace) &&
             !(peek().line > startLine && peek().column <= line.startColumn)) {
        if (advance().kind == TokenKind::Semicolon) break;
      }
    }
    if (pos_ == before) advance();
  }
  inLSystem_ = letters_ = false;
  const Token& close = expect(TokenKind::RBrace, " to close the L-system");
  result.span = keyword.span.to(close.span);
  if (!result.axiomSpan.valid() && !sink_.limitReached())
    sink_.error(name.span, "L-system '" + name.text + "' has no axiom: give it one, as in 'axiom A'");
  return result;
}

void Parser::lsystemItem(System& system) {
  if (match(TokenKind::Semicolon)) return;
  if (check(TokenKind::Directive)) return directive(system.defines, system.settings);
  if (checkWord("equiv")) return system.equivs.push_back(equiv(statement_));
  if (checkWord("interpret") && peek(1).kind == TokenKind::Identifier && peek(1).line == peek().line)
    return symbolInterpretation(system);
  if (checkWord("axiom") && (peek(1).kind == TokenKind::Colon || peek(1).line == peek().line) &&
      peek(1).kind != TokenKind::Arrow && peek(1).kind != TokenKind::Less && peek(1).kind != TokenKind::Greater) {
    system.axiomSpan = peek().span;  // an axiom was written, even if it fails to parse
    return axiom(system);
  }
  if ((checkWord("ignore") || checkWord("consider")) && peek(1).kind == TokenKind::Colon) return symbolList(system);
  if ((checkWord("ignore") || checkWord("consider")) && !arrowInStatement()) {
    const std::string word = peek().text;
    fail(peek().span, "'" + word + "' needs a colon in an L-system, as in '" + word + ": F'");
  }
  if ((checkWord("g") || checkWord("develop")) &&
      (peek(1).kind == TokenKind::Identifier || isSymbolToken(peek(1).kind)) && peek(2).kind == TokenKind::LParen)
    return system.functions.push_back(function());
  if (sectionLine()) return section(system);
  if (checkWord("group") && peek(1).kind == TokenKind::Number && peek(2).kind == TokenKind::Colon) return group();
  if ((checkWord("scale") || checkWord("level")) && peek(1).kind == TokenKind::Number &&
      peek(2).kind == TokenKind::Colon)
    return scaleLine(system);
  if (checkWord("use") && peek(1).kind == TokenKind::Identifier && peek(1).text == "group" &&
      peek(2).kind == TokenKind::Colon)
    return useGroup(system);
  if (checkWord("maximum") && peek(1).kind == TokenKind::Identifier && peek(1).text == "depth" &&
      peek(2).kind == TokenKind::Colon)
    return maximumDepth(system);
  system.productions.push_back(production());
  system.productions.back().kind = section_;
  system.productions.back().group = group_;
  system.productions.back().filter = filter_;
}

void Parser::group() {
  advance();
  const Token& number = advance();
  advance();
  if (!(number.number >= 0) || number.number != std::floor(number.number) || number.number > 1e6)
    fail(number.span, "a group is a whole number from 0, as in 'group 1:'");
  group_ = static_cast<int>(number.number);
  endStatement();
}

void Parser::scaleLine(System& system) {
  const Token& keyword = advance();
  const Token& number = advance();
  advance();
  ScaleLine line;
  line.levels = keyword.text == "level";
  // L-Py's scales are small whole numbers (a plant, its axes, growth units, internodes):
  // 0 to 255 holds every level a description of a plant has.
  if (!(number.number >= 0) || number.number != std::floor(number.number) || number.number > 255)
    fail(number.span, "a " + keyword.text + " is a whole number from 0 to 255, as in '" + keyword.text + " 1: A'");
  line.scale = static_cast<int>(number.number);
  while (!atStatementEnd()) {
    if (letters_) splitLetterRun();
    if (!check(TokenKind::Identifier) && !isSymbolToken(peek().kind)) break;
    if (check(TokenKind::LBracket) || check(TokenKind::RBracket))
      fail(peek().span, "brackets delimit branches and have no " + keyword.text);
    line.symbolSpans.push_back(peek().span);
    line.symbols.push_back(symbolSpelling(advance()));
  }
  if (line.symbols.empty())
    fail(previous().span, "a " + keyword.text + " line names the modules of that " + keyword.text + ", as in '" +
                              keyword.text + " 1: A B'");
  line.span = keyword.span.to(previous().span);
  system.scales.push_back(std::move(line));
  endStatement();
}

void Parser::useGroup(System& system) {
  const Token& first = advance();
  advance();
  advance();
  if (system.useGroup) fail(first.span, "the L-system already says which group it uses");
  system.useGroup = expression();
  endStatement();
}

bool Parser::sectionLine() const {
  if (!(checkWord("production") || checkWord("decomposition") || checkWord("homomorphism") ||
        checkWord("interpretation")))
    return false;
  if (peek(1).kind != TokenKind::Colon) return false;
  const Token& after = peek(2);
  return after.kind == TokenKind::Semicolon || after.kind == TokenKind::RBrace ||
         after.kind == TokenKind::EndOfFile || after.line > peek(1).line;
}

void Parser::section(System& system) {
  (void)system;
  const std::string& word = advance().text;
  advance();
  section_ = word == "production"      ? RuleKind::Production
             : word == "decomposition" ? RuleKind::Decomposition
                                       : RuleKind::Homomorphism;
  endStatement();
}

void Parser::maximumDepth(System& system) {
  const Token& first = peek();
  advance();
  advance();
  advance();
  if (section_ == RuleKind::Production)
    fail(first.span, "'maximum depth' belongs to a 'decomposition:' or 'homomorphism:' section; write it after one");
  ExprPtr& depth = section_ == RuleKind::Decomposition ? system.decompositionDepth : system.homomorphismDepth;
  if (depth)
    fail(first.span, std::string("the ") + (section_ == RuleKind::Decomposition ? "decomposition" : "homomorphism") +
                         "'s maximum depth is given twice");
  depth = expression();
  endStatement();
}

DevelopmentFunction Parser::function() {
  DevelopmentFunction result;
  const Token& keyword = advance();
  const Token& name = advance();
  result.name = symbolSpelling(name);
  result.params = parameters();
  for (const auto& param : result.params)
    if (param.defaultValue) fail(param.span, "a development function's parameters take no default values");
  expect(TokenKind::Equal, " after the development function's parameters");
  result.body = expression();
  result.span = keyword.span.to(previous().span);
  endStatement();
  return result;
}

Rule Parser::production() {
  const Token& first = peek();
  // Under #letters a single letter before ':' is a predecessor (`A : x > 1 -> B`).
  if (check(TokenKind::Identifier) && peek(1).kind == TokenKind::Colon &&
      !(letters_ && codePoints(peek().text) == 1)) {
    // `p1: A -> B` or `A : cond -> B`: try the label first, then fall back.
    // Backtracking restores everything the attempt changed: the position and the
    // parentheses it left open, which would otherwise hide the line breaks after it.
    const size_t savedPos = pos_;
    const int savedDepth = depth_, savedNesting = nesting_;
    ++speculating_;
    try {
      std::string name = advance().text;
      advance();
      Rule rule = productionAfterLabel(first);
      --speculating_;
      rule.name = name;
      return rule;
    } catch (const SyntaxError&) {
      --speculating_;
      pos_ = savedPos;
      depth_ = savedDepth;
      nesting_ = savedNesting;
    }
  }
  return productionAfterLabel(first);
}

Module Parser::contextModule(bool lsystem) {
  if (check(TokenKind::Star)) {
    Module any;
    any.label = "*";
    any.span = advance().span;
    if (check(TokenKind::LParen) && peek().span.begin == any.span.end) {
      if (!lsystem)
        fail(peek().span,
             "the wildcard '*' of a cell's context matches any module and binds nothing; write it "
             "without parameters");
      patternArguments(any, ModuleUse::Pattern);
      any.span = any.span.to(previous().span);
    }
    return any;
  }
  if (lsystem && check(TokenKind::EmptySet)) {
    Module none;
    none.label = "∅";
    none.span = advance().span;
    return none;
  }
  if (lsystem && check(TokenKind::LParen)) return alternativesOrTimed();
  return module(ModuleUse::Predecessor);
}

Module Parser::alternativesOrTimed() {
  const Token& open = advance();
  Nested nested = nest(open.span, "context");
  ++depth_;
  Module group;
  group.label = "(|)";
  group.alternatives.emplace_back();
  for (;;) {
    auto& sequence = group.alternatives.back();
    while (!check(TokenKind::Pipe) && !check(TokenKind::RParen) && !check(TokenKind::Comma) &&
           (canStartModule() || check(TokenKind::Star) || check(TokenKind::EmptySet)))
      sequence.push_back(contextModule());
    if (check(TokenKind::Comma) && group.alternatives.size() == 1 && sequence.size() == 1 &&
        sequence.front().alternatives.empty()) {
      advance();
      Module timed = std::move(sequence.front());
      timed.age = expression();
      --depth_;
      const Token& close = expect(TokenKind::RParen, " to close the timed module");
      timed.span = open.span.to(close.span);
      return timed;
    }
    if (!match(TokenKind::Pipe)) break;
    group.alternatives.emplace_back();
  }
  --depth_;
  const Token& close =
      expect(TokenKind::RParen, " to close the alternatives, as in '(B | C D)', or ', age' after a timed module");
  group.span = open.span.to(close.span);
  return group;
}

std::vector<Module> Parser::contextItems() {
  std::vector<Module> items;
  // A new line at or left of the statement's column ends it (docs/LANGUAGE.md 3.9).
  while (!atStatementEnd() && (canStartModule() || check(TokenKind::Star) || check(TokenKind::EmptySet)) &&
         !check(TokenKind::Less) && !check(TokenKind::Greater))
    items.push_back(contextModule());
  return items;
}

Rule Parser::productionAfterLabel(const Token& first) {
  Rule rule;
  rule.terminal = true;
  std::vector<Module> items = contextItems();
  auto newLeftContext = [&] {
    advance();
    advance();
    rule.hasContext = true;
    rule.newLeft = std::move(items);
    if (rule.newLeft.empty()) failHere("a new left context before '<<'");
    items = contextItems();
  };
  if (atDouble(TokenKind::Less)) {
    newLeftContext();
  } else if (match(TokenKind::Less)) {
    rule.hasContext = true;
    rule.left = std::move(items);
    items = contextItems();
    if (atDouble(TokenKind::Less)) newLeftContext();
    if (items.empty()) failHere("the predecessor after '<'");
  }
  if (items.size() != 1) {
    failOnDigitModule();
    if (items.empty()) failHere("a production such as 'A(x) -> B(x + 1)'");
    fail(items[1].span, "a production has one predecessor module; put context before '<' or after '>'");
  }
  rule.predecessor = std::move(items.front());
  if (rule.predecessor.label == "*")
    fail(rule.predecessor.span,
         "the wildcard '*' stands in contexts, not as the predecessor: a production "
         "belongs to the module it rewrites; write one per label");
  if (rule.predecessor.label == "∅")
    fail(rule.predecessor.span, "'∅' (nothing) stands in contexts, not as the predecessor");
  if (!rule.predecessor.alternatives.empty())
    fail(rule.predecessor.span,
         "alternatives stand in contexts; the predecessor is one module (write one "
         "production per alternative)");
  if (atDouble(TokenKind::Greater)) {
    rule.newRightSpan = peek().span.to(peek(1).span);
    advance();
    advance();
    rule.hasContext = true;
    while (!atStatementEnd() && (canStartModule() || check(TokenKind::Star) || check(TokenKind::EmptySet)) &&
           !check(TokenKind::Greater))
      rule.newRight.push_back(contextModule());
    if (rule.newRight.empty()) failHere("a new right context after '>>'");
  }
  if (match(TokenKind::Greater)) {
    rule.hasContext = true;
    while (!atStatementEnd() && (canStartModule() || check(TokenKind::Star) || check(TokenKind::EmptySet)))
      rule.right.push_back(contextModule());
    if (rule.right.empty()) failHere("a right context after '>'");
  }
  std::function<void(const std::vector<Module>&)> untimed = [&](const std::vector<Module>& side) {
    for (const Module& item : side) {
      if (item.age) fail(item.span, "a context module has no terminal age; write it without '(..., age)'");
      for (const auto& alternative : item.alternatives) untimed(alternative);
    }
  };
  for (const auto* side : {&rule.left, &rule.right, &rule.newLeft, &rule.newRight}) untimed(*side);
  if (match(TokenKind::Colon)) rule.predicate = expression();
  if (!match(TokenKind::Arrow)) failHere("'->' in the production");
  rule.hasAction = true;
  successors(rule);
  rule.span = first.span.to(previous().span);
  endStatement();
  return rule;
}

}  // namespace ontogen::detail
