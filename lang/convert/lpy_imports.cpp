#include "lang/convert/lpy_imports.h"

#include <cctype>
#include <string>

#include "model/builtins.h"
#include "lang/convert/line_reader.h"

namespace ontogen::convert {

namespace {

bool isNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

// A name the converter gives a meaning to where a file reads it: the cell language's
// functions and constants and the Python names translated into them.
bool translatedName(const std::string& name) {
  for (std::string_view python :
       {"math", "random", "uniform", "gauss", "normalvariate", "normal", "int", "float", "round", "radians", "degrees",
        "fabs", "getIterationNb", "seed", "randint", "True", "False", "None", "pi", "e"})
    if (name == python) return true;
  return findBuiltin(name) || findConstant(name);
}

}  // namespace

// `import math`, `from random import *`, `import random as rd`: the names these give
// are translated. Another module's import is read over where the names it binds are
// none the converter gives a meaning to: read, they are then unknown names, a located
// error (`t.time()` is an attribute, refused as such).
bool readImport(ForeignSyntax& syntax, std::string_view text, uint32_t begin, uint32_t end) {
  const Line line{begin, end};
  // from __future__ import division, print_function: Python 2 reading as 3 (pythonVersion).
  if (text.compare(begin, 22, "from __future__ import") == 0) return true;
  auto known = [](std::string_view module) {
    return module == "math" || module == "random" || module == "openalea.plantgl.all";
  };
  if (auto at = afterKeyword(text, line, "import")) {
    for (uint32_t from = *at; from < end;) {
      const uint32_t comma = syntax.find(from, end, ",");
      uint32_t a = from, b = comma;
      syntax.trim(a, b);
      uint32_t stop = a;
      while (stop < b && (isNameChar(text[stop]) || text[stop] == '.')) ++stop;
      const std::string module(text.substr(a, stop - a));
      if (module.empty())
        syntax.fail(a, end, "an import of no module: Python code, which ontogen convert does not translate");
      std::string bound = module.substr(0, module.find('.'));
      if (stop < b) {
        auto as = afterKeyword(text, Line{stop, b}, "as");
        uint32_t x = as ? *as : b, y = b;
        syntax.trim(x, y);
        uint32_t k = x;
        while (k < y && isNameChar(text[k])) ++k;
        if (!as || x == y || k != y)
          syntax.fail(stop, b, "this import: Python code, which ontogen convert does not translate");
        bound = std::string(text.substr(x, y - x));
        if (module == "math" || module == "random") syntax.moduleAliases[bound] = module;
      }
      if (!known(module) && (bound == "math" || bound == "random" || syntax.moduleAliases.count(bound)))
        syntax.fail(a, b,
                    "'import " + module + "' binds the name '" + bound +
                        "', which the converter reads as Python's module " +
                        (bound == "math" || bound == "random" ? bound : syntax.moduleAliases.at(bound)));
      from = comma + 1;
    }
    return true;
  }
  auto at = afterKeyword(text, line, "from");
  if (!at) return false;
  uint32_t a = *at;
  while (a < end && std::isspace(static_cast<unsigned char>(text[a]))) ++a;
  uint32_t stop = a;
  while (stop < end && (isNameChar(text[stop]) || text[stop] == '.')) ++stop;
  const std::string module(text.substr(a, stop - a));
  auto names = afterKeyword(text, Line{stop, end}, "import");
  if (module.empty() || stop == end || !names) return false;
  if (known(module)) return true;
  uint32_t x = *names, y = end;
  syntax.trim(x, y);
  if (x < y && text[x] == '(' && text[y - 1] == ')') syntax.trim(++x, --y);
  if (text.substr(x, y - x) == "*") {
    // L-Py's own modules give classes and functions of its Python side, none of them a
    // name the converter translates.
    if (module == "openalea.lpy" || module.rfind("openalea.lpy.", 0) == 0) return true;
    syntax.fail(x, y, "'from " + module + " import *' gives names the converter cannot know: name them");
  }
  for (uint32_t from = x; from < y;) {
    const uint32_t comma = syntax.find(from, y, ",");
    uint32_t p = from, q = comma;
    syntax.trim(p, q);
    if (auto as = syntax.find(p, q, " as "); as < q) p = as + 4;
    syntax.trim(p, q);
    const std::string name(text.substr(p, q - p));
    if (translatedName(name))
      syntax.fail(p, q,
                  "'" + name + "' imported from " + module +
                      ": a name the converter reads as Python's or the cell language's own");
    from = comma + 1;
  }
  return true;
}

}  // namespace ontogen::convert
