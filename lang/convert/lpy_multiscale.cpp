#include "lang/convert/lpy_multiscale.h"

#include <cctype>
#include <string>

#include "lang/convert/foreign_text.h"

namespace ontogen::convert {

namespace {

using chars::isNameChar;

// The names of `A, B(x, y), C` in [at, end): parameters passed over.
std::vector<std::string> declaredNames(std::string_view clean, uint32_t at, uint32_t end) {
  std::vector<std::string> names;
  for (uint32_t i = at; i < end;) {
    while (i < end && !isNameChar(clean[i])) ++i;
    uint32_t stop = i;
    while (stop < end && isNameChar(clean[stop])) ++stop;
    if (stop > i) names.emplace_back(clean.substr(i, stop - i));
    for (int depth = 0; stop < end && (depth > 0 || clean[stop] != ','); ++stop) {
      if (clean[stop] == '(') ++depth;
      if (clean[stop] == ')') --depth;
    }
    i = stop + 1;
  }
  return names;
}

}  // namespace

void declareScaled(ForeignSyntax& syntax, std::string_view clean, uint32_t at, uint32_t colon, uint32_t end,
                   SourceRange line, LSystemFile& file) {
  if (syntax.find(at, colon, "=") < colon)
    syntax.fail(at, colon, "an alias with a scale (module A = F : scale = N): write the alias and the scale apart");
  uint32_t a = colon + 1, b = end;
  syntax.trim(a, b);
  uint32_t key = a;
  while (key < b && isNameChar(clean[key])) ++key;
  const uint32_t equals = syntax.find(a, b, "=");
  if (clean.substr(a, key - a) != "scale" || equals == b) {
    if (clean.substr(a, key - a) == "base")
      syntax.fail(a, b,
                  "L-Py's module attribute base = A (a module that matches as another) has no cell-language "
                  "counterpart yet");
    syntax.fail(a, b, "an attribute of an L-Py module other than scale = N");
  }
  uint32_t v = equals + 1, w = b;
  syntax.trim(v, w);
  std::string value(clean.substr(v, w - v));
  const bool whole = !value.empty() && value.size() <= 3 &&
                     value.find_first_not_of("0123456789") == std::string::npos && std::stoi(value) <= 255;
  if (!whole) syntax.fail(v, w, "a scale written as a whole number from 0 to 255, as in scale = 2");
  ScaleDeclaration declaration{std::to_string(std::stoi(value)), declaredNames(clean, at, colon), line};
  if (declaration.labels.empty())
    syntax.fail(at, colon, "the modules a scale is given to, as in module A, B : scale = 1");
  for (const std::string& name : declaration.labels) syntax.declaredNames.emplace(name);
  file.scales.push_back(std::move(declaration));
}

bool readsMultiscale(char value, LSystemFile& file) {
  if (value != '2' && value != '3') return false;
  file.multiscale = true;
  file.levels = value == '2';
  return true;
}

}  // namespace ontogen::convert
