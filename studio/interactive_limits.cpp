#include "studio/interactive_limits.h"

#include <string_view>

namespace ontogen::studio {

namespace {
// The engine's phrases (core/limits.cpp, interpreters/run.cpp and the sets that hold memory).
constexpr std::string_view kRaiseCells = "raise it with --max-cells N";
constexpr std::string_view kRaiseMemory = "raise it with --max-memory MIB";
constexpr std::string_view kLowerBoth = "lower the limits with --max-memory MIB or --max-cells N";

void replaceAll(std::string& text, std::string_view from, const std::string& to) {
  for (std::size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size())
    text.replace(at, from.size(), to);
}
}  // namespace

std::string InteractiveLimits::worded(const std::string& message) const {
  std::string text = message;
  replaceAll(text, kRaiseCells,
             maxCells < ceilingCells
                 ? "raise it under Limits on the page (cells, up to " + std::to_string(ceilingCells) + ")"
                 : "the page's cell limit is at its ceiling: start the studio with a larger --max-cells N to raise it");
  replaceAll(text, kRaiseMemory,
             maxMemoryBytes < ceilingMemoryBytes
                 ? "raise it under Limits on the page (memory, up to " + std::to_string(ceilingMemoryBytes >> 20) +
                       " MiB)"
                 : "the page's memory limit is at its ceiling: start the studio with a larger --max-memory MIB to "
                   "raise it");
  replaceAll(text, kLowerBoth, "lower the limits under Limits on the page (cells, memory)");
  return text;
}

}  // namespace ontogen::studio
