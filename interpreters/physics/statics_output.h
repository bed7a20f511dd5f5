#pragma once
// The physics set's results as text: the JSON of `ontogen statics --json` and the
// paper's equation writer (paper 003, Fig. 6), which writes the system of equations of
// the rigid statics with its variables indexed by cell id and the known values
// substituted.

#include <ostream>
#include <stdexcept>

#include "interpreters/physics/physics_frame.h"
#include "interpreters/physics/rod_table.h"

namespace ontogen {

/// Thrown when a result is not a finite number (nothing is written then).
struct NonFiniteResult : std::domain_error {
  using std::domain_error::domain_error;
};

/// {"t": T, "g": 9.81, "rods": [{"id": ID, "parent": ID or -1, "base": [x, y, z],
/// "tip": [...], "rest_tip": [...], "length": L, "mass": M, "force": [...],
/// "moment": [...]}, ...]}, numbers in their shortest exact form; ids are the low 53 bits,
/// as `word --json` prints a cell's, so a rod joins its cell. Throws NonFiniteResult.
void writeStaticsJson(std::ostream& out, const PhysicsFrame& frame);

/// For each rod, in the order drawn:
///   F_<id> = (fx, fy, fz) + F_<child> + ...
///   M_<id> = (mx, my, mz) + (lx, ly, lz) x F_<child> + M_<child> + ...
/// where the first vector of F is the rod's weight plus its external force, of M their
/// moments about its base, and (l) the lever from its base to the child's. Throws
/// NonFiniteResult.
void writeStaticsEquations(std::ostream& out, const RodTable& table, double g, double time);

}  // namespace ontogen
