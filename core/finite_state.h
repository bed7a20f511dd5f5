#pragma once
// A model's state stays finite: a rate that blows up, or a rule whose values overflow,
// stops the development (a ModelError located at the rule or rate that writes the value,
// with the time) instead of carrying inf and NaN into every output. A program that
// accepts such state says `#allow nonfinite` (Program::allowsNonfinite).
//
// The check is one pass over the pool's state values after each step, by their bits, which
// the compiler vectorizes; the cells are walked only once a value is found.

#include <span>

#include "model/program.h"
#include "pools/pool.h"

namespace ontogen {

/// Whether the worlds of `program` check their state (it has state and does not allow
/// non-finite values).
bool checksFiniteState(const Program& program);

/// The index of the first value of `values` that is an infinity or NaN, or values.size().
size_t firstNonFinite(std::span<const double> values);

/// Throws ModelError when a cell of `pool` holds a value that is not finite at `time`
/// (seconds), located at the rate or calculation of its master that writes the value,
/// else at a rule that makes such a cell.
void checkFiniteState(const Program& program, const Pool& pool, double time);

}  // namespace ontogen
