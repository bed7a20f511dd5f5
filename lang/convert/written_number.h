#pragma once
// The value of a converted expression that names no value of the model: numbers and the
// operators and pure functions between them. What the converter may compute once where
// the other tool computes it once (the turns of a loop over range(3)), where a name would
// tie the value to a constant a run can change (`--define N=...`, a hook setting N).

#include <optional>
#include <string>

namespace ontogen::convert {

/// The value of the cell-language expression `expression` if it is made of numbers alone
/// (no names, no random draws); nullopt otherwise.
std::optional<double> writtenNumber(const std::string& expression);

}  // namespace ontogen::convert
