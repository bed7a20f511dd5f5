#pragma once
// The derivation word as text in the style of paper 000's Table 1 (timed modules as
// `(mov(50), 1)`, untimed ones as `f(50)`, parameters after the development function)
// and as JSON, for `ontogen word`.

#include <ostream>
#include <string>
#include <vector>

#include "core/word.h"

namespace ontogen {

/// Table 1 style text, numbers with `precision` significant digits.
std::string formatWord(const std::vector<WordCell>& word, int precision = 6);

/// {"times": [{"t": T, "cells": [{"label": ..., "params": [...], "developed": [...],
/// "age": A, "id": I, "parent": P}, ...]}, ...]} (ids' low 53 bits; P is -1 for none), a system cell with "pool": [its cells], numbers in the shortest form that reads back exactly;
/// infinities and NaN as null.
void writeWordJson(std::ostream& out, const std::vector<WordAtTime>& words);

/// A number in the shortest decimal form that reads back to the same double.
std::string formatExact(double value);

}  // namespace ontogen
