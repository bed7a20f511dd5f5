#pragma once
// The derivation word of a world at its current time, as data and as text in the style
// of paper 000's Table 1: timed modules as `(mov(50), 1)`, untimed ones as `f(50)`,
// parameters after the development function.

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "core/world.h"

namespace ontogen {

struct WordCell {
  std::string label;
  std::vector<double> params;     ///< the actual parameters (state values in declaration order)
  std::vector<double> developed;  ///< after the development function (= params without one)
  double age = 0;                 ///< seconds
  bool timed = false;             ///< written in timed notation: printed as (X, age)
  uint64_t id = 0;      ///< stable id (64 bits; words print the low 53, as rules read it)
  uint64_t parent = ~uint64_t{0};  ///< the id of the cell it hangs from (core/parents.h); all ones: none
  std::vector<double> position;  ///< grid coordinates or spatial x, y, z (empty in a linear pool)
  bool system = false;           ///< a system cell: `pool` holds its system's cells
  std::vector<WordCell> pool;
};

struct WordAtTime {
  double time = 0;
  std::vector<WordCell> cells;
};

/// The world's cells in pool order; a system cell carries its own pool's cells.
std::vector<WordCell> captureWord(const World& world);

/// Table 1 style text, numbers with `precision` significant digits.
std::string formatWord(const std::vector<WordCell>& word, int precision = 6);

/// {"times": [{"t": T, "cells": [{"label": ..., "params": [...], "developed": [...],
/// "age": A, "id": I, "parent": P}, ...]}, ...]} (ids' low 53 bits; P is -1 for none), a system cell with "pool": [its cells], numbers in the shortest form that reads back exactly;
/// infinities and NaN as null.
void writeWordJson(std::ostream& out, const std::vector<WordAtTime>& words);

/// A number in the shortest decimal form that reads back to the same double.
std::string formatExact(double value);

}  // namespace ontogen
