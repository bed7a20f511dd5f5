#include "core/table_replay.h"

#include <string>

#include "core/successors.h"

namespace ontogen {

TableReplay::TableReplay(std::shared_ptr<const CompactWord> anchor, const RewriteTable& table, double instant,
                         const WorldLimits& limits, uint64_t moduleBytes)
    : anchor_(std::move(anchor)),
      table_(std::make_shared<const RewriteTable>(table)),
      instants_(std::make_shared<Instants>()),
      count_(1),
      limits_(limits),
      moduleBytes_(moduleBytes) {
  instants_->values.push_back(instant);
}

std::shared_ptr<const TableReplay> TableReplay::then(double instant) const {
  std::shared_ptr<TableReplay> next(new TableReplay());
  next->anchor_ = anchor_;
  next->table_ = table_;
  {
    std::lock_guard<std::mutex> guard(instants_->lock);
    if (instants_->values.size() == count_) {
      instants_->values.push_back(instant);
      next->instants_ = instants_;
    } else {  // a replay made from this one appended already: this chain branches
      next->instants_ = std::make_shared<Instants>();
      next->instants_->values.assign(instants_->values.begin(),
                                     instants_->values.begin() + static_cast<std::ptrdiff_t>(count_));
      next->instants_->values.push_back(instant);
    }
  }
  next->count_ = count_ + 1;
  next->limits_ = limits_;
  next->moduleBytes_ = moduleBytes_;
  return next;
}

// Each rewrite as ParallelRewrite::rewriteByTableAlone writes it with ids, in one walk of
// the whole word: the runs may split elsewhere than the development's slices split them,
// which no reader sees.
CompactWord TableReplay::replay(size_t heldBytes) const {
  std::vector<double> instants;
  {
    std::lock_guard<std::mutex> guard(instants_->lock);
    instants.assign(instants_->values.begin(), instants_->values.begin() + static_cast<std::ptrdiff_t>(count_));
  }
  CompactWord words[2] = {CompactWord(anchor_->stateCounts()), CompactWord(anchor_->stateCounts())};
  const CompactWord* from = anchor_.get();
  CompactWord::Slice slice(*from);
  for (size_t r = 0; r < instants.size(); ++r) {
    CompactWord& next = words[r % 2];
    next.clearWithBirthsOf(*from);
    slice.restart(*from);
    const size_t size = from->size();
    const TableBound bound = TableRewrite::bound(*from, 0, size, *table_);
    const uint64_t held = heldBytes + anchor_->bytes() + (from == anchor_.get() ? 0 : from->bytes());
    checkOutsideMemory("giving the word of " + std::to_string(bound.modules) + " modules its ids again",
                       bound.modules * moduleBytes_, held, limits_);
    next.beginWholeSlice(slice, bound.modules, size, bound.values);
    TerminalLineage lineage;
    TableRewrite::rewrite(slice, *from, 0, size, *table_, instants[r], lineage);
    next.endWholeSlice(slice);
    next.finish();
    from = &next;
  }
  return instants.empty() ? *anchor_ : std::move(words[(instants.size() - 1) % 2]);
}

size_t TableReplay::bytes() const {
  std::lock_guard<std::mutex> guard(instants_->lock);
  return anchor_->bytes() + instants_->values.capacity() * sizeof(double);
}

}  // namespace ontogen
