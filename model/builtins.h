#pragma once
// The table of built-in functions and constants of the cell language. The compiler
// resolves calls against it, error messages quote its signatures, and `ontogen help`
// prints it. `if(c, a, b)` is not here: the compiler evaluates it lazily.

#include <cstdint>
#include <span>
#include <string_view>

#include "model/random.h"

namespace ontogen {

/// What a built-in may read besides its arguments.
struct EvalEnvironment {
  RandomStream* random = nullptr;  ///< the stream of the current evaluation (stochastic functions)
  uint64_t seed = 0;               ///< the run's seed (noise)
};

using BuiltinFn = double (*)(const double* args, int argc, EvalEnvironment& env);

enum class BuiltinKind {
  Pure,        ///< depends on its arguments only; calls with constant arguments are folded
  Stochastic,  ///< draws from the evaluation's random stream
  Seeded,      ///< depends on the run's seed (smooth noise): deterministic within a run
};

struct BuiltinFunction {
  std::string_view name;
  int minArity;
  int maxArity;  ///< -1: no upper bound
  BuiltinKind kind;
  std::string_view signature;  ///< e.g. "besselj(n, x)"
  std::string_view doc;        ///< one line
  BuiltinFn fn;
};

struct BuiltinConstant {
  std::string_view name;
  double value;
  std::string_view doc;
};

std::span<const BuiltinFunction> builtinFunctions();
std::span<const BuiltinConstant> builtinConstants();
/// nullptr when there is no such function.
const BuiltinFunction* findBuiltin(std::string_view name);
const BuiltinConstant* findConstant(std::string_view name);

}  // namespace ontogen
