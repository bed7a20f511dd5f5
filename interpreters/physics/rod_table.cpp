#include "interpreters/physics/rod_table.h"

#include <numbers>
#include <stdexcept>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/topological_sort.hpp>

namespace ontogen {

double Rod::mass() const { return density * std::numbers::pi * radius * radius * length(); }

std::vector<int> leavesFirstOrder(std::span<const int> parentIndices) {
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::directedS>;
  // Edges child -> parent: topological_sort writes the vertices in reverse topological
  // order, every parent before its children, and the sweep is that order reversed. Rods
  // are drawn parents first (a rod hangs from one drawn before it), so its depth-first
  // search finishes them in drawing order and the sweep runs through memory backwards,
  // in order, not jumping about the tree.
  Graph graph(parentIndices.size());
  for (size_t child = 0; child < parentIndices.size(); ++child)
    if (parentIndices[child] >= 0) boost::add_edge(child, static_cast<size_t>(parentIndices[child]), graph);
  std::vector<size_t> sorted;
  sorted.reserve(parentIndices.size());
  try {
    boost::topological_sort(graph, std::back_inserter(sorted));
  } catch (const boost::not_a_dag&) {
    throw std::logic_error("the rods' parents form a cycle");
  }
  return {sorted.rbegin(), sorted.rend()};
}

void RodTable::beginFrame(double time) {
  time_ = time;
  rods_.clear();
  order_.clear();
}

int RodTable::add(const Rod& rod) {
  rods_.push_back(rod);
  return static_cast<int>(rods_.size()) - 1;
}

void RodTable::finish() {
  std::unordered_map<uint64_t, int> index;
  index.reserve(rods_.size());
  for (size_t i = 0; i < rods_.size(); ++i) index.emplace(rods_[i].id, static_cast<int>(i));
  std::vector<int> parents(rods_.size(), -1);
  for (size_t i = 0; i < rods_.size(); ++i) {
    Rod& rod = rods_[i];
    auto found = rod.parent == kNoParentRod ? index.end() : index.find(rod.parent);
    // A parent later in the word cannot be: the axial tree puts parents first.
    if (found == index.end() || found->second >= static_cast<int>(i)) rod.parent = kNoParentRod;
    rod.parentIndex = rod.parent == kNoParentRod ? -1 : found->second;
    parents[i] = rod.parentIndex;
  }
  order_ = leavesFirstOrder(parents);

  childStart_.assign(rods_.size() + 1, 0);
  for (int p : parents)
    if (p >= 0) ++childStart_[static_cast<size_t>(p) + 1];
  for (size_t i = 0; i < rods_.size(); ++i) childStart_[i + 1] += childStart_[i];
  childList_.assign(static_cast<size_t>(childStart_.back()), 0);
  std::vector<int> fill(childStart_.begin(), childStart_.end() - 1);
  for (size_t i = 0; i < rods_.size(); ++i)
    if (parents[i] >= 0) childList_[static_cast<size_t>(fill[static_cast<size_t>(parents[i])]++)] = static_cast<int>(i);

  std::unordered_map<uint64_t, RodRow> kept;
  kept.reserve(rods_.size());
  for (size_t i = 0; i < rods_.size(); ++i) {
    auto old = rows_.find(rods_[i].id);
    RodRow row{rods_[i].parent, old == rows_.end() ? time_ : old->second.since, static_cast<int>(i)};
    kept.emplace(rods_[i].id, row);
  }
  rows_ = std::move(kept);
}

std::span<const int> RodTable::children(int i) const {
  const auto at = static_cast<size_t>(i);
  return std::span<const int>(childList_).subspan(static_cast<size_t>(childStart_[at]),
                                                  static_cast<size_t>(childStart_[at + 1] - childStart_[at]));
}

}  // namespace ontogen
