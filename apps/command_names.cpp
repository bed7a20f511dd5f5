#include "apps/command_names.h"

#include <algorithm>
#include <array>
#include <numeric>
#include <vector>

namespace ontogen::app {

namespace {
constexpr std::array<std::string_view, 11> kCommands{"check",  "run",        "word",    "statics", "timeline", "sweep",
                                                    "evolve", "studio", "midi-ports", "convert", "help"};
}  // namespace

std::span<const std::string_view> commandNames() { return kCommands; }

size_t editDistance(std::string_view a, std::string_view b) {
  // Wagner-Fischer, one row at a time.
  std::vector<size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), size_t{0});
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string nearMiss(std::string_view word, std::span<const std::string_view> candidates) {
  if (candidates.empty()) return {};
  const auto nearest = std::min_element(candidates.begin(), candidates.end(), [&](std::string_view x, std::string_view y) {
    return editDistance(word, x) < editDistance(word, y);
  });
  // Only a near miss is a suggestion: a wild guess would mislead more than help.
  if (editDistance(word, *nearest) > std::max<size_t>(1, word.size() / 3)) return {};
  return std::string(*nearest);
}

std::string unknownCommandMessage(int argc, const char* const* argv) {
  if (argc < 2) return {};
  const std::string_view word = argv[1];
  if (word.starts_with('-') || std::find(kCommands.begin(), kCommands.end(), word) != kCommands.end()) return {};
  std::string list;
  for (std::string_view name : kCommands) list += (list.empty() ? "" : ", ") + std::string(name);
  std::string message = "unknown command '" + std::string(word) + "'";
  if (std::string nearest = nearMiss(word, kCommands); !nearest.empty()) message += "; did you mean '" + nearest + "'?";
  return message + " (commands: " + list + ")";
}

}  // namespace ontogen::app
