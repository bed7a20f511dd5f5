#include "lang/convert/lsystem_file.h"

#include "lang/convert/foreign_syntax.h"

#include <cctype>
#include <filesystem>

namespace ontogen::convert {

namespace {

std::string moduleText(const ModuleText& module) {
  std::string text = module.label;
  if (!module.hasArgs) return text;
  text += "(";
  for (size_t i = 0; i < module.args.size(); ++i) text += (i ? ", " : "") + module.args[i];
  return text + ")";
}

std::string wordText(const std::vector<ModuleText>& modules) {
  std::string text;
  for (const ModuleText& module : modules) text += (text.empty() ? "" : " ") + moduleText(module);
  return text;
}

bool hasDigitLabel(const std::vector<ModuleText>& modules) {
  for (const ModuleText& module : modules)
    if (!module.label.empty() && std::isdigit(static_cast<unsigned char>(module.label[0]))) return true;
  return false;
}

bool needsLetters(const LSystemFile& file) {
  if (hasDigitLabel(file.axiom)) return true;
  for (const Statement& s : file.statements)
    if (s.kind == StatementKind::Production && (hasDigitLabel(s.left) || hasDigitLabel(s.right) ||
                                                hasDigitLabel(s.successors) || hasDigitLabel({s.predecessor})))
      return true;
  return false;
}

bool isDigitLabel(const std::string& label) {
  return !label.empty() && std::isdigit(static_cast<unsigned char>(label[0]));
}

// An ignore: or consider: list of a block without #letters, where no digit module stands
// in the axiom or a production: its digits (which the cell language spells under
// #letters only) name modules the word never holds, so leaving them out changes nothing.
Statement withoutAbsentDigits(Statement s) {
  if (s.kind != StatementKind::Ignore && s.kind != StatementKind::Consider) return s;
  std::vector<std::string> kept;
  for (std::string& symbol : s.symbols)
    if (!isDigitLabel(symbol)) kept.push_back(std::move(symbol));
  // A list of digits alone stays as it is (an empty list would mean otherwise).
  if (!kept.empty()) s.symbols = std::move(kept);
  return s;
}

std::string statementText(const Statement& s) {
  switch (s.kind) {
    case StatementKind::Section:
      return s.word + ":";
    case StatementKind::MaximumDepth:
      return "maximum depth: " + s.word;
    case StatementKind::Group:
      return "group " + s.word + ":";
    case StatementKind::Ignore:
    case StatementKind::Consider: {
      std::string text = s.kind == StatementKind::Ignore ? "ignore:" : "consider:";
      for (const std::string& symbol : s.symbols) text += " " + symbol;
      return text;
    }
    case StatementKind::Production:
      break;
  }
  std::string text;
  if (!s.left.empty()) text += wordText(s.left) + " " + s.leftArrow + " ";
  text += moduleText(s.predecessor);
  if (!s.right.empty()) text += " " + s.rightArrow + " " + wordText(s.right);
  if (!s.condition.empty()) text += " : " + s.condition;
  text += " -> " + (s.successors.empty() ? std::string("∅") : wordText(s.successors));
  if (!s.probability.empty()) text += " : " + s.probability;
  return text;
}

}  // namespace

size_t statementLineBytes(const Statement& statement) {
  return std::string_view("  ").size() + statementText(statement).size() + 1;
}

std::string_view dialectName(Dialect dialect) {
  return dialect == Dialect::Cpfg ? "cpfg" : "L-Py";
}

std::string blockNameOf(std::string_view path) {
  std::string name = std::filesystem::path(path).stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') c = '_';
  if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) name = "l_" + name;
  return name;
}

CellProgram writeCellProgram(const LSystemFile& file, std::string_view sourceName) {
  CellProgram out;
  auto line = [&](const std::string& text, SourceRange origin = {}) {
    out.text += text;
    out.text += '\n';
    out.lineOrigins.push_back(origin);
  };
  line("// Converted by ontogen convert from " + std::string(sourceName) + " (" +
       std::string(dialectName(file.dialect)) + ")");
  line("lsystem " + file.name + " {");
  const bool letters = needsLetters(file);
  if (letters) line("  #letters");
  for (const Define& define : file.defines) line("  #define " + cellName(define.name) + " " + define.value, define.origin);
  if (file.angle) line("  #angle " + *file.angle);
  if (file.seed) line("  #seed " + *file.seed);
  if (file.derivationLength) line("  #until " + *file.derivationLength, file.derivationLengthOrigin);
  if (file.useGroup) line("  use group: " + *file.useGroup, file.useGroupOrigin);
  if (!file.axiom.empty()) line("  axiom " + wordText(file.axiom), file.axiomOrigin);
  if (file.multiscale)
    for (const ScaleDeclaration& scale : file.scales) {
      std::string text = (file.levels ? "  level " : "  scale ") + scale.scale + ":";
      for (const std::string& label : scale.labels) text += " " + label;
      line(text, scale.origin);
    }
  for (const Statement& statement : file.statements)
    line("  " + statementText(letters ? statement : withoutAbsentDigits(statement)), statement.origin);
  line("}");
  return out;
}

}  // namespace ontogen::convert
