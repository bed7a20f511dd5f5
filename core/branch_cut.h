#pragma once
// The cut `%` of cpfg and L-Py: when a cut module expires, it and the rest of its branch
// (up to the `]` that closes the branch, nested branches included; at the top level, the
// rest of the word) are left out of the next word, without developing. A BranchCut
// follows the word in order while it is rebuilt and says which cells a cut drops.

#include <cstdint>

#include "pools/cell_record.h"

namespace ontogen {

class BranchCut {
 public:
  /// A cut expired here: drop what follows up to the end of its branch.
  void start() {
    active_ = true;
    depth_ = 0;
  }
  /// Whether the next cell of the word, of this symbol class, is dropped by a cut under
  /// way. The `]` that ends the cut branch stays, and ends the cut.
  bool drops(uint8_t symbolClass) {
    if (!active_) return false;
    if (symbolClass & kSymbolBranchOpen) {
      ++depth_;
    } else if (symbolClass & kSymbolBranchClose) {
      if (depth_ == 0) {
        active_ = false;
        return false;
      }
      --depth_;
    }
    return true;
  }

 private:
  bool active_ = false;
  int depth_ = 0;  // branches opened after the cut, still open
};

}  // namespace ontogen
