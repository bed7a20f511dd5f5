#include "lang/variation.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

#include "lang/directives.h"
#include "lang/lexer.h"
#include "model/message_number.h"
#include "lang/parser.h"
#include "model/random.h"
#include "model/utf8.h"

namespace ontogen {

namespace {

using ByteRange = std::pair<uint32_t, uint32_t>;  // [begin, end) in the lexed file

[[noreturn]] void throwFirstError(const DiagnosticSink& sink, const char* stage) {
  std::string where;
  for (const Diagnostic& diagnostic : sink.diagnostics()) {
    if (diagnostic.severity != Severity::Error) continue;
    where = std::to_string(diagnostic.span.line()) + ":" + std::to_string(diagnostic.span.column()) + ": " +
            diagnostic.message;
    break;
  }
  throw std::invalid_argument(std::string("cannot find the numbers of a text that does not ") + stage + ": " + where);
}

// Written as digits alone (a sign aside): "3", not "3.", "3.0" or "3e0".
bool spelledAsInteger(std::string_view spelling) {
  return !spelling.empty() &&
         std::all_of(spelling.begin(), spelling.end(), [](char c) { return c >= '0' && c <= '9'; });
}

void setRange(Gene& gene) {
  // 2v overflows for the largest doubles: the range then ends at the largest finite one.
  constexpr double kLargest = std::numeric_limits<double>::max();
  const double v = gene.value;
  if (v > 0) {
    gene.low = gene.integer && v >= 1 ? 1 : 0;
    gene.high = std::min(2 * v, kLargest);
  } else if (v < 0) {
    gene.low = std::max(2 * v, -kLargest);
    gene.high = 0;
  } else {
    gene.low = -1;
    gene.high = 1;
  }
}

// As the parser ends a directive (lang/parser.cpp, atStatementEnd): at ';', '}', the end
// of the file or a token on a later line.
bool endsStatement(const Token& next, const Token& last) {
  return next.kind == TokenKind::Semicolon || next.kind == TokenKind::RBrace || next.kind == TokenKind::EndOfFile ||
         next.line > last.line;
}

bool isDefine(const Token& token) {
  if (token.kind != TokenKind::Directive) return false;
  const Directive* directive = findDirective(token.text);
  return directive && directive->kind == DirectiveKind::Define;
}

// `#define NAME NUMBER` or `#define NAME -NUMBER` at tokens[i], else nothing. `end` is
// set to the index after the number.
std::optional<Gene> defineGene(const std::vector<Token>& tokens, size_t i, uint32_t shift, size_t& end) {
  if (!isDefine(tokens[i]) || i + 2 >= tokens.size() || tokens[i + 1].kind != TokenKind::Identifier) return {};
  size_t at = i + 2;
  const Token& first = tokens[at];
  const bool negative = first.kind == TokenKind::Minus;
  if (negative) ++at;
  if (at + 1 >= tokens.size() || tokens[at].kind != TokenKind::Number) return {};
  const Token& number = tokens[at];
  if (!endsStatement(tokens[at + 1], number) || number.line != tokens[i].line || !std::isfinite(number.number))
    return {};
  Gene gene;
  gene.kind = Gene::Kind::Define;
  gene.name = tokens[i + 1].text;
  gene.offset = first.span.begin + shift;
  gene.length = number.span.end - first.span.begin;
  gene.line = static_cast<uint32_t>(first.line);
  gene.column = static_cast<uint32_t>(first.column);
  gene.value = negative ? -number.number : number.number;
  gene.integer = spelledAsInteger(number.text);
  setRange(gene);
  end = at + 1;
  return gene;
}

// The byte ranges of the number literals the parser reads as values of expressions.
// Directives (defines and settings) and patterns are left out: the first are no
// constants of rules, the second select what matches.
class LiteralCollector {
 public:
  std::set<ByteRange> run(const ast::Program& program) {
    for (const auto& function : program.functions) visit(function);
    for (const auto& cell : program.cells) visit(cell);
    for (const auto& system : program.systems) visit(system);
    return std::move(ranges_);
  }

 private:
  void visit(const ast::ExprPtr& expr) {
    if (!expr) return;
    if (expr->kind == ast::Expr::Kind::Number) ranges_.insert({expr->span.begin, expr->span.end});
    for (const auto& arg : expr->args) visit(arg);
  }
  void visit(const std::vector<ast::Parameter>& parameters) {
    for (const auto& parameter : parameters) visit(parameter.defaultValue);
  }
  void visit(const ast::Module& module) {
    for (const auto& arg : module.args) visit(arg);
    visit(module.age);
  }
  void visit(const std::vector<ast::Module>& modules) {
    for (const auto& module : modules) visit(module);
  }
  void visit(const ast::DevelopmentFunction& function) {
    visit(function.params);
    visit(function.body);
  }
  void visit(const ast::Rule& rule) {
    // The predecessor, its terminal age `(A, 3)` included, is a pattern too: a symbol
    // has one terminal age, which its rules must agree on.
    visit(rule.predicate);
    for (const auto& calculation : rule.calculations) visit(calculation.value);
    visit(rule.successors);
    visit(rule.probability);
  }
  void visit(const ast::Cell& cell) {
    visit(cell.state);
    visit(cell.lifetime);
    for (const auto& rule : cell.rules) visit(rule);
    for (const auto& interpretation : cell.interpretations) visit(interpretation.instructions);
  }
  void visit(const ast::System& system) {
    visit(system.state);
    for (const auto& arg : system.poolArgs) visit(arg);
    visit(system.axiom);
    for (const auto& placement : system.placements) {
      for (const auto& at : placement.at) visit(at);
      visit(placement.module);
    }
    for (const auto& rule : system.productions) visit(rule);
    visit(system.decompositionDepth);
    visit(system.homomorphismDepth);
    visit(system.useGroup);
    for (const auto& interpretation : system.interpretations) visit(interpretation.block.instructions);
    for (const auto& function : system.functions) visit(function);
  }

  std::set<ByteRange> ranges_;
};

// `#range NAME LOW HIGH` at tokens[i] (each bound optionally signed), else nothing.
std::optional<GeneRange> declaredRange(const std::vector<Token>& tokens, size_t i) {
  const Token& hash = tokens[i];
  if (hash.kind != TokenKind::Directive) return {};
  const Directive* directive = findDirective(hash.text);
  if (!directive || directive->kind != DirectiveKind::Range) return {};
  if (i + 1 >= tokens.size() || tokens[i + 1].kind != TokenKind::Identifier) return {};
  GeneRange range{tokens[i + 1].text, 0, 0};
  size_t at = i + 2;
  auto bound = [&](double& into) {
    const bool negative = at < tokens.size() && tokens[at].kind == TokenKind::Minus;
    if (negative) ++at;
    if (at >= tokens.size() || tokens[at].kind != TokenKind::Number) return false;
    into = negative ? -tokens[at].number : tokens[at].number;
    ++at;
    return true;
  };
  if (!bound(range.low) || !bound(range.high)) return {};
  return range;
}

// A range for a gene: an integer gene keeps to the whole numbers inside it.
void applyRange(Gene& gene, const GeneRange& range, const char* origin) {
  double low = range.low, high = range.high;
  if (!std::isfinite(low) || !std::isfinite(high) || !(low < high))
    throw std::invalid_argument(std::string(origin) + " of " + range.name + " needs finite numbers low < high");
  if (gene.integer) {
    low = std::ceil(low);
    high = std::floor(high);
    if (!(low < high))
      throw std::invalid_argument(std::string(origin) + " of " + range.name +
                                  " holds fewer than two whole numbers, and the gene is written as a whole number");
  }
  gene.low = low;
  gene.high = high;
}

Gene constantGene(const Token& number, uint32_t shift) {
  Gene gene;
  gene.kind = Gene::Kind::Constant;
  gene.name = std::to_string(number.line) + ":" + std::to_string(number.column);
  gene.offset = number.span.begin + shift;
  gene.length = number.span.end - number.span.begin;
  gene.line = static_cast<uint32_t>(number.line);
  gene.column = static_cast<uint32_t>(number.column);
  gene.value = number.number;
  gene.integer = spelledAsInteger(number.text);
  setRange(gene);
  return gene;
}

uint64_t genomeKey(const Genome& genome) {
  uint64_t key = genome.values.size();
  for (double value : genome.values) key = mixKey(key, keyOf(value));
  return key;
}

// Where a mutation may put a value: inside the gene's range, integral for an integer
// gene, and +0 rather than -0 (which would be written "-0").
double limit(const Gene& gene, double value) {
  value = std::clamp(value, gene.low, gene.high);
  if (gene.integer) value = std::round(value);
  return value + 0.0;
}

double perturbed(const Gene& gene, double value, double strength, RandomStream& stream) {
  const double step = strength * (gene.high - gene.low) * stream.gaussian();
  double moved = limit(gene, value + step);
  // Pushed against a bound, or rounded back to where it was: the other way.
  if (moved == value) moved = limit(gene, value - step);
  // A step smaller than one (integer genes) or than the value's precision: the least move.
  const double sign = step >= 0 ? 1 : -1;
  if (moved == value && gene.integer) moved = limit(gene, value + sign);
  if (moved == value && gene.integer) moved = limit(gene, value - sign);
  if (moved == value) moved = limit(gene, std::nextafter(value, (gene.low + gene.high) / 2));
  return moved;
}

}  // namespace

std::string shortestNumber(double value) {
  constexpr double kExactIntegers = 9007199254740992.0;  // 2^53
  value += 0.0;                                          // -0 is written "0"
  char buffer[32];
  const bool integral = std::abs(value) < kExactIntegers && value == std::trunc(value);
  const auto result = integral ? std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed)
                               : std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

VariationSpace::VariationSpace(std::string text, VariationOptions options) : text_(std::move(text)), options_(options) {
  if (!(options_.rate >= 0 && options_.rate <= 1))
    throw std::invalid_argument("the mutation rate must be from 0 to 1, not " + messageNumber(options_.rate, kShortestDigits));
  if (!(options_.strength > 0) || !std::isfinite(options_.strength))
    throw std::invalid_argument("the mutation strength must be a finite number above 0, not " +
                                messageNumber(options_.strength, kShortestDigits));
  // The lexer reads the text without its byte-order mark: offsets into ours are shifted.
  const uint32_t shift = text_.starts_with(kUtf8ByteOrderMark) ? static_cast<uint32_t>(kUtf8ByteOrderMark.size()) : 0;
  const SourceFile file("<variation>", text_);
  DiagnosticSink sink;
  const std::vector<Token> tokens = lex(file, sink);
  if (sink.hasErrors()) throwFirstError(sink, "lex");
  std::set<ByteRange> literals;
  if (options_.constants) {
    const ast::Program program = parse(file, sink);
    if (sink.hasErrors()) throwFirstError(sink, "parse");
    literals = LiteralCollector().run(program);
  }
  std::vector<GeneRange> declared;
  for (size_t i = 0; i < tokens.size(); ++i) {
    if (auto range = declaredRange(tokens, i)) declared.push_back(std::move(*range));
    size_t end = i;
    if (auto gene = defineGene(tokens, i, shift, end)) {
      const bool fixed = std::find(options_.fixed.begin(), options_.fixed.end(), gene->name) != options_.fixed.end();
      if (!fixed) genes_.push_back(std::move(*gene));
      i = end - 1;
      continue;
    }
    const Token& token = tokens[i];
    if (token.kind == TokenKind::Number && token.number != 0 && std::isfinite(token.number) &&
        literals.count({token.span.begin, token.span.end}))
      genes_.push_back(constantGene(token, shift));
  }
  // The program's ranges, then the caller's, which win. A declared range of a define that
  // is no gene (an expression, a fixed one) has nothing to apply to; a given one is a
  // mistake worth a message.
  for (const GeneRange& range : declared)
    for (Gene& gene : genes_)
      if (gene.kind == Gene::Kind::Define && gene.name == range.name) applyRange(gene, range, "#range");
  for (const GeneRange& range : options_.ranges) {
    bool found = false;
    for (Gene& gene : genes_)
      if (gene.name == range.name) {
        applyRange(gene, range, "the range");
        found = true;
      }
    if (!found) throw std::invalid_argument("a range for '" + range.name + "', which is no gene of the program");
  }
}

Genome VariationSpace::original() const {
  Genome genome;
  for (const Gene& gene : genes_) genome.values.push_back(gene.value);
  return genome;
}

void VariationSpace::check(const Genome& genome) const {
  if (genome.values.size() != genes_.size())
    throw std::invalid_argument("a genome of " + std::to_string(genome.values.size()) + " values for " +
                                std::to_string(genes_.size()) + " genes");
  for (size_t i = 0; i < genes_.size(); ++i)
    if (!std::isfinite(genome.values[i]))
      throw std::invalid_argument("gene " + genes_[i].name + " has no finite value");
}

Genome VariationSpace::mutate(const Genome& parent, uint64_t seed) const {
  check(parent);
  Genome child = parent;
  if (genes_.empty()) return child;
  RandomStream stream(mixKey(seed, genomeKey(parent)));
  std::vector<bool> changes(genes_.size());
  bool any = false;
  for (size_t i = 0; i < genes_.size(); ++i) {
    changes[i] = stream.uniform() < options_.rate;
    any = any || changes[i];
  }
  if (!any) changes[std::min(genes_.size() - 1, static_cast<size_t>(stream.uniform() * genes_.size()))] = true;
  for (size_t i = 0; i < genes_.size(); ++i)
    if (changes[i]) child.values[i] = perturbed(genes_[i], parent.values[i], options_.strength, stream);
  return child;
}

Genome VariationSpace::crossover(const Genome& a, const Genome& b, uint64_t seed) const {
  check(a);
  check(b);
  RandomStream stream(mixKey(mixKey(seed, genomeKey(a)), genomeKey(b)));
  Genome child;
  child.values.reserve(genes_.size());
  for (size_t i = 0; i < genes_.size(); ++i) child.values.push_back(stream.next() >> 63 ? a.values[i] : b.values[i]);
  return child;
}

std::string VariationSpace::programText(const Genome& genome) const {
  check(genome);
  std::string result;
  result.reserve(text_.size() + 16 * genes_.size());
  size_t copied = 0;
  for (size_t i = 0; i < genes_.size(); ++i) {
    const Gene& gene = genes_[i];
    const double value = genome.values[i];
    result.append(text_, copied, gene.offset - copied);
    if (value == gene.value)
      result.append(text_, gene.offset, gene.length);
    else if (gene.kind == Gene::Kind::Constant && value < 0)
      result += "(" + shortestNumber(value) + ")";
    else
      result += shortestNumber(value);
    copied = gene.offset + gene.length;
  }
  result.append(text_, copied);
  return result;
}

std::vector<DefineOverride> VariationSpace::defines(const Genome& genome) const {
  check(genome);
  std::vector<DefineOverride> result;
  for (size_t i = 0; i < genes_.size(); ++i)
    if (genes_[i].kind == Gene::Kind::Define) result.push_back({genes_[i].name, genome.values[i]});
  return result;
}

}  // namespace ontogen
