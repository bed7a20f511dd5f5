#include "core/successors.h"

#include <algorithm>

#include "model/message_number.h"

namespace ontogen {

SuccessorWriter::SuccessorWriter(const Program& program) : program_(program) {
  size_t values = 1;
  for (const MasterCell& master : program.masters) values = std::max<size_t>(values, master.stateCount());
  values_.resize(values);
}

ModelError::ModelError(Diagnostic diagnostic_, std::string cell_, double time_)
    : std::runtime_error(formatDiagnostic(diagnostic_)),
      diagnostic(std::move(diagnostic_)),
      cell(std::move(cell_)),
      time(time_) {}

void SuccessorWriter::badBirthAge(const SuccessorTemplate& successor, uint32_t master, double age,
                                  double when) const {
  const MasterCell& target = program_.masters[successor.master];
  const std::string& label = program_.masters[master].label;
  throw ModelError(Diagnostic{Severity::Error, successor.span,
                              "'" + target.label + "' would be born with age " + messageNumber(age) +
                                  (age >= target.lifetime ? ", not below its terminal age " + messageNumber(target.lifetime)
                                                          : ", but ages are ≥ 0") +
                                  " (in a rule of '" + label + "' at t = " + messageNumber(when) + ")"},
                   label, when);
}

}  // namespace ontogen
