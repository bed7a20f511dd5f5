#include "lang/convert/lpy_constants.h"

#include <algorithm>
#include <charconv>
#include <set>

#include "lang/convert/foreign_text.h"
#include "lang/convert/written_number.h"

namespace ontogen::convert {

namespace {

using chars::isLetter;
using chars::isNameChar;

// The shortest text that reads back as `value`.
std::string numberText(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

// `expr` with the recorded constants it names (not those `hidden`) put in as numbers,
// their names (with the constants they were computed from) in `used`; nullopt where it
// names anything else.
std::optional<std::string> withConstants(const ForeignSyntax& syntax, const std::string& expr,
                                         const std::set<std::string, std::less<>>& hidden,
                                         std::set<std::string, std::less<>>& used) {
  std::string result;
  for (size_t i = 0; i < expr.size();) {
    const bool starts = isLetter(expr[i]) && (i == 0 || !(isNameChar(expr[i - 1]) || expr[i - 1] == '.'));
    if (!starts) {
      result += expr[i++];
      continue;
    }
    size_t stop = i;
    while (stop < expr.size() && isNameChar(expr[stop])) ++stop;
    const std::string name = expr.substr(i, stop - i);
    const auto constant = syntax.fileConstants.find(name);
    if (stop < expr.size() && expr[stop] == '(') {
      result += name;  // a function of the cell language: writtenNumber tells
    } else if (constant == syntax.fileConstants.end() || hidden.count(name)) {
      return std::nullopt;
    } else {
      result += "(" + numberText(constant->second.value) + ")";
      used.insert(name);
      used.insert(constant->second.from.begin(), constant->second.from.end());
    }
    i = stop;
  }
  return result;
}

}  // namespace

std::optional<double> ForeignSyntax::fixedNumber(const std::string& expr, uint32_t begin, uint32_t end) const {
  if (std::optional<double> value = writtenNumber(expr)) return value;
  std::set<std::string, std::less<>> used;
  const std::optional<std::string> text = withConstants(*this, expr, bound_, used);
  if (!text) return std::nullopt;
  const std::optional<double> value = writtenNumber(*text);
  if (!value) return std::nullopt;
  for (const std::string& name : used) fixedConstants.emplace(name, SourceRange{begin, end});
  return value;
}

void recordFileConstant(ForeignSyntax& syntax, const std::string& name, const std::string& value) {
  if (syntax.fileConstants.count(name) || syntax.setAgain.count(name)) {
    syntax.fileConstants.erase(name);
    syntax.setAgain.insert(name);
    return;
  }
  std::set<std::string, std::less<>> used;
  std::optional<double> number = writtenNumber(value);
  if (!number) {
    if (const std::optional<std::string> text = withConstants(syntax, value, {}, used)) number = writtenNumber(*text);
  }
  if (number) syntax.fileConstants[name] = {*number, std::move(used)};
}

bool setAgain(ForeignSyntax& syntax, LSystemFile& file, const std::string& name, char op, const std::string& value,
              SourceRange line) {
  const std::string cell = cellName(name);
  const auto before = std::find_if(file.defines.begin(), file.defines.end(),
                                   [&](const Define& d) { return cellName(d.name) == cell; });
  if (before == file.defines.end()) return false;
  std::map<std::string, HookValue, std::less<>> earlier{{cell, {"(" + before->value + ")", before->origin}}};
  auto reads = [&](const std::string& text) {
    bool read = false;
    withHookValues(text, earlier, {}, &read);
    return read;
  };
  bool read = std::any_of(before + 1, file.defines.end(), [&](const Define& d) { return reads(d.value); });
  for (const ModuleText& m : file.axiom)
    for (const std::string& arg : m.args) read = read || reads(arg);
  read = read || (file.derivationLength && reads(*file.derivationLength));
  if (read)
    syntax.fail(line.begin, line.end,
                "'" + name +
                    "' set again after the file's values, axiom or derivation length read it (Python read its "
                    "earlier value there): give the new value another name");
  std::string now = withHookValues(value, earlier, {});
  if (op != '=') now = "(" + before->value + ") " + op + " (" + now + ")";
  recordFileConstant(syntax, cell, now);
  file.defines.erase(before);
  file.defines.push_back({name, now, line});
  return true;
}

void checkFixedConstantsAgainstHooks(const ForeignSyntax& syntax, const HookEffects& effects) {
  for (const auto& [name, where] : syntax.fixedConstants)
    if (effects.defines.count(name) || effects.stepValues.count(name))
      syntax.fail(where.begin, where.end,
                  "'" + name +
                      "', which a hook of L-Py sets, read where the converter writes out its number (a loop's turns, "
                      "randint's choices): the turns would stay those of the file's value");
}

void writeFixedConstantsInPlace(const ForeignSyntax& syntax, LSystemFile& file) {
  if (syntax.fixedConstants.empty()) return;
  std::map<std::string, HookValue, std::less<>> values;
  for (const auto& [name, where] : syntax.fixedConstants) {
    const auto constant = syntax.fileConstants.find(name);
    if (constant == syntax.fileConstants.end())
      syntax.fail(where.begin, where.end, "'" + name + "' is set more than once: no constant of one value");
    values[name] = {numberText(constant->second.value), where};
  }
  std::erase_if(file.defines, [&](const Define& d) { return values.count(cellName(d.name)) > 0; });
  auto inPlace = [&](std::string& text, const std::vector<std::string>& bound) {
    text = withHookValues(text, values, bound);
  };
  for (Define& d : file.defines) inPlace(d.value, {});
  for (ModuleText& m : file.axiom)
    for (std::string& arg : m.args) inPlace(arg, {});
  for (std::optional<std::string>* value : {&file.derivationLength, &file.useGroup, &file.seed, &file.angle})
    if (*value) inPlace(**value, {});
  for (Statement& s : file.statements) {
    if (s.kind == StatementKind::MaximumDepth || s.kind == StatementKind::Group) inPlace(s.word, {});
    if (s.kind != StatementKind::Production) continue;
    std::vector<std::string> bound;
    for (const std::vector<ModuleText>* word : {&s.left, &s.right})
      for (const ModuleText& m : *word) bound.insert(bound.end(), m.args.begin(), m.args.end());
    bound.insert(bound.end(), s.predecessor.args.begin(), s.predecessor.args.end());
    inPlace(s.condition, bound);
    inPlace(s.probability, bound);
    for (ModuleText& m : s.successors)
      for (std::string& arg : m.args) inPlace(arg, bound);
  }
}

}  // namespace ontogen::convert
