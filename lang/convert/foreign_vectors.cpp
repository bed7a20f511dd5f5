// L-Py's PlantGL vectors as module parameters (ForeignSyntax::vectorParameters): each
// vector parameter is written as its components, and an expression of vectors as one
// expression per component, where it is linear (a sum of terms with at most one vector
// factor each, none divided by a vector): there a component of the value is the value
// of the components. Anything else (a product of two vectors, which PlantGL reads as a
// dot product; a vector compared, or passed to a function) is refused at its place.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lang/convert/foreign_syntax.h"
#include "lang/convert/foreign_text.h"

namespace ontogen::convert {

namespace {

using chars::isLetter;
using chars::isNameChar;
using chars::isSpace;

// Reads a cell-language expression and tells whether its value is a vector (of the names
// in `vectors`) or a number; nullopt where it is no linear expression of vectors.
class Linear {
 public:
  Linear(const std::string& text, const std::map<std::string, int, std::less<>>& vectors, int dimension)
      : text_(text), vectors_(vectors), dimension_(dimension) {}

  std::optional<bool> read() {
    const std::optional<bool> value = sum();
    skip();
    if (!value || at_ != text_.size()) return std::nullopt;
    return value;
  }

 private:
  void skip() {
    while (at_ < text_.size() && isSpace(text_[at_])) ++at_;
  }
  bool take(char c) {
    skip();
    if (at_ < text_.size() && text_[at_] == c) {
      ++at_;
      return true;
    }
    return false;
  }

  std::optional<bool> sum() {
    std::optional<bool> first = term();
    while (first) {
      if (!take('+') && !take('-')) return first;
      const std::optional<bool> next = term();
      if (!next || *next != *first) return std::nullopt;  // a vector plus a number
    }
    return std::nullopt;
  }

  std::optional<bool> term() {
    std::optional<bool> value = unary();
    while (value) {
      const bool divide = take('/');
      if (!divide && !take('*')) return value;
      const std::optional<bool> next = unary();
      if (!next || (*next && (divide || *value))) return std::nullopt;  // over or times a vector
      value = *value || *next;
    }
    return std::nullopt;
  }

  std::optional<bool> unary() {
    while (take('-') || take('+')) {
    }
    return primary();
  }

  std::optional<bool> primary() {
    skip();
    if (at_ >= text_.size()) return std::nullopt;
    const char c = text_[at_];
    if (c == '(') {
      ++at_;
      const std::optional<bool> inner = sum();
      if (!inner || !take(')')) return std::nullopt;
      return inner;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      while (at_ < text_.size() && (isNameChar(text_[at_]) || text_[at_] == '.')) ++at_;
      return false;
    }
    if (!isLetter(c)) return std::nullopt;
    const size_t begin = at_;
    while (at_ < text_.size() && isNameChar(text_[at_])) ++at_;
    const std::string name = text_.substr(begin, at_ - begin);
    if (!take('(')) return vectors_.count(name) > 0;
    // A function's arguments are numbers; Vector2(x, y) and Vector3(x, y, z) make a vector.
    const bool vector = name == "Vector2" || name == "Vector3";
    if (vector && name[6] - '0' != dimension_) return std::nullopt;
    if (take(')')) return vector ? std::nullopt : std::optional<bool>(false);
    do {
      const std::optional<bool> argument = sum();
      if (!argument || *argument) return std::nullopt;
    } while (take(','));
    if (!take(')')) return std::nullopt;
    return vector;
  }

  const std::string& text_;
  const std::map<std::string, int, std::less<>>& vectors_;
  int dimension_;
  size_t at_ = 0;
};

std::string_view bare(std::string_view text) {
  while (!text.empty() && isSpace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isSpace(text.back())) text.remove_suffix(1);
  return text;
}

// `text` with each vector name v (a whole name, not a call) read as its component v_k.
std::string component(const std::string& text, const std::map<std::string, int, std::less<>>& vectors, int k) {
  std::string result;
  for (size_t i = 0; i < text.size();) {
    if (!isLetter(text[i]) || (i > 0 && (isNameChar(text[i - 1]) || text[i - 1] == '.'))) {
      result += text[i++];
      continue;
    }
    size_t stop = i;
    while (stop < text.size() && isNameChar(text[stop])) ++stop;
    const std::string name = text.substr(i, stop - i);
    if ((name == "Vector2" || name == "Vector3") && stop < text.size() && text[stop] == '(') {
      // Its k-th argument (Linear read it: as many as the dimension, each a number).
      std::vector<std::string> arguments(1);
      size_t close = stop + 1;
      for (int depth = 0; close < text.size(); ++close) {
        const char c = text[close];
        if (c == ')' && depth == 0) break;
        if (c == ',' && depth == 0) {
          arguments.emplace_back();
          continue;
        }
        if (c == '(') ++depth;
        if (c == ')') --depth;
        arguments.back() += c;
      }
      result += "(" + std::string(bare(arguments[static_cast<size_t>(k)])) + ")";
      i = close + 1;
      continue;
    }
    result += name;
    if (vectors.count(name) && (stop == text.size() || text[stop] != '(')) result += "_" + std::to_string(k);
    i = stop;
  }
  return result;
}

}  // namespace

std::optional<int> ForeignSyntax::vectorCall(uint32_t a, uint32_t b) const {
  trim(a, b);
  for (auto [name, dimension] : {std::pair{std::string_view("Vector2("), 2}, std::pair{std::string_view("Vector3("), 3}})
    if (text_.compare(a, name.size(), name) == 0 && find(a + name.size() - 1, b, ")") == b - 1) return dimension;
  return std::nullopt;
}

std::vector<std::string> ForeignSyntax::vectorComponents(uint32_t a, uint32_t b, int dimension) const {
  trim(a, b);
  std::vector<std::string> components;
  if (vectorCall(a, b)) {
    uint32_t open = a;
    while (open < b && text_[open] != '(') ++open;
    const uint32_t close = b - 1;
    for (uint32_t from = open + 1; from <= close;) {
      const uint32_t comma = find(from, close, ",");
      components.push_back(expression(from, comma));
      from = comma + 1;
    }
    if (components.size() != static_cast<size_t>(dimension))
      fail(a, b, "a vector of " + std::to_string(components.size()) + " components where the module's parameter has " +
                     std::to_string(dimension));
    return components;
  }
  const std::string value = expression(a, b);
  std::map<std::string, int, std::less<>> read;
  for (const auto& [name, d] : vectorNames)
    if (d == dimension) read[name] = d;
  if (Linear(value, read, dimension).read() != true)
    fail(a, b,
         "a vector parameter given other than a sum of vectors times numbers (L-Py's PlantGL vectors; the converter "
         "writes one expression per component where that is exact)");
  for (int k = 0; k < dimension; ++k) components.push_back(component(value, read, k));
  return components;
}

void ForeignSyntax::noVectorRead(const std::string& value, uint32_t a, uint32_t b) const {
  for (const auto& [name, d] : vectorNames) {
    std::map<std::string, int, std::less<>> one{{name, d}};
    if (component(value, one, 0) != value)
      fail(a, b,
           "the vector '" + name +
               "' read as a number (the converter writes a vector parameter as its components; read one as " +
               name + "[0])");
  }
}

}  // namespace ontogen::convert
