#pragma once
// One cell as readers outside a pool see it, whatever the pool stores (pools/cell_cursor.h).

#include <cstddef>
#include <cstdint>

namespace ontogen {

/// One cell as readers see it. `state` points into the pool's storage: valid until the
/// pool changes, like the cursor that made it.
struct CellView {
  uint32_t master = 0;            ///< index of the master cell in the program (its label)
  const double* state = nullptr;  ///< the cell's state values, as many as its master has
  double birth = 0;               ///< global time at which the cell had age 0 (seconds)
  uint64_t id = 0;                ///< stable id (core/successors.h)
  size_t index = 0;               ///< position in pool order
};

}  // namespace ontogen
