#include "lang/convert/foreign_syntax.h"

#include <cctype>
#include <cstdlib>
#include <optional>
#include <utility>

#include "lang/compile_context.h"
#include "lang/convert/python_operators.h"
#include "lang/program.h"

namespace ontogen::convert {

namespace {

bool isLetter(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool isNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}
bool isSpace(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}

// The one-character symbols the cell language takes as labels (docs/LANGUAGE.md 2).
bool isCellSymbol(char c) {
  return std::string_view("+-^&/\\|!<>[]$~@%").find(c) != std::string_view::npos;
}

// What a predefined module of cpfg or L-Py becomes. A turtle command ontogen has is
// translated to it; a drawing command it has not stays a module of a name (the word is the
// other tool's), with a warning that it draws nothing; a query whose parameters ontogen
// would not fill is refused, as the word would differ.
enum class Fate { Translate, Inert, Refuse };
struct Predefined {
  std::string_view name;  ///< as the file writes it
  std::string_view cell;  ///< Translate: the cell-language label; Inert: the module's name
  Fate fate;
  bool lpyOnly = true;    ///< a name of L-Py alone (cpfg's modules are one character or '@' names)
  bool cpfgOnly = false;  ///< a name of cpfg alone
};

bool inDialect(const Predefined& p, Dialect dialect) {
  return dialect == Dialect::LPy ? !p.cpfgOnly : !p.lpyOnly;
}

constexpr Predefined kPredefined[] = {
    // Both tools' '@' modules.
    {"@O", "sphere", Fate::Translate, false},
    {"@o", "disc", Fate::Translate, false},
    {"@v", "$", Fate::Translate, false},
    {"@M", "MoveTo", Fate::Inert, false},
    {"@R", "SetHead", Fate::Inert, false},
    {"@L", "Label", Fate::Inert, false},
    {"@B", "Box", Fate::Inert, true},
    {"@b", "Quad", Fate::Inert, false},
    {"@g", "PglShape", Fate::Inert, true},
    {"@h", "RollToHorizontal", Fate::Inert, true},
    {"@Dd", "DivScale", Fate::Inert, true},
    {"@Di", "MultScale", Fate::Inert, true},
    {"@D", "SetScale", Fate::Inert, true},
    {"@Ts", "Elasticity", Fate::Inert, true},
    {"@Tp", "Tropism", Fate::Inert, true},
    {"@2D", "StartScreenProjection", Fate::Inert, true},
    {"@3D", "EndScreenProjection", Fate::Inert, true},
    {"@Gc", "gcbegin", Fate::Translate, true},  // L-Py's StartGC
    // cpfg's generalized cylinders (its blackbox.c): @Gs starts one, @Gc adds a control
    // point (ontogen's F adds them), @Gt and @Gr shape its tangents.
    {"@Gs", "gcbegin", Fate::Translate, false, true},
    {"@Gc", "ContinueSpline", Fate::Inert, false, true},
    {"@Gt", "SplineTangents", Fate::Inert, false, true},
    {"@Gr", "RadiusTangents", Fate::Inert, false, true},
    {"@c", "Circle3D", Fate::Inert, false, true},  // a circle facing the turtle's heading
    {"@Ge", "gcend", Fate::Translate, false},
    // L-Py's names.
    {"Sphere", "sphere", Fate::Translate},
    {"Circle", "disc", Fate::Translate},
    {"StartGC", "gcbegin", Fate::Translate},
    {"EndGC", "gcend", Fate::Translate},
    {"IncColor", "color", Fate::Translate},
    {"SetColor", "color", Fate::Translate},
    {"SetWidth", "!", Fate::Translate},
    {"DecWidth", "!", Fate::Translate},
    {"Left", "+", Fate::Translate},
    {"Right", "-", Fate::Translate},
    {"Up", "^", Fate::Translate},
    {"Down", "&", Fate::Translate},
    {"RollL", "/", Fate::Translate},
    {"RollR", "\\", Fate::Translate},
    {"TurnAround", "|", Fate::Translate},
    {"RollToVert", "$", Fate::Translate},
    {"SB", "[", Fate::Translate},
    {"EB", "]", Fate::Translate},
    {"GetPos", "?P", Fate::Translate},
    {"GetHead", "?H", Fate::Translate},
    {"GetUp", "?U", Fate::Translate},
    {"GetLeft", "?L", Fate::Translate},
    {"GetRight", "", Fate::Refuse},
    {"GetFrame", "", Fate::Refuse},
    {"DecColor", "DecColor", Fate::Inert},
    {"nF", "nF", Fate::Inert},
    {"BP", "BP", Fate::Inert},
    {"EP", "EP", Fate::Inert},
    {"PP", "PP", Fate::Inert},
    {"MoveTo", "MoveTo", Fate::Inert},
    {"MoveRel", "MoveRel", Fate::Inert},
    {"LineTo", "LineTo", Fate::Inert},
    {"OLineTo", "OLineTo", Fate::Inert},
    {"LineRel", "LineRel", Fate::Inert},
    {"OLineRel", "OLineRel", Fate::Inert},
    {"Pinpoint", "Pinpoint", Fate::Inert},
    {"PinpointRel", "PinpointRel", Fate::Inert},
    {"SetHead", "SetHead", Fate::Inert},
    {"EulerAngles", "EulerAngles", Fate::Inert},
    {"iRollL", "iRollL", Fate::Inert},
    {"iRollR", "iRollR", Fate::Inert},
    {"RollToHorizontal", "RollToHorizontal", Fate::Inert},
    {"Box", "Box", Fate::Inert},
    {"Quad", "Quad", Fate::Inert},
    {"Label", "Label", Fate::Inert},
    {"IncWidth", "IncWidth", Fate::Inert},
    {"InterpolateColors", "InterpolateColors", Fate::Inert},
    {"TextureBaseColor", "TextureBaseColor", Fate::Inert},
    {"InterpolateTextureBaseColors", "InterpolateTextureBaseColors", Fate::Inert},
    {"DivScale", "DivScale", Fate::Inert},
    {"MultScale", "MultScale", Fate::Inert},
    {"SetScale", "SetScale", Fate::Inert},
    {"PglShape", "PglShape", Fate::Inert},
    {"Frame", "Frame", Fate::Inert},
    {"Arrow", "Arrow", Fate::Inert},
    {"Elasticity", "Elasticity", Fate::Inert},
    {"Tropism", "Tropism", Fate::Inert},
    {"SetContour", "SetContour", Fate::Inert},
    {"SectionResolution", "SectionResolution", Fate::Inert},
    {"SetGuide", "SetGuide", Fate::Inert},
    {"EndGuide", "EndGuide", Fate::Inert},
    {"Sweep", "Sweep", Fate::Inert},
    {"PositionOnGuide", "PositionOnGuide", Fate::Inert},
    {"TextureScale", "TextureScale", Fate::Inert},
    {"TextureUScale", "TextureUScale", Fate::Inert},
    {"TextureVScale", "TextureVScale", Fate::Inert},
    {"TextureVCoeff", "TextureVCoeff", Fate::Inert},
    {"TextureTranslation", "TextureTranslation", Fate::Inert},
    {"TextureRotation", "TextureRotation", Fate::Inert},
    {"TextureTransformation", "TextureTransformation", Fate::Inert},
    {"LeftReflection", "LeftReflection", Fate::Inert},
    {"UpReflection", "UpReflection", Fate::Inert},
    {"HeadingReflection", "HeadingReflection", Fate::Inert},
    {"StartScreenProjection", "StartScreenProjection", Fate::Inert},
    {"EndScreenProjection", "EndScreenProjection", Fate::Inert},
};

const Predefined* predefined(std::string_view name, Dialect dialect) {
  for (const Predefined& p : kPredefined)
    if (p.name == name && inDialect(p, dialect)) return &p;
  return nullptr;
}

std::string shown(std::string_view text) {
  return "'" + std::string(text) + "'";
}

}  // namespace

std::string cellName(std::string_view name) {
  return detail::isReadOnlyName(name) ? std::string(name) + "_" : std::string(name);
}

ForeignSyntax::Nested::Nested(const ForeignSyntax& syntax, uint32_t begin, uint32_t end) : depth(syntax.depth_) {
  if (++depth > kMaxConvertNesting) {
    --depth;
    syntax.fail(begin, end,
                "nested too deeply (more than " + std::to_string(kMaxConvertNesting) +
                    " levels of conditionals or alternatives)",
                false);
  }
}

void ForeignSyntax::fail(uint32_t begin, uint32_t end, std::string message, bool untranslatable) const {
  throw ConvertError{begin, end > begin ? end : begin + 1, std::move(message), untranslatable};
}

void ForeignSyntax::trim(uint32_t& begin, uint32_t& end) const {
  while (begin < end && isSpace(text_[begin])) ++begin;
  while (end > begin && isSpace(text_[end - 1])) --end;
}

uint32_t ForeignSyntax::find(uint32_t begin, uint32_t end, std::string_view what) const {
  int depth = 0;
  for (uint32_t at = begin; at < end; ++at) {
    const char c = text_[at];
    if (c == '(') ++depth;
    if (c == ')') --depth;
    if (depth == 0 && text_.compare(at, what.size(), what) == 0 && at + what.size() <= end) return at;
  }
  return end;
}

// The end of the label that starts at `at` (before its parameters).
uint32_t ForeignSyntax::moduleEnd(uint32_t at, uint32_t end, std::string& label) const {
  const char c = text_[at];
  // Query modules ?P ?H ?L ?U (ABOP section 1.10), in both tools; L-Py's ?R ?F as well.
  if (c == '?' && at + 1 < end && isLetter(text_[at + 1])) {
    label = std::string(text_.substr(at, 2));
    if (label == "?R" || label == "?F")
      fail(at, at + 2,
           "L-Py's query " + shown(label) +
               " has no cell-language counterpart: ontogen's turtle fills ?P, ?H, ?L and ?U only, so the word "
               "would differ");
    return at + 2;
  }
  // '@' modules: the longest predefined name, as the tools read them (@GcI is @Gc I).
  if (c == '@' && at + 1 < end && isNameChar(text_[at + 1])) {
    size_t best = 0;
    for (const Predefined& p : kPredefined)
      if (p.name[0] == '@' && inDialect(p, dialect_) && p.name.size() > best &&
          at + p.name.size() <= end && text_.compare(at, p.name.size(), p.name) == 0)
        best = p.name.size();
    if (best == 0) {
      uint32_t stop = at + 1;
      while (stop < end && isNameChar(text_[stop])) ++stop;
      fail(at, stop,
           std::string(dialectName(dialect_)) + "'s module " + shown(text_.substr(at, stop - at)) +
               " is none ontogen can translate (it knows @O, @o, @v, @M, @R, @L, @b, @Ge, @Gc" +
               (dialect_ == Dialect::LPy ? ", @B, @g, @h, @D, @Dd, @Di, @Ts, @Tp, @2D, @3D" : ", @Gs, @Gt, @Gr, @c") +
               ")");
    }
    label = std::string(text_.substr(at, best));
    return at + static_cast<uint32_t>(best);
  }
  // A predefined surface, ~l: one letter names it in both tools.
  if (c == '~' && at + 1 < end && isLetter(text_[at + 1])) {
    label = std::string(text_.substr(at, 2));
    return at + 2;
  }
  if (dialect_ == Dialect::LPy && isLetter(c)) {
    // Longest declared or predefined name first; otherwise one letter is one module.
    size_t best = 1;
    auto consider = [&](std::string_view name) {
      if (name.size() > best && at + name.size() <= end && text_.compare(at, name.size(), name) == 0)
        best = name.size();
    };
    for (const std::string& name : declaredNames) consider(name);
    for (const Predefined& p : kPredefined)
      if (p.name[0] != '@') consider(p.name);
    label = std::string(text_.substr(at, best));
    return at + static_cast<uint32_t>(best);
  }
  if (isNameChar(c) || isCellSymbol(c) || c == ';' || c == ',' || c == '{' || c == '}' || c == '.' ||
      (c == '#' && dialect_ == Dialect::Cpfg)) {
    label = std::string(1, c);
    return at + 1;
  }
  std::string name(1, c);
  if (static_cast<unsigned char>(c) >= 0x80) {
    uint32_t stop = at + 1;
    while (stop < end && (static_cast<unsigned char>(text_[stop]) & 0xC0) == 0x80) ++stop;
    name = std::string(text_.substr(at, stop - at));
  }
  fail(at, at + 1,
       "the module " + shown(name) + " of " + std::string(dialectName(dialect_)) +
           " has no cell-language spelling (labels are names or one of + - ^ & / \\ | ! < > [ ] $ ~ @ %)");
}

void ForeignSyntax::warnOnce(const std::string& label, uint32_t begin, uint32_t end, std::string message) const {
  if (!warned_.insert(label).second) return;
  warnings.push_back({SourceRange{begin, end > begin ? end : begin + 1}, std::move(message)});
}

// A module of the other tool's vocabulary as the cell language has it (kPredefined).
void ForeignSyntax::vocabulary(ModuleText& module, uint32_t begin, uint32_t end, bool pattern) const {
  if (auto alias = aliases.find(module.label); alias != aliases.end()) module.label = alias->second;
  if (declaredNames.count(module.label)) return;  // the file's own module
  const std::string tool(dialectName(dialect_));
  auto inert = [&](std::string name, const std::string& what) {
    warnOnce(module.label, begin, end,
             tool + "'s " + what + " " + shown(module.label) +
                 " has no counterpart in ontogen's turtle: it stays a module named " + shown(name) +
                 ", so the word is " + tool + "'s, but it draws nothing");
    module.label = std::move(name);
  };
  const std::string label = module.label;
  if (label == "?P" || label == "?H" || label == "?L" || label == "?U") {
    if (module.hasArgs) return;
    // L-Py writes a query bare; ontogen's has the three parameters the turtle fills.
    if (pattern)
      fail(begin, end,
           "a query " + shown(label) + " without parameters in a pattern: write " + label +
               "(x, y, z) to match it",
           false);
    module.hasArgs = true;
    module.args = {"0", "0", "0"};
    return;
  }
  if (label == ";" || (label == "," && module.hasArgs && !module.args.empty())) {
    module.label = "color";  // ;  and ;(i) take the next colour or colour i; ,(i) colour i
    return;
  }
  if (label == ",") return inert("DecColor", "colour module (the previous colour)");
  if (label == "{") return inert("BP", "polygon module");
  if (label == "}") return inert("EP", "polygon module");
  if (label == ".") return inert("PP", "polygon module");
  if (label == "#") return inert("IncWidth", "module");
  if (label.size() == 2 && label[0] == '~') return inert("Surface_" + label.substr(1), "surface");
  const Predefined* p = predefined(label, dialect_);
  if (!p) return;
  if (p->fate == Fate::Refuse)
    fail(begin, end, tool + "'s module " + shown(label) + " has no cell-language counterpart; the word would differ");
  if (p->fate == Fate::Inert) return inert(std::string(p->cell), "module");
  if (p->cell == "color" && module.args.size() > 1) return inert("SetColor", "colour by components");
  module.label = std::string(p->cell);
}

std::vector<ModuleText> ForeignSyntax::modules(uint32_t begin, uint32_t end, bool pattern) const {
  std::vector<ModuleText> result;
  uint32_t at = begin;
  while (at < end) {
    if (isSpace(text_[at])) {
      ++at;
      continue;
    }
    if (text_[at] == '(' || text_[at] == ')')
      fail(at, at + 1, "expected a module before " + shown(text_.substr(at, 1)), false);
    ModuleText module;
    const uint32_t moduleBegin = at;
    if (dialect_ == Dialect::LPy && text_.compare(at, 4, "None") == 0 && at + 4 <= end &&
        (at + 4 == end || !isNameChar(text_[at + 4])) && !declaredNames.count("None")) {
      if (!pattern) fail(at, at + 4, "L-Py's None stands in a context, for no module there", false);
      // L-Py's None in a context: no module there, the cell language's ∅ (the start of
      // the word on the left, the end of the branch or word on the right).
      module.label = "∅";
      at += 4;
      result.push_back(std::move(module));
      continue;
    }
    if (text_[at] == '*' && pattern) {
      module.label = "*";  // a wildcard in a context
      ++at;
    } else if (text_[at] == '*') {
      fail(at, at + 1, "'*' (the empty word) stands alone as a successor, as in A --> *", false);
    } else if (pattern && dialect_ == Dialect::LPy && text_.substr(at, 3) == "or(") {
      module.label = "or";  // L-Py's alternatives, below
      at += 2;
    } else {
      at = moduleEnd(at, end, module.label);
    }
    if (pattern && dialect_ == Dialect::LPy && module.label == "x" && at < end && text_[at] == '(' &&
        !declaredNames.count("x"))
      fail(moduleBegin, at + 1,
           "L-Py's repetition x(...) in a context has no cell-language counterpart (a context of the cell "
           "language is a fixed sequence of modules)");
    if (at < end && text_[at] == '(') {
      int depth = 0;
      uint32_t stop = at;
      for (; stop < end; ++stop) {
        if (text_[stop] == '(') ++depth;
        if (text_[stop] == ')' && --depth == 0) break;
      }
      if (stop >= end) fail(at, end, "the parameters of " + shown(module.label) + " have no closing ')'", false);
      if (pattern && dialect_ == Dialect::LPy && module.label == "or") {
        const Nested nested(*this, moduleBegin, stop + 1);
        // L-Py's or(B(x) C, D) in a context: the cell language's alternatives (B(x) C | D).
        std::string group;
        uint32_t argBegin = at + 1;
        for (uint32_t comma = find(argBegin, stop, ","); argBegin <= stop; comma = find(argBegin, stop, ",")) {
          std::string sequence;
          uint32_t a = argBegin, b = comma;
          trim(a, b);
          // L-Py's None: an alternative of nothing.
          const bool none = text_.substr(a, b - a) == "None";
          for (const ModuleText& item : none ? std::vector<ModuleText>{} : modules(argBegin, comma, true)) {
            sequence += (sequence.empty() ? "" : " ") + item.label;
            if (!item.hasArgs) continue;
            sequence += "(";
            for (size_t k = 0; k < item.args.size(); ++k) sequence += (k ? ", " : "") + item.args[k];
            sequence += ")";
          }
          group += (group.empty() ? "(" : sequence.empty() ? " |" : " | ") + sequence;
          if (comma == stop) break;
          argBegin = comma + 1;
        }
        module.label = group + ")";
        at = stop + 1;
        result.push_back(std::move(module));
        continue;
      }
      module.hasArgs = true;
      bool skippedLabel = false;  // L-Py's *(name, ...)
      uint32_t argBegin = at + 1;
      // Parameters split at commas outside inner parentheses.
      for (uint32_t comma = find(argBegin, stop, ","); argBegin <= stop; comma = find(argBegin, stop, ",")) {
        uint32_t a = argBegin, b = comma;
        trim(a, b);
        if (a == b) {
          if (comma == stop && module.args.empty()) break;  // X()
          fail(argBegin, comma, "an empty parameter of " + shown(module.label), false);
        }
        if (pattern) {
          std::string_view name = text_.substr(a, b - a);
          bool isName = isLetter(name[0]);
          for (char c : name) isName = isName && isNameChar(c);
          // A value pattern, A(3) or A(-1.5): a number, as the cell language writes it.
          bool isNumber = !name.empty();
          size_t digits = 0;
          for (size_t k = 0; k < name.size(); ++k) {
            const char c = name[k];
            if (std::isdigit(static_cast<unsigned char>(c)))
              ++digits;
            else if (!(c == '.' || (c == '-' && k == 0)))
              isNumber = false;
          }
          isNumber = isNumber && digits > 0;
          if (name[0] == '*')
            fail(a, b,
                 "L-Py's '*args' takes any number of parameters; a pattern of the cell language takes a "
                 "fixed number, as in *(x, y)");
          if (!isName && !isNumber)
            fail(a, b,
                 "a pattern's parameter " + shown(std::string(name)) +
                     " is neither a name nor a number; write a "
                     "name and test it in a condition, as in " +
                     module.label + "(x) : x == ...");
          // L-Py's wildcard names the module's label first, *(name, x): the cell language
          // has numbers only, so its wildcard binds the parameters alone.
          if (dialect_ == Dialect::LPy && module.label == "*" && !skippedLabel)
            skippedLabel = true;
          else
            module.args.push_back(isNumber ? std::string(name) : cellName(name));
        } else {
          module.args.push_back(expression(a, b));
        }
        if (comma == stop) break;
        argBegin = comma + 1;
      }
      at = stop + 1;
    }
    vocabulary(module, moduleBegin, at, pattern);
    result.push_back(std::move(module));
  }
  return result;
}

std::string ForeignSyntax::maximumDepth(uint32_t begin, uint32_t end) const {
  std::string value = expression(begin, end);
  char* stop = nullptr;
  const double depth = std::strtod(value.c_str(), &stop);
  if (stop == value.c_str() + value.size() && depth > kMaxRewriteDepth) {
    trim(begin, end);
    warnings.push_back({SourceRange{begin, end},
                        "maximum depth " + value + " is above ontogen's limit of " +
                            std::to_string(kMaxRewriteDepth) + ": the block rewrites at most " +
                            std::to_string(kMaxRewriteDepth) +
                            " deep, which differs only where the rules recurse deeper"});
    value = std::to_string(kMaxRewriteDepth);
  }
  return value;
}

std::vector<std::string> ForeignSyntax::symbols(uint32_t begin, uint32_t end) const {
  std::vector<std::string> result;
  for (const ModuleText& module : modules(begin, end, false)) result.push_back(module.label);
  return result;
}

// The conditionals, C's `c ? a : b` and Python's `a if c else b`, become the cell
// language's if(c, a, b); they bind loosest, so they are split off first.
std::optional<std::string> ForeignSyntax::conditional(uint32_t begin, uint32_t end) const {
  if (dialect_ == Dialect::Cpfg) {
    const uint32_t question = find(begin, end, "?");
    if (question == end) return std::nullopt;
    const Nested nested(*this, question, question + 1);
    // The ':' that matches this '?' (conditionals nest to the right).
    int open = 0;
    uint32_t colon = end;
    int depth = 0;
    for (uint32_t at = question + 1; at < end && colon == end; ++at) {
      if (text_[at] == '(') ++depth;
      if (text_[at] == ')') --depth;
      if (depth != 0) continue;
      if (text_[at] == '?') ++open;
      if (text_[at] == ':' && open-- == 0) colon = at;
    }
    if (colon == end) fail(question, question + 1, "a '?' without its ':'", false);
    return "if(" + condition(begin, question) + ", " + expression(question + 1, colon) + ", " +
           expression(colon + 1, end) + ")";
  }
  auto word = [&](uint32_t from, std::string_view name) {
    for (uint32_t at = find(from, end, name); at < end; at = find(at + 1, end, name)) {
      const bool startsWord = at == begin || !isNameChar(text_[at - 1]);
      const bool endsWord = at + name.size() >= end || !isNameChar(text_[at + name.size()]);
      if (startsWord && endsWord) return at;
    }
    return end;
  };
  const uint32_t ifAt = word(begin, "if");
  if (ifAt == end) return std::nullopt;
  const Nested nested(*this, ifAt, ifAt + 2);
  const uint32_t elseAt = word(ifAt + 2, "else");
  if (elseAt == end) fail(ifAt, ifAt + 2, "Python's 'if' without 'else' in an expression", false);
  return "if(" + condition(ifAt + 2, elseAt) + ", " + expression(begin, ifAt) + ", " + expression(elseAt + 4, end) +
         ")";
}

bool ForeignSyntax::atomic(uint32_t begin, uint32_t end) const {
  trim(begin, end);
  if (begin == end) return false;
  uint32_t at = begin;
  while (at < end && (isNameChar(text_[at]) || text_[at] == '.')) ++at;
  if (at == end) return true;
  while (at < end && isSpace(text_[at])) ++at;
  if (at < end && text_[at] == '(' && (at == begin || isNameChar(text_[begin]))) {
    int depth = 0;
    for (uint32_t k = at; k < end; ++k) {
      if (text_[k] == '(') ++depth;
      if (text_[k] == ')' && --depth == 0) return k + 1 == end;
    }
  }
  return false;
}

std::string ForeignSyntax::inlined(const Function& function, uint32_t begin, uint32_t at, uint32_t open,
                                   uint32_t end, uint32_t& stop) const {
  const std::string name(text_.substr(at, open - at));
  int depth = 0;
  uint32_t close = open;
  for (; close < end; ++close) {
    if (text_[close] == '(') ++depth;
    if (text_[close] == ')' && --depth == 0) break;
  }
  if (close >= end) fail(at, end, "the call of '" + name + "' has no closing ')'", false);
  const Nested nested(*this, at, close + 1);
  std::vector<std::pair<std::string, std::string>> arguments;
  uint32_t a = open + 1, b = close;
  trim(a, b);
  for (uint32_t from = open + 1; a < b && from <= close;) {
    const uint32_t comma = find(from, close, ",");
    if (arguments.size() < function.parameters.size()) {
      std::string value = expression(from, comma);
      bool single = true;  // a name or a number needs no parentheses
      for (char c : value) single = single && (isNameChar(c) || c == '.');
      arguments.emplace_back(function.parameters[arguments.size()], single ? value : "(" + value + ")");
    }
    else
      arguments.emplace_back("", "");
    from = comma + 1;
  }
  if (arguments.size() != function.parameters.size())
    fail(at, close + 1,
         "the function '" + name + "' takes " + std::to_string(function.parameters.size()) +
             " parameters; this call gives " + std::to_string(arguments.size()),
         false);
  // A C macro is replaced as text: its value is the same as that of the parenthesised
  // expression only where each parameter and the body are single operands where they
  // stand; elsewhere (#define sq(x) x*x with sq(a+1)) C reads another expression.
  if (dialect_ == Dialect::Cpfg) {
    auto alone = [](char before, char after) {
      return (before == '\0' || before == '(' || before == ',') && (after == '\0' || after == ')' || after == ',');
    };
    if (!atomic(function.begin, function.end) && !alone(previous(at, begin), following(close + 1, end)))
      fail(at, close + 1,
           "the macro '" + name +
               "' is replaced as text by C: its value, which is no single operand, would join the operators around "
               "this call; put the macro's value in parentheses");
    uint32_t from = open + 1;
    for (const std::string& parameter : function.parameters) {
      const uint32_t comma = find(from, close, ",");
      if (!atomic(from, comma)) {
        for (uint32_t k = function.begin; k < function.end; ++k) {
          if (text_.compare(k, parameter.size(), parameter) != 0 || (k > 0 && isNameChar(text_[k - 1])) ||
              (k + parameter.size() < text_.size() && isNameChar(text_[k + parameter.size()])))
            continue;
          const uint32_t after = k + static_cast<uint32_t>(parameter.size());
          if (!alone(previous(k, function.begin), following(after, function.end)))
            fail(from, comma,
                 "the macro '" + name + "' is replaced as text by C: this argument, which is no single operand, "
                 "would join the operators around '" + parameter + "' in its value; put the argument in parentheses");
        }
      }
      from = comma + 1;
    }
  }
  const std::string body = expression(function.begin, function.end);
  // An argument that draws a random number is drawn once by Python: it may be read once
  // (a C macro draws it as often as its text names it, as the cell language does).
  for (const auto& [parameter, value] : arguments) {
    size_t uses = 0;
    for (size_t k = body.find(parameter); k != std::string::npos; k = body.find(parameter, k + 1))
      if ((k == 0 || !(isNameChar(body[k - 1]) || body[k - 1] == '.')) &&
          (k + parameter.size() == body.size() || !isNameChar(body[k + parameter.size()])))
        ++uses;
    bool draws = false;
    for (std::string_view f : {"uniform(", "gaussian(", "ran(", "bernoulli("})
      draws = draws || value.find(f) != std::string::npos;
    if (uses > 1 && draws && dialect_ == Dialect::LPy)  // C's macros draw again as cpfg does
      fail(at, close + 1,
           "an argument that draws a random number, read " + std::to_string(uses) + " times by '" + name +
               "': the cell language would draw it anew each time; pass a local holding the draw");
  }
  stop = close + 1;
  std::string value = "(" + substituted(body, arguments) + ")";
  inlinedBytes_ += value.size();
  if (inlinedBytes_ > kMaxInlinedBytes)
    fail(at, stop,
         "the calls of helper functions or macros write more than " + std::to_string(kMaxInlinedBytes >> 20) +
             " MiB (calls within calls multiply)",
         false);
  return value;
}

char ForeignSyntax::previous(uint32_t at, uint32_t from) const {
  while (at > from && isSpace(text_[at - 1])) --at;
  return at == from ? '\0' : text_[at - 1];
}

char ForeignSyntax::following(uint32_t at, uint32_t to) const {
  while (at < to && isSpace(text_[at])) ++at;
  return at == to ? '\0' : text_[at];
}

bool ForeignSyntax::plainMacro(const Function& macro, int depth) const {
  if (!atomic(macro.begin, macro.end)) return false;
  uint32_t a = macro.begin, b = macro.end;
  trim(a, b);
  // A name that is itself a macro is as plain as that one's value.
  if (auto inner = macros.find(text_.substr(a, b - a)); inner != macros.end())
    return depth < kMaxConvertNesting && &inner->second != &macro && plainMacro(inner->second, depth + 1);
  return true;
}

namespace {

// The bytes [open, close] of a call's parentheses: the offset of its ')', or `end`.
uint32_t closingParenthesis(std::string_view text, uint32_t open, uint32_t end) {
  int depth = 0;
  for (uint32_t at = open; at < end; ++at) {
    if (text[at] == '(') ++depth;
    if (text[at] == ')' && --depth == 0) return at;
  }
  return end;
}

bool drawsRandom(std::string_view text) {
  for (std::string_view f : {"uniform(", "gaussian(", "ran(", "bernoulli("})
    if (text.find(f) != std::string_view::npos) return true;
  return false;
}

}  // namespace

std::optional<std::string> ForeignSyntax::degreeCall(const std::string& name, uint32_t at, uint32_t open,
                                                     uint32_t end, uint32_t& stop) const {
  const bool direct = name == "sin" || name == "cos" || name == "tan";
  const bool inverse = name == "asin" || name == "acos" || name == "atan";
  if (name == "atan2")
    fail(at, open,
         "cpfg's atan2, in degrees, whose arguments its evaluator takes in an order of its own: write "
         "atan(y / x) with the quadrant's test");
  if (!direct && !inverse) return std::nullopt;
  const uint32_t close = closingParenthesis(text_, open, end);
  if (close >= end) fail(at, end, "the call of '" + name + "' has no closing ')'", false);
  const Nested nested(*this, at, close + 1);
  const std::string x = expression(open + 1, close);
  stop = close + 1;
  // cpfg's angles are degrees (generate.c), the cell language's radians.
  return direct ? name + "(rad(" + x + "))" : "deg(" + name + "(" + x + "))";
}

std::string ForeignSyntax::pythonRound(uint32_t at, uint32_t open, uint32_t end, uint32_t& stop) const {
  const uint32_t close = closingParenthesis(text_, open, end);
  if (close >= end) fail(at, end, "the call of 'round' has no closing ')'", false);
  const Nested nested(*this, at, close + 1);
  if (find(open + 1, close, ",") < close)
    fail(at, close + 1,
         "Python's round(x, n), to n decimals of x's exact binary value, has no cell-language counterpart; "
         "round(x * 10 ** n) / 10 ** n is near it");
  const std::string x = expression(open + 1, close);
  stop = close + 1;
  // Python 2 takes halves away from zero, as the cell language's round does.
  if (python2) return "round(" + x + ")";
  if (drawsRandom(x))
    fail(at, close + 1,
         "Python's round() of a value that draws a random number: Python 3 takes halves to the even "
         "neighbour, which writes the value three times, and the cell language would draw it anew each time; "
         "round a local holding the draw");
  // Python 3 takes halves to the even neighbour (round(2.5) is 2): x / 2 is then no half.
  return "if(fract(" + x + ") == 0.5, 2 * round((" + x + ") / 2), round(" + x + "))";
}

std::string ForeignSyntax::expression(uint32_t begin, uint32_t end) const {
  return expression(begin, end, nullptr);
}

std::string ForeignSyntax::condition(uint32_t begin, uint32_t end) const {
  truthNext_ = true;
  return expression(begin, end, nullptr);
}

std::string ForeignSyntax::expression(uint32_t begin, uint32_t end, std::vector<ExpressionToken>* raw) const {
  const bool truth = std::exchange(truthNext_, false);
  if (std::optional<std::string> chosen = conditional(begin, end)) {
    if (raw) *raw = {ExpressionToken{*chosen, begin, end, false}};
    return *chosen;
  }
  const bool python = dialect_ == Dialect::LPy;
  std::string out;
  // The tokens as written, for Python's operators the cell language spells otherwise.
  std::vector<ExpressionToken> tokens;
  uint32_t at = begin;
  auto emit = [&](std::string_view token, bool glueLeft = false, uint32_t length = 0) {
    tokens.push_back({std::string(token), at, at + (length ? length : static_cast<uint32_t>(token.size())), glueLeft});
    if (!out.empty() && !glueLeft && out.back() != '(' && out.back() != '!') out += ' ';
    out += token;
  };
  auto code = [&](uint32_t from, uint32_t stop, const std::string& what) {
    fail(from, stop,
         what + (python ? ": Python code, which ontogen convert does not translate (it reads L-Py's declarative "
                          "part: modules, productions with -->, conditions over arithmetic)"
                        : ": C code, which ontogen convert does not translate (it reads cpfg's productions, "
                          "conditions and expressions over arithmetic)"));
  };
  // Whether a conditional may stand inside parentheses here (looked for once).
  bool mayNestConditionals = false;
  for (uint32_t k = begin; k < end && !mayNestConditionals; ++k)
    mayNestConditionals = python ? text_.compare(k, 2, "if") == 0 && k + 2 <= end : text_[k] == '?';
  // Python's `not` binds looser than comparisons (`not x == 0` is `!(x == 0)`): its
  // operand runs to the next `and`, `or`, ',' or ')' at the same depth.
  std::vector<int> notDepths;
  int depth = 0;
  auto closeNots = [&] {
    while (!notDepths.empty() && notDepths.back() == depth) {
      tokens.push_back({")", at, at + 1, true});
      out += ")";
      notDepths.pop_back();
    }
  };
  while (at < end) {
    const char c = text_[at];
    if (isSpace(c)) {
      ++at;
      continue;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) ||
        (c == '.' && at + 1 < end && std::isdigit(static_cast<unsigned char>(text_[at + 1])))) {
      uint32_t stop = at;
      while (stop < end && (std::isdigit(static_cast<unsigned char>(text_[stop])) || text_[stop] == '.')) ++stop;
      if (stop < end && (text_[stop] == 'e' || text_[stop] == 'E')) {
        uint32_t exponent = stop + 1;
        if (exponent < end && (text_[exponent] == '+' || text_[exponent] == '-')) ++exponent;
        if (exponent < end && std::isdigit(static_cast<unsigned char>(text_[exponent]))) {
          stop = exponent;
          while (stop < end && std::isdigit(static_cast<unsigned char>(text_[stop]))) ++stop;
        }
      }
      emit(text_.substr(at, stop - at), false, stop - at);
      at = stop;
      continue;
    }
    if (isLetter(c)) {
      uint32_t stop = at;
      while (stop < end && (isNameChar(text_[stop]) || (python && text_[stop] == '.'))) ++stop;
      std::string name(text_.substr(at, stop - at));
      if (python) {
        // import random as rd: rd.uniform is random.uniform.
        if (const size_t dot = name.find('.'); dot != std::string::npos)
          if (auto alias = moduleAliases.find(std::string_view(name).substr(0, dot)); alias != moduleAliases.end())
            name = alias->second + name.substr(dot);
      }
      // cpfg's variables of the blocks around each step, unless a parameter hides one.
      if (auto variable = stepVariables.find(name); !python && variable != stepVariables.end() && !bound_.count(name)) {
        if (variable->second.stepEnd && inHomomorphism)
          fail(at, stop,
               "the variable '" + name +
                   "', which cpfg's EndEach: block changes after each step: after the last one, where the "
                   "homomorphism reads it, it is one step on, which the converter does not write");
        emit("(" + variable->second.value + ")", false, stop - at);
        at = stop;
        continue;
      }
      // cpfg's macro `#define X 1+2` among operators: its tokens, as C's replacement
      // reads them (2*X is 2*1+2).
      if (auto macro = macros.find(name); !python && macro != macros.end()) {
        const char before = previous(at, begin), after = following(stop, end);
        // In a macro's value being put in, "alone" is the place of the outer name.
        const bool alone = !raw && (before == '\0' || before == '(' || before == ',') &&
                           (after == '\0' || after == ')' || after == ',');
        const bool plain = plainMacro(macro->second);
        if (!macro->second.constant && (plain || alone)) {
          const Nested nested(*this, at, stop);
          emit("(" + expression(macro->second.begin, macro->second.end) + ")", false, stop - at);
          at = stop;
          continue;
        }
        if (!plain && !alone) {
          if (find(macro->second.begin, macro->second.end, "?") < macro->second.end)
            fail(at, stop,
                 "the macro '" + name +
                     "' is replaced as text by C: its value, a conditional c ? a : b, would take the operators "
                     "around it into its condition and branches; put the macro's value in parentheses");
          const Nested nested(*this, at, stop);
          std::vector<ExpressionToken> inner;
          expression(macro->second.begin, macro->second.end, &inner);
          for (const ExpressionToken& token : inner) {
            tokens.push_back({token.text, at, stop, token.glued});
            if (!out.empty() && !token.glued && out.back() != '(' && out.back() != '!') out += ' ';
            out += token.text;
          }
          at = stop;
          continue;
        }
      }
      if (auto function = functions.find(name); function != functions.end()) {
        uint32_t open = stop;
        while (open < end && isSpace(text_[open])) ++open;
        if (open < end && text_[open] == '(') {
          uint32_t after = open;
          const std::string value = inlined(function->second, begin, at, open, end, after);
          emit(value, false, after - at);
          at = after;
          continue;
        }
      }
      if (!python) {
        uint32_t open = stop;
        while (open < end && isSpace(text_[open])) ++open;
        if (open < end && text_[open] == '(') {
          uint32_t after = open;
          if (std::optional<std::string> call = degreeCall(name, at, open, end, after)) {
            emit(*call, false, after - at);
            at = after;
            continue;
          }
          if (name == "fabs") name = "abs";
          if (name == "nran") name = "gaussian";  // cpfg's nran(mean, deviation)
        }
      }
      if (python) {
        if (name.rfind("math.", 0) == 0) name = name.substr(5);  // math.sqrt is sqrt
        if (name.rfind("random.", 0) == 0) name = name.substr(7);  // random.uniform is uniform
        uint32_t next = stop;
        while (next < end && isSpace(text_[next])) ++next;
        if (next < end && text_[next] == '(') {
          // Python's functions as the cell language names them; random ones draw from
          // ontogen's seeded streams (docs/LANGUAGE.md 4.12).
          static constexpr std::pair<std::string_view, std::string_view> kCalls[] = {
              {"random", "uniform"}, {"gauss", "gaussian"},  {"normalvariate", "gaussian"},
              {"normal", "gaussian"}, {"int", "trunc"},      {"radians", "rad"},
              {"degrees", "deg"},     {"fabs", "abs"},
          };
          for (const auto& [pythonName, cell] : kCalls)
            if (name == pythonName) name = std::string(cell);
          if (name == "round") {
            uint32_t after = next;
            const std::string value = pythonRound(at, next, end, after);
            emit(value, false, after - at);
            at = after;
            continue;
          }
          if (name == "float") {  // float(x) is x
            at = stop;
            continue;
          }
          if (name == "randint" || name == "choice" || name == "randrange" || name == "shuffle" ||
              name == "sample" || name == "len" || name == "range" || name == "str")
            code(at, stop, "Python's " + shown(name));
        }
        if (name.find('.') != std::string::npos) code(at, stop, "the attribute " + shown(name));
        if (name == "and" || name == "or") {
          closeNots();
          name = name == "and" ? "&&" : "||";
        } else if (name == "not") {
          emit("!", false, 3);
          tokens.push_back({"(", at, at + 3, true});
          out += "(";
          notDepths.push_back(depth);
          at = stop;
          continue;
        } else if (name == "True")
          name = "1";
        else if (name == "False")
          name = "0";
        else if (name == "lambda" || name == "for" || name == "in" || name == "is")
          code(at, stop, "Python's " + shown(name));
      }
      {
        uint32_t next = stop;
        while (next < end && isSpace(text_[next])) ++next;
        if (next == end || text_[next] != '(') name = cellName(name);
      }
      emit(name, false, stop - at);
      at = stop;
      continue;
    }
    auto two = [&](std::string_view op) { return text_.compare(at, 2, op) == 0 && at + 1 < end; };
    if (two("**")) {
      if (!python) fail(at, at + 2, "'**' is no operator of cpfg's expressions", false);
      emit("^");
      at += 2;
    } else if (two("//")) {
      if (!python) code(at, at + 2, "'//'");
      emit("//");
      at += 2;
    } else if (two("<>")) {  // cpfg's and Python 2's other spelling of !=
      emit("!=", false, 2);
      at += 2;
    } else if (two("==") || two("!=") || two("<=") || two(">=") || two("&&") || two("||")) {
      emit(text_.substr(at, 2));
      at += 2;
    } else if (c == '=') {
      code(at, at + 1, "an assignment");
    } else if (c == '(') {
      // A call keeps its '(' on the name: f(x).
      const bool call = !out.empty() && (isNameChar(out.back()));
      // A conditional inside parentheses, (c ? a : b) or f(a if c else b, 2): each
      // argument read as an expression of its own, where conditionals are split off.
      if (depth >= kMaxConvertParentheses)
        fail(at, at + 1,
             "nested too deeply (more than " + std::to_string(kMaxConvertParentheses) + " parentheses)", false);
      int inner = 0;
      uint32_t close = at;
      if (mayNestConditionals)
        for (; close < end; ++close) {
          if (text_[close] == '(') ++inner;
          if (text_[close] == ')' && --inner == 0) break;
        }
      bool conditional = false;
      if (mayNestConditionals && close < end) {
        if (!python) {
          conditional = find(at + 1, close, "?") < close;
        } else {
          for (uint32_t k = find(at + 1, close, "if"); k < close && !conditional; k = find(k + 1, close, "if"))
            conditional = !isNameChar(text_[k - 1]) && k + 2 < close && !isNameChar(text_[k + 2]);
        }
      }
      if (conditional) {
        const Nested nested(*this, at, close + 1);
        std::string group = "(";
        for (uint32_t from = at + 1; from <= close;) {
          const uint32_t comma = find(from, close, ",");
          group += (from > at + 1 ? ", " : "") + expression(from, comma);
          from = comma + 1;
        }
        emit(group + ")", call, close + 1 - at);
        at = close + 1;
        continue;
      }
      emit("(", call);
      ++depth;
      ++at;
    } else if (c == ')' || c == ',') {
      closeNots();
      if (c == ')') --depth;
      emit(text_.substr(at, 1), true);
      ++at;
    } else if (std::string_view("+-*/%<>!^").find(c) != std::string_view::npos) {
      if (c == '^' && python) code(at, at + 1, "Python's '^' (exclusive or; a power is '**')");
      // Python 2 divides truly where an operand is a float: a float literal beside the '/'.
      auto floatLiteral = [](std::string_view token) {
        return !token.empty() && (std::isdigit(static_cast<unsigned char>(token[0])) || token[0] == '.') &&
               token.find_first_of(".eE") != std::string_view::npos;
      };
      auto literalAfter = [&] {
        uint32_t k = at + 1;
        while (k < end && isSpace(text_[k])) ++k;
        uint32_t stop = k;
        while (stop < end && (isNameChar(text_[stop]) || text_[stop] == '.')) ++stop;
        return floatLiteral(text_.substr(k, stop - k));
      };
      if (c == '/' && python && python2 && !futureDivision &&
          !(!tokens.empty() && floatLiteral(tokens.back().text)) && !literalAfter()) {
        uint32_t line = 1;
        for (uint32_t k = 0; k < *python2; ++k) line += text_[k] == '\n';
        fail(at, at + 1,
             "'/' in a file of Python 2 (line " + std::to_string(line) +
                 "), where it floors between integers, which the converter cannot tell from other numbers: "
                 "write '//' for a floor, or a float operand beside it (x / 2.0, x * 1.0 / y) for a quotient");
      }
      emit(text_.substr(at, 1));
      ++at;
    } else if (c == '?' || c == ':') {
      fail(at, at + 1, "unexpected " + shown(text_.substr(at, 1)) + " in an expression", false);
    } else if (c == '{' || c == '}' || c == ';') {
      code(at, at + 1, "a block or statement " + shown(text_.substr(at, 1)));
    } else if (c == '[' || c == ']' || c == '"' || c == '\'') {
      code(at, at + 1, python ? "a list, index or string" : "an array or string");
    } else {
      fail(at, at + 1, "unexpected " + shown(text_.substr(at, 1)) + " in an expression", false);
    }
  }
  depth = 0;
  closeNots();
  if (out.empty()) fail(begin, end, "expected an expression", false);
  if (raw) {
    *raw = std::move(tokens);
    return out;
  }
  if (std::optional<std::string> rewritten = foreignOperators(*this, tokens, dialect_, truth)) return *rewritten;
  return out;
}

void ForeignSyntax::checkPredecessor(const ModuleText& predecessor, uint32_t begin, uint32_t end) const {
  trim(begin, end);
  if (predecessor.label == "*")
    fail(begin, end,
         "a wildcard predecessor: a production of the cell language belongs to the module it rewrites; "
         "write one production per label");
  if (!predecessor.label.empty() && predecessor.label[0] == '(')
    fail(begin, end, "alternatives as the predecessor: write one production per alternative");
}

Statement ForeignSyntax::production(uint32_t begin, uint32_t end) const {
  Statement s;
  uint32_t arrow = find(begin, end, "-->");
  uint32_t arrowEnd = arrow + 3;
  if (arrow == end) {
    arrow = find(begin, end, "->");
    arrowEnd = arrow + 2;
  }
  // The head: left < predecessor > right : condition.
  uint32_t headEnd = arrow;
  const uint32_t colon = find(begin, arrow, ":");
  uint32_t condBegin = arrow, condEnd = arrow;
  if (colon < arrow) {
    uint32_t a = colon + 1, b = arrow;
    trim(a, b);
    if (text_.substr(a, b - a) != "*") {  // cpfg's '*': no condition
      condBegin = a;
      condEnd = b;
    }
    headEnd = colon;
  }
  uint32_t predBegin = begin, predEnd = headEnd;
  const uint32_t less = find(begin, headEnd, "<");
  if (less < headEnd) {
    s.leftArrow = text_.compare(less, 2, "<<") == 0 ? "<<" : "<";
    s.left = modules(begin, less, true);
    predBegin = less + static_cast<uint32_t>(s.leftArrow.size());
  }
  const uint32_t greater = find(predBegin, headEnd, ">");
  if (greater < headEnd) {
    s.rightArrow = text_.compare(greater, 2, ">>") == 0 ? ">>" : ">";
    s.right = modules(greater + static_cast<uint32_t>(s.rightArrow.size()), headEnd, true);
    predEnd = greater;
  }
  std::vector<ModuleText> predecessor = modules(predBegin, predEnd, true);
  if (predecessor.size() != 1) {
    uint32_t a = predBegin, b = predEnd;
    trim(a, b);
    fail(a, b,
         predecessor.empty() ? std::string("expected a predecessor before the arrow")
                             : "a production has one predecessor module, found " + std::to_string(predecessor.size()) +
                                   " (" + std::string(text_.substr(a, b - a)) + ")",
         false);
  }
  checkPredecessor(predecessor.front(), predBegin, predEnd);
  s.predecessor = std::move(predecessor.front());
  // The production's parameters hide cpfg's variables of the same name.
  bound_.clear();
  for (const std::vector<ModuleText>* modules : {&s.left, &s.right})
    for (const ModuleText& m : *modules) bound_.insert(m.args.begin(), m.args.end());
  bound_.insert(s.predecessor.args.begin(), s.predecessor.args.end());
  struct Unbind {
    std::set<std::string, std::less<>>& names;
    ~Unbind() { names.clear(); }
  } unbind{bound_};
  // cpfg's blocks around the condition, `{t = t - PL;} t > 0 {u = t / 2;}`: assignments
  // put in where they are read after them.
  std::vector<std::pair<std::string, std::string>> locals;
  if (condBegin < condEnd) {
    uint32_t a = condBegin, b = condEnd;
    if (text_[a] == '{') a = block(a, b, s, begin, end, locals);
    const uint32_t post = find(a, b, "{");
    uint32_t x = a, y = post;
    trim(x, y);
    if (x < y) s.condition = substituted(condition(x, y), locals);
    if (post < b && block(post, b, s, begin, end, locals) < b)
      fail(post, b, "a C block '{ ... }' in the condition: C code, which ontogen convert does not translate", false);
  }
  // The body: successors : probability (cpfg's stochastic productions).
  uint32_t bodyEnd = end;
  const uint32_t probability = find(arrowEnd, end, ":");
  if (probability < end) {
    if (dialect_ == Dialect::LPy)
      fail(probability, probability + 1, "L-Py writes no probability after a production; this ':' cannot be read",
           false);
    s.probability = expression(probability + 1, end);
    bodyEnd = probability;
  }
  uint32_t a = arrowEnd, b = bodyEnd;
  trim(a, b);
  if (text_.substr(a, b - a) != "*") s.successors = modules(a, b, false);
  for (ModuleText& m : s.successors)
    for (std::string& arg : m.args) arg = substituted(arg, locals);
  if (!s.probability.empty()) s.probability = substituted(s.probability, locals);
  return s;
}

std::string ForeignSyntax::substituted(const std::string& expr,
                                       const std::vector<std::pair<std::string, std::string>>& locals) const {
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
    const std::string* value = nullptr;
    for (const auto& [local, text] : locals)
      if (local == name) value = &text;
    result += value && (stop == expr.size() || expr[stop] != '(') ? *value : name;
    i = stop;
  }
  return result;
}

bool ForeignSyntax::bindsParameter(size_t at, std::string_view name) const {
  // The statement's first line: cpfg continues a statement on lines that start with a tab.
  size_t begin = text_.rfind('\n', at) == std::string_view::npos ? 0 : text_.rfind('\n', at) + 1;
  while (begin >= 2 && text_[begin] == '\t') {
    const size_t before = text_.rfind('\n', begin - 2);
    begin = before == std::string_view::npos ? 0 : before + 1;
  }
  size_t arrow = text_.find("->", begin);
  if (arrow == std::string_view::npos) return false;
  // The head ends at the condition's ':' or the arrow; the statement must reach `at`.
  size_t head = begin;
  int depth = 0;
  for (; head < arrow && !(depth == 0 && text_[head] == ':'); ++head) {
    if (text_[head] == '\n' && (head + 1 >= text_.size() || text_[head + 1] != '\t')) return false;
    if (text_[head] == '(') ++depth;
    if (text_[head] == ')') --depth;
  }
  for (size_t k = arrow; k < at; ++k)
    if (text_[k] == '\n' && (k + 1 >= text_.size() || text_[k + 1] != '\t')) return false;
  depth = 0;
  for (size_t k = begin; k < head; ++k) {
    if (text_[k] == '(') ++depth;
    if (text_[k] == ')') --depth;
    if (depth > 0 && text_.compare(k, name.size(), name) == 0 && !isNameChar(text_[k - 1]) &&
        (k + name.size() >= text_.size() || !isNameChar(text_[k + name.size()])))
      return true;
  }
  return false;
}

// A block `{ name = expr; ... }` at `at` of a cpfg condition; the offset after its '}'.
// A name that is no parameter of the production is a variable of the whole file in
// cpfg: it is taken as the production's own only where every other line that reads it
// assigns it in a block of its own.
uint32_t ForeignSyntax::block(uint32_t at, uint32_t end, const Statement& s, uint32_t statementBegin,
                              uint32_t statementEnd, std::vector<std::pair<std::string, std::string>>& locals) const {
  uint32_t close = at + 1;
  while (close < end && text_[close] != '}' && text_[close] != '{') ++close;
  if (close >= end || text_[close] != '}') fail(at, at + 1, "a C block '{' without its '}'", false);
  auto code = [&](uint32_t a, uint32_t b, const std::string& what) {
    fail(a, b, what + ": C code, which ontogen convert does not translate (it reads blocks of assignments "
                      "name = expression; before and after a condition)");
  };
  for (uint32_t from = at + 1; from < close;) {
    uint32_t semi = from;
    while (semi < close && text_[semi] != ';') ++semi;
    uint32_t a = from, b = semi;
    trim(a, b);
    from = semi + 1;
    if (a == b) continue;
    uint32_t stop = a;
    while (stop < b && isNameChar(text_[stop])) ++stop;
    uint32_t eq = stop;
    while (eq < b && isSpace(text_[eq])) ++eq;
    if (stop == a || !isLetter(text_[a]) || eq >= b || text_[eq] != '=' || (eq + 1 < b && text_[eq + 1] == '='))
      code(a, b, "a statement other than an assignment in a C block");
    const std::string name(text_.substr(a, stop - a));
    bool parameter = false;
    auto binds = [&](const std::vector<ModuleText>& modules) {
      for (const ModuleText& m : modules)
        for (const std::string& arg : m.args) parameter = parameter || arg == name;
    };
    binds(s.left);
    binds({s.predecessor});
    binds(s.right);
    if (!parameter) {
      // Every other place of the name must be on a line that assigns it in a block, or in
      // a production that has a parameter of that name (its own).
      for (size_t k = text_.find(name); k != std::string_view::npos; k = text_.find(name, k + 1)) {
        if ((k > 0 && isNameChar(text_[k - 1])) || (k + name.size() < text_.size() && isNameChar(text_[k + name.size()])))
          continue;
        if (k >= statementBegin && k < statementEnd) continue;
        if (bindsParameter(k, name)) continue;
        const size_t lineBegin = text_.rfind('\n', k) == std::string_view::npos ? 0 : text_.rfind('\n', k) + 1;
        size_t lineEnd = text_.find('\n', k);
        if (lineEnd == std::string_view::npos) lineEnd = text_.size();
        const std::string_view line = text_.substr(lineBegin, lineEnd - lineBegin);
        const size_t brace = line.find('{');
        bool assigns = brace != std::string_view::npos && line.find("-->") != std::string_view::npos;
        if (assigns) {
          const size_t own = line.find(name, brace);
          size_t after = own == std::string_view::npos ? line.size() : own + name.size();
          while (after < line.size() && isSpace(line[after])) ++after;
          assigns = after < line.size() && line[after] == '=' && (after + 1 >= line.size() || line[after + 1] != '=');
        }
        if (!assigns)
          code(a, stop,
               "the variable '" + name +
                   "', which other statements of the file read (a variable of cpfg holds its value between "
                   "productions)");
      }
    }
    std::string value = substituted(expression(eq + 1, b), locals);
    locals.emplace_back(cellName(name), "(" + value + ")");
  }
  return close + 1;
}

}  // namespace ontogen::convert
