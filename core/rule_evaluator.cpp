#include "core/rule_evaluator.h"

namespace ontogen {

size_t ruleFrameSize(const Program& program) {
  size_t size = FrameSlot::kCount;
  for (const MasterCell& master : program.masters) {
    size = std::max<size_t>(size, master.stateCount() + FrameSlot::kCount);
    for (const auto& rule : master.rules) size = std::max<size_t>(size, rule.frameSize);
    for (const auto* rules : {&master.terminalRules, &master.decompositionRules, &master.homomorphismRules})
      for (const auto& rule : *rules) size = std::max<size_t>(size, rule.frameSize);
  }
  return size;
}

}  // namespace ontogen
