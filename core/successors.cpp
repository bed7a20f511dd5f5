#include "core/successors.h"

#include <algorithm>
#include <cstdio>

#include "lang/diagnostics.h"

namespace ontogen {

namespace {
std::string formatNumber(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}
}  // namespace

SuccessorWriter::SuccessorWriter(const Program& program) : program_(program) {
  size_t values = 1;
  for (const MasterCell& master : program.masters) values = std::max<size_t>(values, master.stateCount());
  values_.resize(values);
}

void SuccessorWriter::badBirthAge(const SuccessorTemplate& successor, const CellRecord& cell, double age,
                                  double when) const {
  const MasterCell& target = program_.masters[successor.master];
  throw ModelError(formatDiagnostic(Diagnostic{
      Severity::Error, successor.span,
      "'" + target.label + "' would be born with age " + formatNumber(age) +
          (age >= target.lifetime ? ", not below its terminal age " + formatNumber(target.lifetime)
                                  : ", but ages are ≥ 0") +
          " (in a rule of '" + program_.masters[cell.master].label + "' at t = " + formatNumber(when) + ")"}));
}

}  // namespace ontogen
