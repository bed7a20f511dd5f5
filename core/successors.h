#pragma once
// The one successor writer every pool kind uses: when a rule with an action fires for a
// cell, it evaluates each successor's arguments and birth age (checking the age against
// the successor's terminal age), gives it its id (a new one from the cell's lineage, or
// the cell's own for `me` and `=X`), records the birth in the lineage log when asked, and
// hands the cell to the pool's own placement. The id goes out as its coordinates, a
// ModuleValue (core/module_value.h): the event's lineage key, computed once for all its
// successors, and the successor's number k. What differs between pools (where a
// successor goes) stays in the pool's development; everything else is here.

#include <cstdint>
#include <string>
#include <vector>

#include "core/limits.h"
#include "core/module_value.h"
#include "core/salts.h"
#include "model/diagnostics.h"
#include "model/expression.h"
#include "model/program.h"
#include "pools/cell_record.h"

namespace ontogen {

/// What made a cell develop: its terminal age (a production, `me` starts its age again)
/// or a per-step rule (`me` keeps its age).
enum class BirthCause : uint8_t { Terminal, StepRule };

/// One birth: `child` was made by a rule of `parent` at `time` (seconds). Ids as the engine
/// keeps them (64 bits).
struct LineageRecord {
  uint64_t child = 0;
  uint64_t parent = 0;
  double time = 0;
  bool operator==(const LineageRecord&) const = default;
};

/// A model failed while it ran (e.g. a birth age not below the terminal age). Carries the
/// diagnostic (the rule's source span and the message), the cell and the time; what() is
/// the diagnostic formatted like a compiler's.
struct ModelError : std::runtime_error {
  ModelError(Diagnostic diagnostic, std::string cell, double time);
  Diagnostic diagnostic;
  std::string cell;  ///< label of the cell whose rule failed
  double time = 0;   ///< global time of the failure, seconds
};

/// The key all the new successors of `cell` share when it develops at `when`.
inline uint64_t lineageKey(uint64_t cellId, double when, BirthCause cause) {
  return mixKey(cellId, keyOf(when)) ^ (cause == BirthCause::StepRule ? kStepRuleSalt : 0);
}

/// lineageKey(cell, death, BirthCause::Terminal) for a cell given as mixKeyFirst(cell),
/// the second part of the death's key computed once for a run of equal deaths (every
/// event of a step of Koch shares one).
class TerminalLineage {
 public:
  uint64_t operator()(uint64_t cellFirst, double death) {
    const uint64_t bits = keyOf(death);
    if (!known_ || bits != deathBits_) {
      known_ = true;
      deathBits_ = bits;
      deathSecond_ = mixKeySecond(bits);
    }
    return mixKeyJoin(cellFirst, deathSecond_);
  }

 private:
  bool known_ = false;
  uint64_t deathBits_ = 0, deathSecond_ = 0;
};

/// The id of the k-th successor (k from 1) of `cell` when it develops at `when`.
inline uint64_t successorId(uint64_t cellId, double when, BirthCause cause, uint64_t k) {
  return mixKey(lineageKey(cellId, when, cause), k);
}

class SuccessorWriter {
 public:
  explicit SuccessorWriter(const Program& program);

  /// Logs every birth into `log` from now on (null: none). Not thread-safe: one writer
  /// and one log per thread.
  void recordLineage(std::vector<LineageRecord>* log) { lineage_ = log; }

  /// Writes the successors of `rule`, fired for `cell` at `when`. `frame` holds the cell's
  /// state after the rule's calculations (what `me` keeps); `context` evaluates the
  /// successors' arguments. For each successor, in order, calls
  /// `emit(const ModuleValue&, const double* values, uint32_t count)`: a new cell has the
  /// event's lineage key and its number k, `me` and `=X` the coordinates of `cell`.
  /// Returns the number of new cells (not `me`).
  template <typename Emit>
  uint64_t write(const CompiledRule& rule, const ModuleValue& cell, const double* frame, double when, BirthCause cause,
                 const EvalContext& context, Emit&& emit);
  /// The same for a cell a pool keeps as a record.
  template <typename Emit>
  uint64_t write(const CompiledRule& rule, const CellRecord& cell, const double* frame, double when, BirthCause cause,
                 const EvalContext& context, Emit&& emit) {
    return write(rule, moduleOf(cell), frame, when, cause, context, static_cast<Emit&&>(emit));
  }

 private:
  [[noreturn]] void badBirthAge(const SuccessorTemplate& successor, uint32_t master, double age, double when) const;

  const Program& program_;
  std::vector<double> values_;
  std::vector<LineageRecord>* lineage_ = nullptr;
};

template <typename Emit>
uint64_t SuccessorWriter::write(const CompiledRule& rule, const ModuleValue& cell, const double* frame, double when,
                                BirthCause cause, const EvalContext& context, Emit&& emit) {
  // Copied: `emit` may write into the storage `cell` was read from.
  const ModuleValue parent = cell;
  const uint64_t lineage = lineageKey(parent.id(), when, cause);
  uint32_t k = 0;
  uint64_t born = 0;
  for (const SuccessorTemplate& successor : rule.successors) {
    ++k;
    if (successor.isMe) {
      ModuleValue me = parent;
      if (cause == BirthCause::Terminal) me.birth = when;
      emit(me, frame, program_.masters[parent.master].stateCount());
      continue;
    }
    ModuleValue made{successor.master, k, when, lineage};
    if (successor.keepsIdentity) {
      made.k = parent.k;
      made.key = parent.key;
    }
    ++born;
    if (lineage_) lineage_->push_back(LineageRecord{made.id(), parent.id(), when});
    if (successor.stateless) {
      // The common case of a bare symbol born at age 0: nothing to evaluate or check.
      emit(made, values_.data(), 0u);
      continue;
    }
    const MasterCell& target = program_.masters[successor.master];
    const uint32_t count = target.stateCount();
    for (uint32_t j = 0; j < count; ++j) values_[j] = successor.args[j].evaluate(context);
    const double age = successor.birthAge.empty() ? 0.0 : successor.birthAge.evaluate(context);
    if (!(age >= 0) || age >= target.lifetime) [[unlikely]]
      badBirthAge(successor, parent.master, age, when);
    made.birth = when - age;
    emit(made, values_.data(), count);
  }
  return born;
}

}  // namespace ontogen
