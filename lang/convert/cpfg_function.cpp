#include "lang/convert/cpfg_function.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "lang/convert/line_reader.h"

namespace ontogen::convert {

namespace {

// Samples a function file may ask for: the converter writes the argument once per
// sample, and the function editor writes tens.
constexpr int kMaxSamples = 1024;
// Control points of one function (multiplicities counted): the editor's curves have few.
constexpr size_t kMaxPoints = 4096;
// Functions of one set: the function editor's galleries hold a few.
constexpr long kMaxSetItems = 256;
// Halvings of the curve's parameter before the search for an x gives up: a double has
// 53 bits, so past that the parameter no longer moves.
constexpr int kMaxHalvings = 200;

struct Point {
  double x = 0, y = 0;
};

// The clamped uniform knots of a cubic B-spline (order 4) over points 0..n: 0 four times,
// then 1, 2, ..., up to n - 2 four times.
int knot(int j, int n) {
  constexpr int kOrder = 4;
  if (j < kOrder) return 0;
  if (j > n) return n - kOrder + 2;
  return j - kOrder + 1;
}

// The B-spline basis of order `order` at u (Cox and de Boor); order 1 holds on [u_k, u_k+1).
double basis(int k, int order, double u, int n) {
  if (order == 1) return knot(k, n) <= u && u < knot(k + 1, n) ? 1.0 : 0.0;
  double sum = 0;
  if (int span = knot(k + order - 1, n) - knot(k, n); span != 0)
    sum = (u - knot(k, n)) / span * basis(k, order - 1, u, n);
  if (int span = knot(k + order, n) - knot(k + 1, n); span != 0)
    sum += (knot(k + order, n) - u) / span * basis(k + 1, order - 1, u, n);
  return sum;
}

// The curve at parameter d in [0, 1].
Point curveAt(const std::vector<Point>& points, double d) {
  const int n = static_cast<int>(points.size()) - 1;
  const double u = d * (n - 2);
  Point sum;
  for (int k = 0; k <= n; ++k) {
    const double weight = basis(k, 4, u, n);
    sum.x += points[static_cast<size_t>(k)].x * weight;
    sum.y += points[static_cast<size_t>(k)].y * weight;
  }
  return sum;
}

// The curve's y where its x is `x`, as cpfg finds it: halving the parameter until the
// curve's x is within 0.001 of it.
std::optional<double> valueAt(const std::vector<Point>& points, double x) {
  double low = 0, high = 1;
  for (int halving = 0; halving < kMaxHalvings; ++halving) {
    const double check = (low + high) / 2;
    const Point p = curveAt(points, check);
    if (p.x > x)
      high = check;
    else
      low = check;
    if (std::fabs(p.x - x) <= 0.001) return p.y;
  }
  return std::nullopt;
}

// The lines of a text, without their line breaks.
std::vector<std::string> linesOf(std::string_view text) {
  std::vector<std::string> lines;
  std::istringstream in{std::string(text)};
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> result;
  for (std::string word; in >> word;) result.push_back(word);
  return result;
}

// A number as C's strtof reads it (the function editor's files hold floats), whole.
std::optional<float> floatOf(const std::string& word) {
  char* last = nullptr;
  const float value = std::strtof(word.c_str(), &last);
  if (word.empty() || last != word.c_str() + word.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

// "KEY: N", N a whole number.
std::optional<long> countAfter(const std::string& line, std::string_view key) {
  if (line.compare(0, key.size(), key) != 0) return std::nullopt;
  const std::vector<std::string> rest = words(line.substr(key.size()));
  if (rest.size() != 1) return std::nullopt;
  char* last = nullptr;
  const long value = std::strtol(rest[0].c_str(), &last, 10);
  if (last != rest[0].c_str() + rest[0].size()) return std::nullopt;
  return value;
}

}  // namespace

namespace {

// The function whose `fver 1 1` line is lines[at], sampled; `at` moves past it, and
// `name` is its `name:`.
std::optional<std::vector<double>> sampleFunctionAt(const std::vector<std::string>& lines, size_t& at,
                                                    std::string& name, std::string& error) {
  auto next = [&]() -> const std::string* { return at < lines.size() ? &lines[at++] : nullptr; };
  const std::string* line = next();
  if (!line || words(*line) != std::vector<std::string>{"fver", "1", "1"}) {
    error = "it is no function file of the format 'fver 1 1' (the one the function editor writes)";
    return std::nullopt;
  }
  if (!(line = next()) || line->compare(0, 5, "name:") != 0) {
    error = "expected 'name:' on its second line";
    return std::nullopt;
  }
  const std::vector<std::string> named = words(line->substr(5));
  name = named.empty() ? "" : named[0];
  std::optional<long> samples;
  if (!(line = next()) || !(samples = countAfter(*line, "samples:"))) {
    error = "expected 'samples: N' on its third line";
    return std::nullopt;
  }
  if (*samples <= 2 || *samples > kMaxSamples) {
    error = "'samples: " + std::to_string(*samples) + "': the converter reads functions of 3 to " +
            std::to_string(kMaxSamples) + " samples (cpfg computes fewer at each call, which it does not write)";
    return std::nullopt;
  }
  // A background image (two lines) and markers, which change no value.
  if (at < lines.size() && !lines[at].empty() && lines[at][0] == 'b') at += 2;
  if (at < lines.size() && !lines[at].empty() && lines[at][0] == 'm') {
    const std::optional<long> markers = countAfter(lines[at], "markers:");
    if (!markers || *markers < 0) {
      error = "expected 'markers: N'";
      return std::nullopt;
    }
    at += 1 + static_cast<size_t>(*markers);
  }
  ++at;  // flip: which cpfg does not read
  std::optional<long> count;
  if (!(line = next()) || !(count = countAfter(*line, "points:")) || *count < 4) {
    error = "expected 'points: N' with N at least 4 after the 'flip:' line";
    return std::nullopt;
  }
  std::vector<Point> points;
  for (long i = 0; i < *count; ++i) {
    if (!(line = next())) {
      error = "it has fewer points than its 'points: " + std::to_string(*count) + "'";
      return std::nullopt;
    }
    const std::vector<std::string> values = words(*line);
    std::optional<float> x, y, multiplicity = 1.0f;
    if (values.size() >= 2) x = floatOf(values[0]), y = floatOf(values[1]);
    if (values.size() == 3) multiplicity = floatOf(values[2]);
    if (values.size() < 2 || values.size() > 3 || !x || !y || !multiplicity) {
      error = "expected a point 'x y' or 'x y multiplicity' on line " + std::to_string(at);
      return std::nullopt;
    }
    // A point of multiplicity m stands m times in the curve's points.
    for (int repeat = 0; repeat < static_cast<int>(*multiplicity); ++repeat) {
      if (points.size() == kMaxPoints) {
        error = "more than " + std::to_string(kMaxPoints) + " points";
        return std::nullopt;
      }
      points.push_back({*x, *y});
    }
  }
  if (points.size() < 4) {
    error = "fewer than 4 points";
    return std::nullopt;
  }
  std::vector<double> values;
  for (long i = 0; i < *samples; ++i) {
    const double x = static_cast<double>(i) / static_cast<double>(*samples - 1);
    std::optional<double> y = valueAt(points, x);
    if (!y) {
      char shown[32];
      std::snprintf(shown, sizeof shown, "%g", x);
      error = std::string("its curve's x does not reach ") + shown + " (cpfg would search for it forever)";
      return std::nullopt;
    }
    values.push_back(*y);
  }
  return values;
}

}  // namespace

std::optional<std::vector<double>> sampleFunctionFile(std::string_view text, std::string& error) {
  size_t at = 0;
  std::string name;
  return sampleFunctionAt(linesOf(text), at, name, error);
}

std::optional<std::vector<SampledFunction>> sampleFunctionSet(std::string_view text, const std::string& file,
                                                             std::string& error) {
  const std::vector<std::string> lines = linesOf(text);
  std::optional<long> items;
  if (lines.empty() || words(lines[0]) != std::vector<std::string>{"funcgalleryver", "1", "1"}) {
    error = "it is no function set of the format 'funcgalleryver 1 1' (the one the function editor writes)";
    return std::nullopt;
  }
  if (lines.size() < 2 || !(items = countAfter(lines[1], "items:")) || *items < 0 || *items > kMaxSetItems) {
    error = "expected 'items: N' (N from 0 to " + std::to_string(kMaxSetItems) + ") on its second line";
    return std::nullopt;
  }
  std::vector<SampledFunction> functions;
  size_t at = 2;
  for (long item = 0; item < *items; ++item) {
    SampledFunction function;
    function.file = file;
    std::string why;
    std::optional<std::vector<double>> samples = sampleFunctionAt(lines, at, function.name, why);
    if (!samples) {
      error = "its function " + std::to_string(item + 1) + ": " + why;
      return std::nullopt;
    }
    // cpfg defines the name without what follows its last '.' (`leaf.func` is `leaf`).
    if (const size_t dot = function.name.rfind('.'); dot != std::string::npos) function.name.resize(dot);
    function.samples = std::move(*samples);
    functions.push_back(std::move(function));
  }
  return functions;
}

std::vector<SampledFunction> viewFunctions(std::string_view view, const SideFileReader& read) {
  std::vector<SampledFunction> functions;
  for (const Line& line : splitLines(view)) {
    if (const std::optional<uint32_t> set = afterKeyword(view, line, "function set:")) {
      // A set takes the place of the functions before it (cpfg's ReadFunctionSet).
      functions.clear();
      const std::vector<std::string> values = words(std::string(view.substr(*set, line.end - *set)));
      SampledFunction failed;
      failed.file = values.empty() ? "" : values[0];
      std::optional<std::string> text;
      if (failed.file.empty())
        failed.error = "the view file's 'function set:' line names no file";
      else if (!read || !(text = read(failed.file)))
        failed.error = "the function set '" + failed.file + "' cannot be read";
      else if (auto members = sampleFunctionSet(*text, failed.file, failed.error))
        functions = std::move(*members);
      if (!failed.error.empty()) {
        if (text) failed.error = "the function set '" + failed.file + "': " + failed.error;
        // Whichever function a call names, the set could not be read.
        failed.setUnread = true;
        functions.push_back(std::move(failed));
      }
      continue;
    }
    const std::optional<uint32_t> at = afterKeyword(view, line, "function:");
    if (!at) continue;
    const std::vector<std::string> values = words(std::string(view.substr(*at, line.end - *at)));
    SampledFunction function;
    function.file = values.empty() ? "" : values[0];
    std::optional<std::string> text;
    if (function.file.empty())
      function.error = "the view file's 'function:' line names no file";
    else if (!read || !(text = read(function.file)))
      function.error = "the function file '" + function.file + "' cannot be read";
    else if (std::optional<std::vector<double>> samples = sampleFunctionFile(*text, function.error))
      function.samples = std::move(*samples);
    if (!function.error.empty() && !function.file.empty() && text)
      function.error = "the function file '" + function.file + "': " + function.error;
    // Named only while a set is the view file's last word on functions.
    for (SampledFunction& earlier : functions) earlier.name.clear();
    functions.push_back(std::move(function));
  }
  return functions;
}

std::string sampledValue(const SampledFunction& function, const std::string& x) {
  const size_t last = function.samples.size() - 1;
  const std::string k = "clamp(" + x + ", 0, 1) * " + std::to_string(last);
  std::string sum;
  for (size_t i = 0; i <= last; ++i) {
    if (function.samples[i] == 0) continue;  // its weight times 0 adds nothing
    char value[32];
    std::snprintf(value, sizeof value, "%.17g", function.samples[i]);
    sum += std::string(sum.empty() ? "" : " + ") + "(" + value + ") * max(0, 1 - abs(" + k + " - " +
           std::to_string(i) + "))";
  }
  return sum.empty() ? "0" : "(" + sum + ")";
}

}  // namespace ontogen::convert
