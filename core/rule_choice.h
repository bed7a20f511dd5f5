#pragma once
// How a module chooses among its L-system rules (productions, decomposition and
// homomorphism rules alike; docs/LANGUAGE.md 4.5): the first rule that matches is
// chosen; if it is stochastic, the choice is made among it and the later matching
// stochastic rules, weighted by their probabilities, each rule once however many of its
// variants (the alternatives of its context) match. Of an L-system's rule groups, only
// the active group's rules and group 0's take part (the compiler puts group 0's last).

#include <algorithm>
#include <utility>
#include <vector>

#include "model/expression.h"
#include "model/program.h"
#include "model/random.h"

namespace ontogen {

/// The rule group `system` uses at `time` (`use group: EXPR`), 0 without one. A value that
/// is not a whole number ≥ 0 stops the run with a ModelError at the expression.
int activeGroup(const Program& program, const SystemDefinition& system, double time, uint64_t seed);

/// Which of `count` weights (each at least 0, `total` their sum, above 0) a uniform draw
/// in [0, 1) picks: the first whose running sum passes uniform x total, else the last.
/// `weightOf(c)` gives weight c. The one weighing of every stochastic choice.
template <typename WeightOf>
size_t pickByWeight(double uniform, double total, size_t count, WeightOf&& weightOf) {
  double x = uniform * total;
  for (size_t c = 0; c + 1 < count; ++c) {
    const double weight = weightOf(c);
    if (x < weight) return c;
    x -= weight;
  }
  return count - 1;
}

/// The rule chosen from `rules`, or null, with `group` the active rule group.
/// `matches(rule)` tells whether a rule's context and condition hold; `candidates` is
/// scratch space, kept by the caller to reuse.
template <typename Matches>
const CompiledRule* chooseRule(const std::vector<CompiledRule>& rules, int group, Matches&& matches,
                               const EvalContext& context, RandomStream& random,
                               std::vector<std::pair<const CompiledRule*, double>>& candidates) {
  auto applies = [&](const CompiledRule& rule) { return (rule.group == 0 || rule.group == group) && matches(rule); };
  for (size_t r = 0; r < rules.size(); ++r) {
    const CompiledRule& rule = rules[r];
    if (!applies(rule)) continue;
    if (rule.probability.empty()) return &rule;
    candidates.clear();
    double total = 0;
    bool taken = false;  // a variant of the rule at hand (alternatives of a context) is a candidate
    for (size_t s = r; s < rules.size(); ++s) {
      if (s == r || rules[s].variant == 0) taken = false;
      if (taken || rules[s].probability.empty() || (s != r && !applies(rules[s]))) continue;
      double weight = std::max(0.0, rules[s].probability.evaluate(context));
      candidates.push_back({&rules[s], weight});
      total += weight;
      taken = true;
    }
    if (!(total > 0)) return nullptr;
    return candidates[pickByWeight(random.uniform(), total, candidates.size(),
                                   [&](size_t c) { return candidates[c].second; })]
        .first;
  }
  return nullptr;
}

}  // namespace ontogen
