#include "core/finite_state.h"

#include <cstdint>
#include <cstring>

#include "core/successors.h"
#include "model/message_number.h"

namespace ontogen {

namespace {

constexpr uint64_t kExponent = 0x7FF0000000000000ull;  // all ones: an infinity or NaN

struct Writer {
  SourceSpan span;
  std::string what;  // "its rate", "its calculation", "a rule of 'B'"
};

// What writes value `slot` of master `master`: its rate or calculation of that variable,
// else the first rule of the program that makes such a cell, else the master itself.
Writer writerOf(const Program& program, uint32_t master, uint32_t slot) {
  const MasterCell& cell = program.masters[master];
  for (const auto* rules : {&cell.rules, &cell.terminalRules})
    for (const CompiledRule& rule : *rules)
      for (const StateCalculation& calculation : rule.calculations)
        if (calculation.slot == static_cast<int>(slot))
          return {calculation.span, calculation.isRate ? "its rate" : "its calculation"};
  // The cell's own rules first: a cell that renews itself (`B(y) -> B(y * 1e200)`).
  auto maker = [&](const MasterCell& other) -> const SuccessorTemplate* {
    for (const auto* rules : {&other.rules, &other.terminalRules, &other.decompositionRules})
      for (const CompiledRule& rule : *rules)
        for (const SuccessorTemplate& successor : rule.successors)
          if (!successor.isMe && successor.master == master) return &successor;
    return nullptr;
  };
  if (const SuccessorTemplate* successor = maker(cell)) return {successor->span, "a rule of '" + cell.label + "'"};
  for (const MasterCell& other : program.masters)
    if (const SuccessorTemplate* successor = maker(other)) return {successor->span, "a rule of '" + other.label + "'"};
  return {cell.span, "its development"};
}

}  // namespace

bool checksFiniteState(const Program& program) {
  if (program.allowsNonfinite) return false;
  for (const MasterCell& master : program.masters)
    if (master.stateCount() > 0) return true;
  return false;
}

size_t firstNonFinite(std::span<const double> values) {
  // Blocks of 64, each reduced without a branch (vectorized); the block that holds one is
  // searched again.
  constexpr size_t kBlock = 64;
  for (size_t begin = 0; begin < values.size(); begin += kBlock) {
    const size_t end = begin + kBlock < values.size() ? begin + kBlock : values.size();
    uint64_t found = 0;
    for (size_t i = begin; i < end; ++i) {
      uint64_t bits;
      std::memcpy(&bits, &values[i], sizeof bits);
      found |= static_cast<uint64_t>((bits & kExponent) == kExponent);
    }
    if (found == 0) [[likely]]
      continue;
    for (size_t i = begin; i < end; ++i) {
      uint64_t bits;
      std::memcpy(&bits, &values[i], sizeof bits);
      if ((bits & kExponent) == kExponent) return i;
    }
  }
  return values.size();
}

void checkFiniteState(const Program& program, const Pool& pool, double time) {
  const std::span<const double> values = pool.stateArena();
  if (firstNonFinite(values) == values.size()) [[likely]]
    return;
  // A value may lie in no cell's (a slot a step left behind): only the cells' count.
  for (CellCursor cell = pool.cursor(); !cell.done(); cell.next()) {
    const CellView view = cell.view();
    const MasterCell& master = program.masters[view.master];
    const size_t bad = firstNonFinite({view.state, master.stateCount()});
    if (bad == master.stateCount()) continue;
    const Writer writer = writerOf(program, view.master, static_cast<uint32_t>(bad));
    const std::string& name = master.stateNames[bad];
    throw ModelError(Diagnostic{Severity::Error, writer.span,
                                "'" + master.label + "' holds " + name + " = " + messageNumber(view.state[bad]) +
                                    " at t = " + messageNumber(time) + ", written by " + writer.what +
                                    ": a model's state must stay finite (#allow nonfinite accepts infinities and "
                                    "NaN)"},
                     master.label, time);
  }
}

}  // namespace ontogen
