#pragma once
// cpfg's functions of one variable, `func(n, x)`: the view file names them in order,
// `function: internode.func 100`, each a file the function editor wrote (`fver 1 1`):
// control points of a cubic B-spline (x, y), clamped at both ends. cpfg samples each
// function at the `samples:` its file states, x = i / (samples - 1), finding the curve's
// parameter where its x is that value (bisection to 0.001), and reads `func(n, x)` as
// the straight line between the two samples around x (clamped to [0, 1]). The converter
// computes the same samples and writes the call as that line, in the cell language.

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "lang/convert/lsystem_file.h"

namespace ontogen::convert {

/// One function of the view file, sampled as cpfg samples it.
struct SampledFunction {
  std::string file;             ///< as the view file names it
  /// Of a function set, its `name:` (cpfg defines it as the function's number for the
  /// file, `func(LEAF, x)`); empty otherwise.
  std::string name;
  std::vector<double> samples;  ///< the values at x = i / (samples - 1)
  std::string error;            ///< why it could not be read (samples empty then)
  bool setUnread = false;       ///< it stands for a function set that could not be read
};

/// The functions a view file names, in its order: each `function: FILE N` line adds one
/// (cpfg's func(1, x) is the first); a `function set: FILE.fset` line (a gallery of
/// the function editor, `funcgalleryver 1 1`) takes the place of those before it by the
/// set's functions, named (their names count only while no `function:` line follows).
/// `read` gives the files' texts (none: each function says so in `error`; a set that
/// cannot be read is one function with setUnread and the error).
std::vector<SampledFunction> viewFunctions(std::string_view view, const SideFileReader& read);

/// The samples of a function file of format `fver 1 1`, or nullopt with `error` set.
std::optional<std::vector<double>> sampleFunctionFile(std::string_view text, std::string& error);

/// The functions of a function set's text (`file` its name), or nullopt with `error` set.
std::optional<std::vector<SampledFunction>> sampleFunctionSet(std::string_view text, const std::string& file,
                                                             std::string& error);

/// The value of `function` at the cell-language expression `x`, as cpfg reads it
/// between its samples: a sum of each sample times its weight max(0, 1 - |k - i|),
/// k = clamp(x, 0, 1) * (samples - 1). `x` is written once per sample.
std::string sampledValue(const SampledFunction& function, const std::string& x);

}  // namespace ontogen::convert
