#pragma once
// The ids of a word rewritten by a table (pools/table_rewrite.h) without them: the last
// word that held its ids (the anchor), the table, and the instants of every rewrite
// since. Replaying the rewrites with ids from the anchor gives the ids the development
// would have written: which modules expire at an instant depends on labels and births
// alone, and a module's id on its parent's id and its death (core/successors.h).

#include <memory>
#include <mutex>
#include <vector>

#include "core/limits.h"
#include "pools/compact_word.h"
#include "pools/id_replay.h"
#include "pools/table_rewrite.h"

namespace ontogen {

class TableReplay final : public IdReplay {
 public:
  /// The first word written without ids, by `table` at `instant` from `anchor`, in a
  /// world of `limits` whose compact words take at most `moduleBytes` bytes a module.
  TableReplay(std::shared_ptr<const CompactWord> anchor, const RewriteTable& table, double instant,
              const WorldLimits& limits, uint64_t moduleBytes);
  /// The word after this one's, written at `instant`: the same anchor, table and limits.
  std::shared_ptr<const TableReplay> then(double instant) const;

  /// Before each rewrite, the words it holds then (`heldBytes`, the anchor, the word it
  /// rewrites, and the next at `moduleBytes` a module of its bound) are checked against
  /// the memory limit, as the development checks the words it writes.
  CompactWord replay(size_t heldBytes) const override;
  size_t bytes() const override;

 private:
  TableReplay() = default;
  std::shared_ptr<const CompactWord> anchor_;
  std::shared_ptr<const RewriteTable> table_;
  // The instants of each rewrite since the anchor, in order, shared by a replay and those
  // then() makes from it: each reads the first count_. then() appends in place when no
  // replay appended past it, so a chain of n rewrites within a step (a module of lifetime
  // 2^-16 s, 65,536 rewrites in a step of 1 s) costs n appends, not n copies of the chain.
  struct Instants {
    mutable std::mutex lock;  // a copy of the pool may replay while the development appends
    std::vector<double> values;
  };
  std::shared_ptr<Instants> instants_;
  size_t count_ = 0;
  WorldLimits limits_;
  uint64_t moduleBytes_ = 0;
};

}  // namespace ontogen
