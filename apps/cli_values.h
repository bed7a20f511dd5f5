#pragma once
// Strict values for the numeric flags of the ontogen executable. Every numeric flag of
// every command is declared through these, so they all reject alike: the whole text is
// one number (no "800x800junk", no sign on a count, no "nan" or "inf"), the number is
// inside the flag's range, and a bad value is one short line (ranges printed with %g,
// never 300 digits) and exit code 2.

#include <CLI/CLI.hpp>

#include <cstdint>
#include <limits>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ontogen::app {

/// The real numbers a flag takes: finite, from min to max, min itself excluded when
/// minOpen.
struct RealRange {
  double min = -std::numeric_limits<double>::max();
  double max = std::numeric_limits<double>::max();
  bool minOpen = false;

  static constexpr RealRange above(double min) { return {min, std::numeric_limits<double>::max(), true}; }
  static constexpr RealRange atLeast(double min) { return {min, std::numeric_limits<double>::max(), false}; }
  static constexpr RealRange between(double min, double max) { return {min, max, false}; }
};

/// The whole numbers a flag takes, min to max.
struct WholeRange {
  uint64_t min = 0;
  uint64_t max = std::numeric_limits<uint64_t>::max();

  static constexpr WholeRange any() { return {0, std::numeric_limits<uint64_t>::max()}; }
  static constexpr WholeRange atLeast(uint64_t min) { return {min, std::numeric_limits<uint64_t>::max()}; }
  static constexpr WholeRange between(uint64_t min, uint64_t max) { return {min, max}; }
};

/// A finite decimal number, optionally signed, and nothing else.
std::optional<double> parseReal(std::string_view text);
/// Decimal digits only (no sign, no spaces), within uint64_t.
std::optional<uint64_t> parseWhole(std::string_view text);
/// "WIDTHxHEIGHT", both whole numbers 1 to kMaxPictureSide.
std::optional<std::pair<int, int>> parsePictureSize(std::string_view text);

/// The largest side of a picture, pixels: what the renderer draws (RenderDef).
inline constexpr int kMaxPictureSide = 8192;

/// "> 0", "≥ 0", "1 to 17", "-90 to 90": a range as a message prints it.
std::string describeRange(const RealRange& range);
std::string describeRange(const WholeRange& range);

/// `--name` taking one real number of `range`.
CLI::Option* addRealOption(CLI::App& app, const std::string& name, std::optional<double>& into, RealRange range,
                           const std::string& doc);
/// `--name` taking real numbers of `range`, comma-separated; `count` of them, or any
/// number (at least one) when count is 0.
CLI::Option* addRealListOption(CLI::App& app, const std::string& name, std::vector<double>& into,
                               std::vector<RealRange> ranges, const std::string& doc);
/// `--name` taking one whole number of `range`, stored in any unsigned or signed type
/// that holds the range.
template <typename Whole>
CLI::Option* addWholeOption(CLI::App& app, const std::string& name, Whole& into, WholeRange range,
                            const std::string& doc);
template <typename Whole>
CLI::Option* addWholeOption(CLI::App& app, const std::string& name, std::optional<Whole>& into, WholeRange range,
                            const std::string& doc);

/// A `--name=` with nothing after the '=' (CLI11 would take the next argument as its
/// value): the message for the first such argument, or empty.
std::string emptyAssignment(int argc, const char* const* argv);

/// A value of a comma-separated flag (`listFlags`, as "--at") with an empty item
/// (`1,,2`, `1,`, `,1`), which CLI11 would drop without a word: the message for the
/// first, or empty.
std::string emptyListItem(int argc, const char* const* argv, std::initializer_list<std::string_view> listFlags);

namespace detail {
/// Parses `text` as a whole number of `range` or throws CLI::ValidationError for `name`.
uint64_t wholeOrThrow(const std::string& name, const std::string& text, WholeRange range);
}  // namespace detail

template <typename Whole>
CLI::Option* addWholeOption(CLI::App& app, const std::string& name, Whole& into, WholeRange range,
                            const std::string& doc) {
  return app
      .add_option_function<std::string>(
          name, [&into, name, range](const std::string& text) {
            into = static_cast<Whole>(detail::wholeOrThrow(name, text, range));
          },
          doc)
      ->type_name("N");
}

template <typename Whole>
CLI::Option* addWholeOption(CLI::App& app, const std::string& name, std::optional<Whole>& into, WholeRange range,
                            const std::string& doc) {
  return app
      .add_option_function<std::string>(
          name, [&into, name, range](const std::string& text) {
            into = static_cast<Whole>(detail::wholeOrThrow(name, text, range));
          },
          doc)
      ->type_name("N");
}

}  // namespace ontogen::app
