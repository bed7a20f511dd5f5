#include "apps/cli_values.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "model/message_number.h"

namespace ontogen::app {

namespace {

std::string shortNumber(double value) { return messageNumber(value); }

std::string shortNumber(uint64_t value) { return std::to_string(value); }

bool inRange(double value, const RealRange& range) {
  return (range.minOpen ? value > range.min : value >= range.min) && value <= range.max;
}

constexpr double kLargest = std::numeric_limits<double>::max();

// What a bad value was, for the message: "'nan' is not a number".
[[noreturn]] void reject(const std::string& name, const std::string& text, const std::string& wanted) {
  throw CLI::ValidationError(name, "'" + text + "' is not " + wanted);
}

double realOrThrow(const std::string& name, const std::string& text, const RealRange& range) {
  const std::optional<double> value = parseReal(text);
  if (!value || !inRange(*value, range)) reject(name, text, "a number " + describeRange(range));
  return *value;
}

}  // namespace

std::optional<double> parseReal(std::string_view text) {
  // from_chars takes no '+' and would read "inf" and "nan"; neither is a value here.
  if (text.starts_with('+')) text.remove_prefix(1);
  if (text.empty()) return std::nullopt;
  for (char c : text)
    if (!(c >= '0' && c <= '9') && c != '.' && c != '-' && c != 'e' && c != 'E' && c != '+') return std::nullopt;
  double value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<uint64_t> parseWhole(std::string_view text) {
  if (text.empty()) return std::nullopt;
  for (char c : text)
    if (c < '0' || c > '9') return std::nullopt;
  uint64_t value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::optional<std::pair<int, int>> parsePictureSize(std::string_view text) {
  const size_t x = text.find('x');
  if (x == std::string_view::npos) return std::nullopt;
  const std::optional<uint64_t> width = parseWhole(text.substr(0, x)), height = parseWhole(text.substr(x + 1));
  const auto fits = [](const std::optional<uint64_t>& side) {
    return side && *side >= 1 && *side <= static_cast<uint64_t>(kMaxPictureSide);
  };
  if (!fits(width) || !fits(height)) return std::nullopt;
  return std::pair{static_cast<int>(*width), static_cast<int>(*height)};
}

std::string describeRange(const RealRange& range) {
  const bool bottom = range.min > -kLargest, top = range.max < kLargest;
  if (bottom && top && !range.minOpen) return shortNumber(range.min) + " to " + shortNumber(range.max);
  std::string text;
  if (bottom) text = (range.minOpen ? "> " : "≥ ") + shortNumber(range.min);
  if (top) text += (text.empty() ? "≤ " : " and ≤ ") + shortNumber(range.max);
  return text.empty() ? "(finite)" : text;
}

std::string describeRange(const WholeRange& range) {
  if (range.max == std::numeric_limits<uint64_t>::max()) return "≥ " + shortNumber(range.min);
  return shortNumber(range.min) + " to " + shortNumber(range.max);
}

CLI::Option* addRealOption(CLI::App& app, const std::string& name, std::optional<double>& into, RealRange range,
                           const std::string& doc) {
  return app
      .add_option_function<std::string>(
          name, [&into, name, range](const std::string& text) { into = realOrThrow(name, text, range); }, doc)
      ->type_name("X");
}

CLI::Option* addRealListOption(CLI::App& app, const std::string& name, std::vector<double>& into,
                               std::vector<RealRange> ranges, const std::string& doc) {
  const size_t count = ranges.size();
  CLI::Option* option = app.add_option_function<std::vector<std::string>>(
      name,
      [&into, name, ranges](const std::vector<std::string>& texts) {
        if (ranges.size() > 1 && texts.size() != ranges.size())
          throw CLI::ValidationError(name, "takes " + std::to_string(ranges.size()) + " numbers, comma-separated");
        into.clear();
        for (size_t i = 0; i < texts.size(); ++i)
          into.push_back(realOrThrow(name, texts[i], ranges[ranges.size() > 1 ? i : 0]));
      },
      doc);
  option->delimiter(',')->type_name("X,...");
  if (count > 1) option->expected(static_cast<int>(count));
  return option;
}

std::string emptyAssignment(int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg.starts_with("--") && arg.size() > 3 && arg.back() == '=' && arg.find('=') == arg.size() - 1) {
      const std::string flag(arg.substr(0, arg.size() - 1));
      return flag + "= has no value: write " + flag + "=VALUE or " + flag + " VALUE";
    }
  }
  return {};
}

std::string emptyListItem(int argc, const char* const* argv, std::initializer_list<std::string_view> listFlags) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    for (std::string_view flag : listFlags) {
      std::string_view value;
      if (arg == flag && i + 1 < argc)
        value = argv[i + 1];
      else if (arg.size() > flag.size() && arg.starts_with(flag) && arg[flag.size()] == '=')
        value = arg.substr(flag.size() + 1);
      else
        continue;
      if (value.empty()) continue;  // emptyAssignment's case, or no value at all
      if (value.front() == ',' || value.back() == ',' || value.find(",,") != std::string_view::npos)
        return std::string(flag) + ": '" + std::string(value) + "' has an empty item: write the values with one comma between each";
    }
  }
  return {};
}

namespace detail {

uint64_t wholeOrThrow(const std::string& name, const std::string& text, WholeRange range) {
  const std::optional<uint64_t> value = parseWhole(text);
  if (!value || *value < range.min || *value > range.max) reject(name, text, "a whole number " + describeRange(range));
  return *value;
}

}  // namespace detail

}  // namespace ontogen::app
