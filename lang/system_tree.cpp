#include "lang/system_tree.h"

#include <algorithm>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/depth_first_search.hpp>

namespace ontogen {

namespace {
using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::directedS>;
using Vertex = boost::graph_traits<Graph>::vertex_descriptor;
using Edge = boost::graph_traits<Graph>::edge_descriptor;

// Records the tree edges (to walk back along the current path) and stops at the first
// back edge, which closes a cycle.
struct CycleFinder : boost::default_dfs_visitor {
  std::vector<Vertex>* parent;
  std::vector<int>* cycle;
  void tree_edge(Edge e, const Graph& g) const { (*parent)[boost::target(e, g)] = boost::source(e, g); }
  void back_edge(Edge e, const Graph& g) const {
    if (!cycle->empty()) return;
    const Vertex from = boost::source(e, g), to = boost::target(e, g);
    std::vector<int> path{static_cast<int>(from)};
    for (Vertex v = from; v != to;) {
      v = (*parent)[v];
      path.push_back(static_cast<int>(v));
    }
    std::reverse(path.begin(), path.end());
    path.push_back(static_cast<int>(to));
    *cycle = std::move(path);
  }
};
}  // namespace

SystemTree::SystemTree(const Program& program) : program_(program) {
  for (const SystemDefinition& system : program.systems) holds_.push_back(reachableMasters(program, system));
}

std::vector<bool> SystemTree::reachableMasters(const Program& program, const SystemDefinition& system) {
  std::vector<bool> seen(program.masters.size(), false);
  std::vector<MasterId> pending;
  auto visit = [&](MasterId m) {
    if (m < seen.size() && !seen[m]) {
      seen[m] = true;
      pending.push_back(m);
    }
  };
  for (const auto& cell : system.axiom) visit(cell.master);
  for (const auto& placement : system.placements) visit(placement.master);
  while (!pending.empty()) {
    const MasterCell& master = program.masters[pending.back()];
    pending.pop_back();
    for (const auto* rules : {&master.rules, &master.terminalRules})
      for (const auto& rule : *rules)
        for (const auto& successor : rule.successors)
          if (!successor.isMe) visit(successor.master);
  }
  return seen;
}

std::vector<int> SystemTree::findCycle() const {
  const size_t n = program_.systems.size();
  Graph graph(n);
  for (size_t s = 0; s < n; ++s)
    for (size_t t = 0; t < n; ++t) {
      const int master = program_.systems[t].master;
      if (master >= 0 && holds_[s][master]) boost::add_edge(s, t, graph);
    }
  std::vector<Vertex> parent(n);
  std::vector<int> cycle;
  std::vector<boost::default_color_type> colors(n);
  boost::depth_first_search(
      graph, CycleFinder{{}, &parent, &cycle},
      boost::make_iterator_property_map(colors.begin(), boost::get(boost::vertex_index, graph)));
  return cycle;
}

std::vector<int> SystemTree::containers(int s) const {
  const int master = program_.systems[s].master;
  return master < 0 ? std::vector<int>{} : systemsHolding(static_cast<MasterId>(master));
}

SystemTree::Depths SystemTree::depths() const {
  const size_t n = program_.systems.size();
  Depths result{std::vector<int>(n, 0), std::vector<int>(n, -1)};
  std::vector<std::vector<int>> containersOf(n);
  for (size_t s = 0; s < n; ++s) containersOf[s] = containers(static_cast<int>(s));
  // Longest path in a DAG, by relaxing until nothing changes: at most n rounds, and the
  // systems number at most kMaxSystems.
  for (size_t s = 0; s < n; ++s) result.depth[s] = 1;
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t s = 0; s < n; ++s)
      for (int c : containersOf[s])
        if (result.depth[c] + 1 > result.depth[s]) {
          result.depth[s] = result.depth[c] + 1;
          result.above[s] = c;
          changed = true;
        }
  }
  return result;
}

std::vector<int> SystemTree::systemsHolding(MasterId master) const {
  std::vector<int> result;
  for (size_t s = 0; s < holds_.size(); ++s)
    if (master < holds_[s].size() && holds_[s][master]) result.push_back(static_cast<int>(s));
  return result;
}

}  // namespace ontogen
