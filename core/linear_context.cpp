#include "core/linear_context.h"

#include <algorithm>

#include "core/multiscale_context.h"

namespace ontogen {

namespace {

// Copies the values the side's patterns bind; a wildcard `*(x, y)` needs a module with
// exactly that many parameters. masterOf(j) and stateOf(j) give the master and the values
// of cell j: a pool may hold its word compactly, without records.
template <typename MasterOf, typename StateOf>
bool bindSide(const Program& program, const std::vector<ContextBinding>& bindings, MasterOf&& masterOf,
              StateOf&& stateOf, const uint32_t* matched, double* frame) {
  for (size_t k = 0; k < bindings.size(); ++k) {
    const ContextBinding& binding = bindings[k];
    if (binding.arity < 0 && binding.count == 0) continue;
    if (binding.arity >= 0 && program.masters[masterOf(matched[k])].stateCount() != static_cast<uint32_t>(binding.arity))
      return false;
    const double* values = stateOf(matched[k]);
    std::copy(values, values + binding.count, frame + binding.firstSlot);
  }
  return true;
}

}  // namespace

bool matchLinearContext(const Program& program, const CompiledRule& rule, const LinearPool& pool, size_t index,
                        const WrittenWord& written, std::span<const uint8_t> classOf, double* frame,
                        uint32_t* matched) {
  rule.clearUnbound(frame);
  const double* arena = pool.stateArena().data();
  // The pool finds a cell's values by counting (Pool::countValues); the word being
  // written keeps them in its records.
  auto inPool = [&](uint32_t j) { return arena + pool.stateOffset(j); };
  auto inWritten = [&](uint32_t j) { return written.state + written.cells[j].state; };
  auto masterInPool = [&](uint32_t j) { return pool.masterAt(j); };
  auto masterInWritten = [&](uint32_t j) { return written.cells[j].master; };
  if (rule.scales) {  // a multiscale block, which has no new right context (lang/compile_scales.cpp)
    const ScaleTable& scales = *rule.scales;
    if (!rule.leftItems.empty() &&
        !(matchMultiscaleLeft(pool, index, rule.leftItems, classOf, scales, matched) &&
          bindSide(program, rule.left, masterInPool, inPool, matched, frame)))
      return false;
    if (!rule.newLeftItems.empty() &&
        !(matchMultiscaleNewLeft(written.cells, pool.masterAt(index), rule.newLeftItems, classOf, scales, matched) &&
          bindSide(program, rule.newLeft, masterInWritten, inWritten, matched, frame)))
      return false;
    return rule.rightItems.empty() ||
           (matchMultiscaleRight(pool, index, rule.rightItems, classOf, scales, matched) &&
            bindSide(program, rule.right, masterInPool, inPool, matched, frame));
  }
  if (!rule.leftItems.empty()) {
    if (!pool.matchLeft(index, rule.leftItems, classOf, matched)) return false;
    if (!bindSide(program, rule.left, masterInPool, inPool, matched, frame)) return false;
  }
  if (!rule.newLeftItems.empty()) {
    if (!LinearPool::matchLeftOfEnd(written.cells, rule.newLeftItems, classOf, matched)) return false;
    if (!bindSide(program, rule.newLeft, masterInWritten, inWritten, matched, frame)) return false;
  }
  if (!rule.newRightItems.empty()) {
    if (!LinearPool::matchRightOfReversed(written.cells, rule.newRightItems, classOf, matched)) return false;
    if (!bindSide(program, rule.newRight, masterInWritten, inWritten, matched, frame)) return false;
  }
  if (!rule.rightItems.empty()) {
    if (!pool.matchRight(index, rule.rightItems, classOf, matched)) return false;
    if (!bindSide(program, rule.right, masterInPool, inPool, matched, frame)) return false;
  }
  return true;
}

}  // namespace ontogen
