#include "model/builtins.h"

#include <array>
#include <cassert>
#include <cmath>
#include <exception>
#include <limits>
#include <numbers>

#include "model/noise.h"

namespace ontogen {

namespace {

using Env = EvalEnvironment;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

bool isInteger(double x) { return std::isfinite(x) && x == std::trunc(x); }
// fmod is exact, so this holds even beyond 2^53 (where every double is even).
bool isOddInteger(double x) { return isInteger(x) && std::fmod(x, 2.0) != 0.0; }

// ---- Trigonometry (radians) -------------------------------------------------------

double fnSin(const double* a, int, Env&) { return std::sin(a[0]); }
double fnCos(const double* a, int, Env&) { return std::cos(a[0]); }
double fnTan(const double* a, int, Env&) { return std::tan(a[0]); }
double fnAsin(const double* a, int, Env&) { return std::asin(a[0]); }
double fnAcos(const double* a, int, Env&) { return std::acos(a[0]); }
double fnAtan(const double* a, int, Env&) { return std::atan(a[0]); }
double fnAtan2(const double* a, int, Env&) { return std::atan2(a[0], a[1]); }
double fnSinh(const double* a, int, Env&) { return std::sinh(a[0]); }
double fnCosh(const double* a, int, Env&) { return std::cosh(a[0]); }
double fnTanh(const double* a, int, Env&) { return std::tanh(a[0]); }
double fnDeg(const double* a, int, Env&) { return a[0] * (180.0 / std::numbers::pi); }
double fnRad(const double* a, int, Env&) { return a[0] * (std::numbers::pi / 180.0); }

// ---- Powers and logarithms --------------------------------------------------------

double fnSqrt(const double* a, int, Env&) { return std::sqrt(a[0]); }
double fnCbrt(const double* a, int, Env&) { return std::cbrt(a[0]); }

double fnRoot(const double* a, int argc, Env&) {
  const double x = a[0];
  const double n = argc > 1 ? a[1] : 2.0;
  // The common roots are exact through the dedicated functions (pow(8, 1/3.) < 2).
  if (n == 2.0) return std::sqrt(x);
  if (n == 3.0) return std::cbrt(x);
  if (x < 0.0 && isOddInteger(n)) return -std::pow(-x, 1.0 / n);
  return std::pow(x, 1.0 / n);  // NaN for negative x otherwise: the root is not real
}

double fnPow(const double* a, int, Env&) { return std::pow(a[0], a[1]); }
double fnExp(const double* a, int, Env&) { return std::exp(a[0]); }

double fnLog(const double* a, int argc, Env&) {
  if (argc > 1) return std::log(a[0]) / std::log(a[1]);
  return std::log(a[0]);
}

double fnLog10(const double* a, int, Env&) { return std::log10(a[0]); }
double fnLog2(const double* a, int, Env&) { return std::log2(a[0]); }
double fnHypot(const double* a, int, Env&) { return std::hypot(a[0], a[1]); }

// ---- Rounding and sign ------------------------------------------------------------

double fnAbs(const double* a, int, Env&) { return std::fabs(a[0]); }
double fnFloor(const double* a, int, Env&) { return std::floor(a[0]); }
double fnCeil(const double* a, int, Env&) { return std::ceil(a[0]); }
double fnRound(const double* a, int, Env&) { return std::round(a[0]); }
double fnTrunc(const double* a, int, Env&) { return std::trunc(a[0]); }
double fnFract(const double* a, int, Env&) { return a[0] - std::floor(a[0]); }
double fnFmod(const double* a, int, Env&) { return std::fmod(a[0], a[1]); }

double fnSign(const double* a, int, Env&) {
  const double x = a[0];
  if (std::isnan(x)) return x;
  return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0);
}

// ---- Ranges and interpolation -----------------------------------------------------

// min and max propagate NaN (unlike std::fmin), so a broken argument shows in the result
// instead of being silently dropped.
double fnMin(const double* a, int argc, Env&) {
  double result = a[0];
  for (int i = 0; i < argc; ++i) {
    if (std::isnan(a[i])) return a[i];
    if (a[i] < result) result = a[i];
  }
  return result;
}

double fnMax(const double* a, int argc, Env&) {
  double result = a[0];
  for (int i = 0; i < argc; ++i) {
    if (std::isnan(a[i])) return a[i];
    if (a[i] > result) result = a[i];
  }
  return result;
}

// min(max(x, lo), hi) as in GLSL: defined (as hi) even when lo > hi, where std::clamp
// is undefined behaviour; a NaN x stays NaN.
double clamp(double x, double lo, double hi) {
  const double atLeastLo = x < lo ? lo : x;
  return atLeastLo > hi ? hi : atLeastLo;
}

double fnClamp(const double* a, int, Env&) { return clamp(a[0], a[1], a[2]); }
double fnLerp(const double* a, int, Env&) { return std::lerp(a[0], a[1], a[2]); }
double fnStep(const double* a, int, Env&) { return a[1] < a[0] ? 0.0 : 1.0; }

double fnSmoothstep(const double* a, int, Env&) {
  const double edge0 = a[0], edge1 = a[1], x = a[2];
  // Equal edges make a step rather than a division by zero.
  if (edge0 == edge1) return x < edge0 ? 0.0 : 1.0;
  const double t = clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// ---- Special functions ------------------------------------------------------------

// J_n(x) for real n >= 0 and x >= 0 from the standard library; the rest of the real
// plane by the integer-order symmetries J_{-n}(x) = (-1)^n J_n(x) and
// J_n(-x) = (-1)^n J_n(x). Non-integer orders with x < 0 are complex, and negative
// non-integer orders would need Y_n: both give NaN.
double besselJ(double n, double x) {
  if (std::isnan(n) || std::isnan(x) || std::isinf(n)) return kNaN;
  double sign = 1.0;
  if (n < 0.0) {
    if (!isInteger(n)) return kNaN;
    n = -n;
    if (isOddInteger(n)) sign = -sign;
  }
  if (x < 0.0) {
    if (!isInteger(n)) return kNaN;
    x = -x;
    if (isOddInteger(n)) sign = -sign;
  }
  if (std::isinf(x)) return 0.0;  // the oscillation decays like 1/sqrt(x)
  try {
    return sign * std::cyl_bessel_j(n, x);
  } catch (const std::exception&) {
    // libstdc++ throws when its continued fraction does not converge (huge arguments).
    return kNaN;
  }
}

double fnBesselJ(const double* a, int, Env&) { return besselJ(a[0], a[1]); }

// ---- Random draws -----------------------------------------------------------------

// Only the compiler calls stochastic built-ins, and it always supplies a stream; a
// missing one is a bug there. Release builds answer 0 rather than crash.
RandomStream* streamOf(Env& env) {
  assert(env.random != nullptr && "stochastic built-in evaluated without a random stream");
  return env.random;
}

// lo + (hi - lo) u for u in [0, 1), kept below hi where rounding would reach it.
double uniformBetween(double lo, double hi, double u) {
  const double value = lo + (hi - lo) * u;
  if (lo < hi && value >= hi) return std::nextafter(hi, lo);
  return value;
}

double fnUniform(const double* a, int argc, Env& env) {
  RandomStream* random = streamOf(env);
  if (random == nullptr) return 0.0;
  const double u = random->uniform();
  if (argc == 0) return u;
  if (argc == 1) return uniformBetween(0.0, a[0], u);
  return uniformBetween(a[0], a[1], u);
}

double fnRan(const double* a, int, Env& env) {
  RandomStream* random = streamOf(env);
  if (random == nullptr) return 0.0;
  return uniformBetween(0.0, a[0], random->uniform());
}

double fnGaussian(const double* a, int argc, Env& env) {
  RandomStream* random = streamOf(env);
  if (random == nullptr) return 0.0;
  const double mean = argc > 0 ? a[0] : 0.0;
  const double deviation = argc > 1 ? a[1] : 1.0;
  return mean + deviation * random->gaussian();
}

double fnBernoulli(const double* a, int, Env& env) {
  RandomStream* random = streamOf(env);
  if (random == nullptr) return 0.0;
  if (std::isnan(a[0])) return a[0];
  return random->uniform() < a[0] ? 1.0 : 0.0;
}

// ---- Seeded -----------------------------------------------------------------------

double fnNoise(const double* a, int argc, Env& env) {
  return smoothNoise(a[0], argc > 1 ? a[1] : 0.0, argc > 2 ? a[2] : 0.0, env.seed);
}

constexpr BuiltinKind kPure = BuiltinKind::Pure;
constexpr BuiltinKind kStochastic = BuiltinKind::Stochastic;
constexpr BuiltinKind kSeeded = BuiltinKind::Seeded;
constexpr int kVariadic = -1;

// Every built-in function, in the order `ontogen help` lists them. Signatures mark
// optional arguments with brackets.
constexpr auto kFunctions = std::to_array<BuiltinFunction>({
    {"sin", 1, 1, kPure, "sin(x)", "sine of x (radians)", fnSin},
    {"cos", 1, 1, kPure, "cos(x)", "cosine of x (radians)", fnCos},
    {"tan", 1, 1, kPure, "tan(x)", "tangent of x (radians)", fnTan},
    {"asin", 1, 1, kPure, "asin(x)", "arc sine of x, in radians in [-pi/2, pi/2]", fnAsin},
    {"acos", 1, 1, kPure, "acos(x)", "arc cosine of x, in radians in [0, pi]", fnAcos},
    {"atan", 1, 1, kPure, "atan(x)", "arc tangent of x, in radians in [-pi/2, pi/2]", fnAtan},
    {"atan2", 2, 2, kPure, "atan2(y, x)",
     "angle of the point (x, y) from the x axis, in radians in [-pi, pi]", fnAtan2},
    {"sinh", 1, 1, kPure, "sinh(x)", "hyperbolic sine of x", fnSinh},
    {"cosh", 1, 1, kPure, "cosh(x)", "hyperbolic cosine of x", fnCosh},
    {"tanh", 1, 1, kPure, "tanh(x)", "hyperbolic tangent of x", fnTanh},
    {"deg", 1, 1, kPure, "deg(x)", "the angle x (radians) in degrees", fnDeg},
    {"rad", 1, 1, kPure, "rad(x)", "the angle x (degrees) in radians", fnRad},

    {"sqrt", 1, 1, kPure, "sqrt(x)", "square root of x (NaN for x < 0)", fnSqrt},
    {"cbrt", 1, 1, kPure, "cbrt(x)", "cube root of x (negative for x < 0)", fnCbrt},
    {"root", 1, 2, kPure, "root(x[, n])",
     "n-th root of x (n = 2 by default); for odd integer n a negative x has a negative root",
     fnRoot},
    {"pow", 2, 2, kPure, "pow(x, y)", "x raised to the power y", fnPow},
    {"exp", 1, 1, kPure, "exp(x)", "e raised to the power x", fnExp},
    {"log", 1, 2, kPure, "log(x[, b])", "natural logarithm of x, or its logarithm to base b",
     fnLog},
    {"log10", 1, 1, kPure, "log10(x)", "base-10 logarithm of x", fnLog10},
    {"log2", 1, 1, kPure, "log2(x)", "base-2 logarithm of x", fnLog2},
    {"hypot", 2, 2, kPure, "hypot(x, y)", "sqrt(x^2 + y^2), without overflow", fnHypot},

    {"abs", 1, 1, kPure, "abs(x)", "absolute value of x", fnAbs},
    {"floor", 1, 1, kPure, "floor(x)", "largest integer not above x", fnFloor},
    {"ceil", 1, 1, kPure, "ceil(x)", "smallest integer not below x", fnCeil},
    {"round", 1, 1, kPure, "round(x)", "nearest integer to x, halves away from zero", fnRound},
    {"trunc", 1, 1, kPure, "trunc(x)", "x with its fraction dropped (rounded toward zero)",
     fnTrunc},
    {"fract", 1, 1, kPure, "fract(x)", "x - floor(x), in [0, 1)", fnFract},
    {"fmod", 2, 2, kPure, "fmod(x, y)", "remainder of x / y, with the sign of x", fnFmod},
    {"sign", 1, 1, kPure, "sign(x)", "-1, 0 or 1 as x is negative, zero or positive", fnSign},

    {"min", 2, kVariadic, kPure, "min(a, b, ...)", "smallest argument (NaN if any is NaN)",
     fnMin},
    {"max", 2, kVariadic, kPure, "max(a, b, ...)", "largest argument (NaN if any is NaN)",
     fnMax},
    {"clamp", 3, 3, kPure, "clamp(x, lo, hi)", "x limited to [lo, hi], i.e. min(max(x, lo), hi)",
     fnClamp},
    {"lerp", 3, 3, kPure, "lerp(a, b, t)", "a + (b - a) t: a at t = 0, b at t = 1", fnLerp},
    {"step", 2, 2, kPure, "step(edge, x)", "0 if x < edge, else 1", fnStep},
    {"smoothstep", 3, 3, kPure, "smoothstep(e0, e1, x)",
     "0 below e0, 1 above e1, a smooth cubic ramp between", fnSmoothstep},

    {"besselj", 2, 2, kPure, "besselj(n, x)",
     "Bessel function of the first kind J_n(x), real n (negative n only if integer)",
     fnBesselJ},

    {"uniform", 0, 2, kStochastic, "uniform([[a,] b])",
     "random number uniform in [0, 1), [0, b) or [a, b)", fnUniform},
    {"ran", 1, 1, kStochastic, "ran(x)", "random number uniform in [0, x) (cpfg's name)", fnRan},
    {"gaussian", 0, 2, kStochastic, "gaussian([mu[, sigma]])",
     "normally distributed random number, mean mu (0) and deviation sigma (1)", fnGaussian},
    {"bernoulli", 1, 1, kStochastic, "bernoulli(p)", "1 with probability p, else 0",
     fnBernoulli},

    {"noise", 1, 3, kSeeded, "noise(x[, y[, z]])",
     "smooth gradient noise in about [-1, 1], 0 at integer points; fixed for a run's seed",
     fnNoise},
});

// `tau` is deliberately absent: the language reserves it for a module's age.
constexpr auto kConstants = std::to_array<BuiltinConstant>({
    {"pi", std::numbers::pi, "the ratio of a circle's circumference to its diameter"},
    {"e", std::numbers::e, "the base of the natural logarithm"},
    {"true", 1.0, "1"},
    {"false", 0.0, "0"},
    {"inf", kInfinity, "positive infinity"},
});

}  // namespace

std::span<const BuiltinFunction> builtinFunctions() { return kFunctions; }

std::span<const BuiltinConstant> builtinConstants() { return kConstants; }

// A linear scan: the compiler resolves each name once, and the table is a few dozen rows.
const BuiltinFunction* findBuiltin(std::string_view name) {
  for (const BuiltinFunction& function : kFunctions) {
    if (function.name == name) return &function;
  }
  return nullptr;
}

const BuiltinConstant* findConstant(std::string_view name) {
  for (const BuiltinConstant& constant : kConstants) {
    if (constant.name == name) return &constant;
  }
  return nullptr;
}

}  // namespace ontogen
