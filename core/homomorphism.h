#pragma once
// The image of a linear word under its L-system's homomorphism (L-Py's interpretation
// rules, docs/LANGUAGE.md 4.9): every module with homomorphism rules is rewritten by
// its first matching rule, and what that makes is rewritten in turn, at most the
// system's homomorphismDepth rewrites deep. The image is made for interpretation only:
// the developing word never changes. Modules of the image keep the birth time of the
// module they come from (so development functions and interpretation blocks see its
// age), and get ids derived from its id, deterministically. Rules with context read it
// around the module in the developing word.

#include <cstddef>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "core/successors.h"
#include "core/world.h"
#include "pools/linear_pool.h"

namespace ontogen {

class HomomorphismImage {
 public:
  /// The image of the world's word at its current time. A world whose system has no
  /// homomorphism rules is its own image.
  explicit HomomorphismImage(const World& world);

  /// A cursor at the image's first cell (pools/cell_cursor.h).
  CellCursor cursor() const { return CellCursor(cells_, state_.data()); }
  /// Index in the world's word of the module the i-th cell of the image comes from.
  size_t sourceOf(size_t i) const { return sources_[i]; }

 private:
  void rewrite(const ModuleValue& cell, const double* state, size_t source, int depth);
  void push(const ModuleValue& cell, const double* state, size_t source);

  const World& world_;
  SuccessorWriter successors_;
  std::vector<CellRecord> cells_;
  std::vector<double> state_;
  std::vector<size_t> sources_;
  std::vector<std::vector<double>> frames_;  // one per level of the rewriting
  std::vector<std::pair<const CompiledRule*, double>> candidates_;
  int group_ = 0;  // the rule group active at the world's time
  std::unique_ptr<LinearPool> word_;  // the word, indexed, when some rule reads context
  uint32_t matched_[kMaxContextItems];
};

}  // namespace ontogen
