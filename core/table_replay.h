#pragma once
// The ids of a word rewritten by a table (pools/table_rewrite.h) without them: the last
// word that held its ids (the anchor), the table, and the instants of every rewrite
// since. Replaying the rewrites with ids from the anchor gives the ids the development
// would have written: which modules expire at an instant depends on labels and births
// alone, and a module's id on its parent's id and its death (core/successors.h).

#include <memory>
#include <vector>

#include "pools/compact_word.h"
#include "pools/id_replay.h"
#include "pools/table_rewrite.h"

namespace ontogen {

class TableReplay final : public IdReplay {
 public:
  /// The first word written without ids, by `table` at `instant` from `anchor`.
  TableReplay(std::shared_ptr<const CompactWord> anchor, const RewriteTable& table, double instant);
  /// The word after this one's, written at `instant`: the same anchor and table.
  std::shared_ptr<const TableReplay> then(double instant) const;

  CompactWord replay() const override;
  size_t bytes() const override;

 private:
  TableReplay() = default;
  std::shared_ptr<const CompactWord> anchor_;
  std::shared_ptr<const RewriteTable> table_;
  std::vector<double> instants_;  // of each rewrite since the anchor, in order
};

}  // namespace ontogen
