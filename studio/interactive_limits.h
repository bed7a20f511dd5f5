#pragma once
// The limits a growth in the studio stays within: the page's (shown under Limits there and
// raisable on it) below the command line's, which are their ceiling. The engine's limit
// messages name the command line's flags (`raise it with --max-cells N`); a growth in the
// studio passed the page's limit, so its message names the page's control instead, or,
// when the page's limit is already at its ceiling, the flag that raises the ceiling when
// the studio starts.

#include <cstdint>
#include <string>

namespace ontogen::studio {

struct InteractiveLimits {
  uint64_t maxCells = 0;            ///< the page's
  uint64_t maxMemoryBytes = 0;      ///< the page's
  uint64_t ceilingCells = 0;        ///< the command line's (--max-cells)
  uint64_t ceilingMemoryBytes = 0;  ///< the command line's (--max-memory)

  /// `message` with each way of raising or lowering a limit by a flag worded as the page
  /// does it; any other message as it is.
  std::string worded(const std::string& message) const;
};

}  // namespace ontogen::studio
