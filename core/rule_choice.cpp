#include "core/rule_choice.h"

#include <cmath>

#include "core/successors.h"
#include "model/message_number.h"
#include "model/program.h"

namespace ontogen {

int activeGroup(const Program& program, const SystemDefinition& system, double time, uint64_t seed) {
  if (system.useGroup.empty()) return 0;
  double frame[FrameSlot::kCount] = {};
  frame[FrameSlot::kTime] = time;
  const FunctionTable functions = program.functionTable();
  EvalContext context{frame, EvalEnvironment{nullptr, seed}, &functions};
  const double group = system.useGroup.evaluate(context);
  // Groups are numbered as the text numbers them; a million is more than any program has.
  if (!(group >= 0) || group != std::floor(group) || group > 1e6) {
    throw ModelError(Diagnostic{Severity::Error, system.useGroupSpan,
                                "'use group' gives " + messageNumber(group) + " at t = " + messageNumber(time) +
                                    ", not a whole number ≥ 0"},
                     system.name, time);
  }
  return static_cast<int>(group);
}

}  // namespace ontogen
