#include "core/pool_view.h"

namespace ontogen {

void LinearPoolView::neighbours(size_t i, std::vector<uint32_t>& out) const {
  static constexpr ContextItem kAny[1] = {ContextItem{ContextItem::Kind::Any, 0}};
  out.clear();
  uint32_t matched[1];
  if (pool_.matchLeft(i, kAny, classOf_, matched)) out.push_back(matched[0]);
  if (pool_.matchRight(i, kAny, classOf_, matched)) out.push_back(matched[0]);
}

bool LinearPoolView::matchContext(const CompiledRule& rule, size_t i, uint32_t* left, uint32_t* right) const {
  if (!rule.leftItems.empty() && !pool_.matchLeft(i, rule.leftItems, classOf_, left)) return false;
  return rule.rightItems.empty() || pool_.matchRight(i, rule.rightItems, classOf_, right);
}

void GridPoolView::neighbours(size_t i, std::vector<uint32_t>& out) const {
  uint32_t sites[GridPool::kMaxNeighbours];
  const int count = pool_.neighbourSites(pool_.siteOf(i), sites);
  out.clear();
  for (int k = 0; k < count; ++k) {
    if (sites[k] == GridPool::kEmpty) continue;
    const uint32_t cell = pool_.cellAt(sites[k]);
    if (cell != GridPool::kEmpty) out.push_back(cell);
  }
}

bool GridPoolView::matchContext(const CompiledRule& rule, size_t i, uint32_t* left, uint32_t* right) const {
  // The compiler checks that the context's dimensions are the grid's.
  const GridCoordinates here = pool_.coordinates(pool_.siteOf(i));
  if (rule.contextDimensions > 1) {
    // `(A) (B me C) (D)`: each module at its offset, after the boundary; an empty or
    // missing site fails the match (`*` places had no module and are not here).
    for (size_t k = 0; k < rule.right.size(); ++k) {
      const auto& offset = rule.right[k].offset;
      const uint32_t site = pool_.siteAt({here[0] + offset[0], here[1] + offset[1], here[2] + offset[2]});
      if (site == GridPool::kEmpty) return false;
      const uint32_t cell = pool_.cellAt(site);
      if (cell == GridPool::kEmpty) return false;
      if (pool_.cells()[cell].master != rule.rightItems[k].master) return false;
      right[k] = cell;
    }
    return true;
  }
  auto match = [&](const std::vector<ContextItem>& items, int direction, uint32_t* matched) {
    for (size_t k = 0; k < items.size(); ++k) {
      const uint32_t site = pool_.siteAt({here[0] + direction * static_cast<int64_t>(k + 1), 0, 0});
      if (site == GridPool::kEmpty) return false;
      const uint32_t cell = pool_.cellAt(site);
      if (cell == GridPool::kEmpty) return false;
      if (items[k].kind != ContextItem::Kind::Any && pool_.cells()[cell].master != items[k].master) return false;
      matched[k] = cell;
    }
    return true;
  };
  return match(rule.leftItems, -1, left) && match(rule.rightItems, 1, right);
}

std::array<double, 3> GridPoolView::position(size_t i) const {
  const GridCoordinates c = pool_.coordinates(pool_.siteOf(i));
  return {static_cast<double>(c[0]), static_cast<double>(c[1]), static_cast<double>(c[2])};
}

}  // namespace ontogen
