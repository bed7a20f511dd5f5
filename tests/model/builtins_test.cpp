#include "model/builtins.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "model/noise.h"
#include "model/random.h"

namespace ontogen {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = std::numbers::pi;

// Calls a built-in by name through the table, as the compiled program does.
double call(std::string_view name, std::initializer_list<double> args, EvalEnvironment& env) {
  const BuiltinFunction* function = findBuiltin(name);
  EXPECT_NE(function, nullptr) << name;
  if (function == nullptr) return kNaN;
  const int argc = static_cast<int>(args.size());
  EXPECT_GE(argc, function->minArity) << name;
  if (function->maxArity >= 0) {
    EXPECT_LE(argc, function->maxArity) << name;
  }
  return function->fn(args.begin(), argc, env);
}

// Pure and seeded calls: no random stream, so a stray draw would trip the assertion.
double call(std::string_view name, std::initializer_list<double> args) {
  EvalEnvironment env{.random = nullptr, .seed = 7};
  return call(name, args, env);
}

// ---- The table ----------------------------------------------------------------------

TEST(BuiltinTable, NamesAreUniqueIdentifiers) {
  std::set<std::string_view> names;
  for (const BuiltinFunction& function : builtinFunctions()) {
    EXPECT_TRUE(names.insert(function.name).second) << "duplicate " << function.name;
    ASSERT_FALSE(function.name.empty());
    EXPECT_TRUE(function.name[0] >= 'a' && function.name[0] <= 'z') << function.name;
    for (char c : function.name) {
      EXPECT_TRUE((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9')) << function.name;
    }
  }
  for (const BuiltinConstant& constant : builtinConstants()) {
    EXPECT_TRUE(names.insert(constant.name).second)
        << constant.name << " is both a function and a constant, or a duplicate";
  }
}

TEST(BuiltinTable, EntriesAreWellFormed) {
  for (const BuiltinFunction& function : builtinFunctions()) {
    SCOPED_TRACE(std::string(function.name));
    EXPECT_GE(function.minArity, 0);
    EXPECT_LE(function.minArity, 3);
    EXPECT_TRUE(function.maxArity == -1 || function.maxArity >= function.minArity);
    EXPECT_LE(function.maxArity, 3);
    EXPECT_NE(function.fn, nullptr);
    // The signature opens with the name and is a call.
    EXPECT_EQ(function.signature.substr(0, function.name.size() + 1),
              std::string(function.name) + "(");
    EXPECT_EQ(function.signature.back(), ')');
    EXPECT_FALSE(function.doc.empty());
    EXPECT_EQ(function.doc.find('\n'), std::string_view::npos) << "doc must be one line";
  }
  for (const BuiltinConstant& constant : builtinConstants()) {
    EXPECT_FALSE(constant.doc.empty()) << constant.name;
    EXPECT_EQ(constant.doc.find('\n'), std::string_view::npos) << constant.name;
  }
}

TEST(BuiltinTable, HasTheDocumentedFunctions) {
  struct Expected {
    std::string_view name;
    int minArity;
    int maxArity;
    BuiltinKind kind;
  };
  const BuiltinKind pure = BuiltinKind::Pure;
  const std::vector<Expected> expected = {
      {"sin", 1, 1, pure},        {"cos", 1, 1, pure},        {"tan", 1, 1, pure},
      {"asin", 1, 1, pure},       {"acos", 1, 1, pure},       {"atan", 1, 1, pure},
      {"atan2", 2, 2, pure},      {"sinh", 1, 1, pure},       {"cosh", 1, 1, pure},
      {"tanh", 1, 1, pure},       {"sqrt", 1, 1, pure},       {"cbrt", 1, 1, pure},
      {"root", 1, 2, pure},       {"pow", 2, 2, pure},        {"exp", 1, 1, pure},
      {"log", 1, 2, pure},        {"log10", 1, 1, pure},      {"log2", 1, 1, pure},
      {"abs", 1, 1, pure},        {"floor", 1, 1, pure},      {"ceil", 1, 1, pure},
      {"round", 1, 1, pure},      {"trunc", 1, 1, pure},      {"fract", 1, 1, pure},
      {"min", 2, -1, pure},       {"max", 2, -1, pure},       {"clamp", 3, 3, pure},
      {"sign", 1, 1, pure},       {"hypot", 2, 2, pure},      {"lerp", 3, 3, pure},
      {"step", 2, 2, pure},       {"smoothstep", 3, 3, pure}, {"fmod", 2, 2, pure},
      {"deg", 1, 1, pure},        {"rad", 1, 1, pure},        {"besselj", 2, 2, pure},
      {"uniform", 0, 2, BuiltinKind::Stochastic},  {"ran", 1, 1, BuiltinKind::Stochastic},
      {"gaussian", 0, 2, BuiltinKind::Stochastic}, {"bernoulli", 1, 1, BuiltinKind::Stochastic},
      {"noise", 1, 3, BuiltinKind::Seeded},
  };
  EXPECT_EQ(builtinFunctions().size(), expected.size());
  for (const Expected& e : expected) {
    const BuiltinFunction* function = findBuiltin(e.name);
    ASSERT_NE(function, nullptr) << e.name;
    EXPECT_EQ(function->name, e.name);
    EXPECT_EQ(function->minArity, e.minArity) << e.name;
    EXPECT_EQ(function->maxArity, e.maxArity) << e.name;
    EXPECT_EQ(function->kind, e.kind) << e.name;
  }
}

TEST(BuiltinTable, FindReturnsTableEntriesOrNull) {
  for (const BuiltinFunction& function : builtinFunctions()) {
    EXPECT_EQ(findBuiltin(function.name), &function);
  }
  for (const BuiltinConstant& constant : builtinConstants()) {
    EXPECT_EQ(findConstant(constant.name), &constant);
  }
  EXPECT_EQ(findBuiltin("nosuch"), nullptr);
  EXPECT_EQ(findBuiltin(""), nullptr);
  EXPECT_EQ(findBuiltin("Sin"), nullptr);  // names are case-sensitive
  EXPECT_EQ(findBuiltin("si"), nullptr);
  EXPECT_EQ(findBuiltin("sine"), nullptr);
  EXPECT_EQ(findBuiltin("pi"), nullptr);  // a constant, not a function
  EXPECT_EQ(findConstant("sin"), nullptr);
  EXPECT_EQ(findConstant("nosuch"), nullptr);
}

TEST(BuiltinTable, TauIsReservedForModuleAge) {
  EXPECT_EQ(findConstant("tau"), nullptr);
  EXPECT_EQ(findBuiltin("tau"), nullptr);
}

// Every function, at every arity it accepts, over arguments that include zero,
// negatives, huge values, infinities and NaN: nothing may throw or crash (the
// sanitizers watch the rest).
TEST(BuiltinTable, EveryFunctionIsCallableAtEveryArity) {
  const std::vector<double> values = {0.0, -0.0, 1.0, -1.0, 0.5, -2.5, 3.0, 1e300, -1e300,
                                      kInf, -kInf, kNaN};
  RandomStream random(42);
  for (const BuiltinFunction& function : builtinFunctions()) {
    SCOPED_TRACE(std::string(function.name));
    const int maxArity = function.maxArity < 0 ? function.minArity + 3 : function.maxArity;
    for (int argc = function.minArity; argc <= maxArity; ++argc) {
      std::vector<double> args(static_cast<size_t>(std::max(argc, 1)), 0.5);
      EvalEnvironment env{.random = &random, .seed = 3};
      EXPECT_NO_THROW(function.fn(args.data(), argc, env));
      // Each argument position through every special value, the others at 0.5.
      for (int position = 0; position < argc; ++position) {
        for (double value : values) {
          args.assign(static_cast<size_t>(argc), 0.5);
          args[static_cast<size_t>(position)] = value;
          EXPECT_NO_THROW(function.fn(args.data(), argc, env));
        }
      }
    }
  }
}

TEST(BuiltinTable, PureFunctionsAreDeterministicAndDrawNothing) {
  for (const BuiltinFunction& function : builtinFunctions()) {
    if (function.kind != BuiltinKind::Pure) continue;
    SCOPED_TRACE(std::string(function.name));
    const std::vector<double> args = {0.3, 0.7, 0.9, 0.1};
    RandomStream random(5);
    EvalEnvironment env{.random = &random, .seed = 1};
    const double first = function.fn(args.data(), function.minArity, env);
    EvalEnvironment otherSeed{.random = nullptr, .seed = 2};
    const double second = function.fn(args.data(), function.minArity, otherSeed);
    EXPECT_EQ(first, second);
    RandomStream untouched(5);
    EXPECT_EQ(random.next(), untouched.next()) << "a pure function drew a random number";
  }
}

TEST(BuiltinTable, StochasticFunctionsDrawFromTheStream) {
  for (const BuiltinFunction& function : builtinFunctions()) {
    if (function.kind != BuiltinKind::Stochastic) continue;
    SCOPED_TRACE(std::string(function.name));
    const std::vector<double> args = {0.5, 2.0};
    RandomStream random(5);
    EvalEnvironment env{.random = &random, .seed = 1};
    function.fn(args.data(), function.minArity, env);
    RandomStream untouched(5);
    EXPECT_NE(random.next(), untouched.next()) << "a stochastic function drew nothing";
  }
}

// ---- Constants ----------------------------------------------------------------------

TEST(BuiltinConstants, Values) {
  ASSERT_NE(findConstant("pi"), nullptr);
  EXPECT_EQ(findConstant("pi")->value, kPi);
  ASSERT_NE(findConstant("e"), nullptr);
  EXPECT_EQ(findConstant("e")->value, std::numbers::e);
  ASSERT_NE(findConstant("true"), nullptr);
  EXPECT_EQ(findConstant("true")->value, 1.0);
  ASSERT_NE(findConstant("false"), nullptr);
  EXPECT_EQ(findConstant("false")->value, 0.0);
  ASSERT_NE(findConstant("inf"), nullptr);
  EXPECT_EQ(findConstant("inf")->value, kInf);
  EXPECT_EQ(builtinConstants().size(), 5u);
}

// ---- Trigonometry -------------------------------------------------------------------

TEST(BuiltinTrigonometry, Values) {
  EXPECT_DOUBLE_EQ(call("sin", {kPi / 6}), 0.5);
  EXPECT_NEAR(call("sin", {kPi}), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(call("cos", {0.0}), 1.0);
  EXPECT_DOUBLE_EQ(call("cos", {kPi / 3}), 0.5);
  EXPECT_DOUBLE_EQ(call("tan", {kPi / 4}), 1.0);
  EXPECT_DOUBLE_EQ(call("asin", {1.0}), kPi / 2);
  EXPECT_TRUE(std::isnan(call("asin", {2.0})));
  EXPECT_DOUBLE_EQ(call("acos", {-1.0}), kPi);
  EXPECT_DOUBLE_EQ(call("atan", {1.0}), kPi / 4);
  EXPECT_DOUBLE_EQ(call("atan", {-kInf}), -kPi / 2);
}

TEST(BuiltinTrigonometry, Atan2TakesYThenX) {
  EXPECT_DOUBLE_EQ(call("atan2", {1.0, 0.0}), kPi / 2);
  EXPECT_DOUBLE_EQ(call("atan2", {0.0, -1.0}), kPi);
  EXPECT_DOUBLE_EQ(call("atan2", {-1.0, -1.0}), -3 * kPi / 4);
  EXPECT_DOUBLE_EQ(call("atan2", {1.0, 2.0}), std::atan(0.5));
  EXPECT_DOUBLE_EQ(call("atan2", {2.0, 1.0}), std::atan(2.0));
}

TEST(BuiltinTrigonometry, Hyperbolic) {
  EXPECT_DOUBLE_EQ(call("sinh", {1.0}), 1.1752011936438014569);
  EXPECT_DOUBLE_EQ(call("cosh", {1.0}), 1.5430806348152437785);
  EXPECT_DOUBLE_EQ(call("tanh", {0.5}), 0.4621171572600097585);
  EXPECT_DOUBLE_EQ(call("tanh", {kInf}), 1.0);
}

TEST(BuiltinTrigonometry, DegreesAndRadians) {
  EXPECT_DOUBLE_EQ(call("deg", {kPi}), 180.0);
  EXPECT_DOUBLE_EQ(call("deg", {-kPi / 2}), -90.0);
  EXPECT_DOUBLE_EQ(call("rad", {180.0}), kPi);
  EXPECT_DOUBLE_EQ(call("rad", {45.0}), kPi / 4);
  EXPECT_DOUBLE_EQ(call("rad", {call("deg", {1.234})}), 1.234);
}

// ---- Powers and logarithms ----------------------------------------------------------

TEST(BuiltinPowers, Roots) {
  EXPECT_EQ(call("sqrt", {16.0}), 4.0);
  EXPECT_TRUE(std::isnan(call("sqrt", {-1.0})));
  // glibc's cbrt is not correctly rounded, so these allow a few ulps.
  EXPECT_DOUBLE_EQ(call("cbrt", {-27.0}), -3.0);
  EXPECT_DOUBLE_EQ(call("cbrt", {8.0}), 2.0);
}

TEST(BuiltinPowers, RootOfAnyOrder) {
  EXPECT_EQ(call("root", {9.0}), 3.0);  // one argument: square root
  EXPECT_EQ(call("root", {9.0, 2.0}), 3.0);
  EXPECT_DOUBLE_EQ(call("root", {-8.0, 3.0}), -2.0);
  EXPECT_DOUBLE_EQ(call("root", {8.0, 3.0}), 2.0);
  EXPECT_DOUBLE_EQ(call("root", {-27.0, 3.0}), -3.0);
  EXPECT_DOUBLE_EQ(call("root", {16.0, 4.0}), 2.0);
  EXPECT_DOUBLE_EQ(call("root", {-32.0, 5.0}), -2.0);
  EXPECT_DOUBLE_EQ(call("root", {-1e-9, 9.0}), -std::pow(1e-9, 1.0 / 9.0));
  EXPECT_DOUBLE_EQ(call("root", {27.0, -3.0}), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(call("root", {-27.0, -3.0}), -1.0 / 3.0);
  EXPECT_DOUBLE_EQ(call("root", {5.0, 1.0}), 5.0);
  EXPECT_DOUBLE_EQ(call("root", {-5.0, 1.0}), -5.0);
  EXPECT_DOUBLE_EQ(call("root", {2.0, 0.5}), 4.0);
  // No real root: even or non-integer order of a negative number.
  EXPECT_TRUE(std::isnan(call("root", {-16.0, 4.0})));
  EXPECT_TRUE(std::isnan(call("root", {-4.0})));
  EXPECT_TRUE(std::isnan(call("root", {-8.0, 2.5})));
}

TEST(BuiltinPowers, PowExpLog) {
  EXPECT_EQ(call("pow", {2.0, 10.0}), 1024.0);
  EXPECT_EQ(call("pow", {-2.0, 3.0}), -8.0);
  EXPECT_DOUBLE_EQ(call("pow", {4.0, 0.5}), 2.0);
  EXPECT_TRUE(std::isnan(call("pow", {-8.0, 1.0 / 3.0})));  // use root for that
  EXPECT_DOUBLE_EQ(call("exp", {1.0}), std::numbers::e);
  EXPECT_EQ(call("exp", {0.0}), 1.0);
  EXPECT_DOUBLE_EQ(call("log", {std::numbers::e}), 1.0);
  EXPECT_EQ(call("log", {1.0}), 0.0);
  EXPECT_EQ(call("log", {0.0}), -kInf);
  EXPECT_TRUE(std::isnan(call("log", {-1.0})));
  EXPECT_DOUBLE_EQ(call("log", {8.0, 2.0}), 3.0);
  EXPECT_DOUBLE_EQ(call("log", {1000.0, 10.0}), 3.0);
  EXPECT_DOUBLE_EQ(call("log", {0.25, 2.0}), -2.0);
  EXPECT_DOUBLE_EQ(call("log", {81.0, 3.0}), 4.0);
  EXPECT_DOUBLE_EQ(call("log10", {1000.0}), 3.0);
  EXPECT_DOUBLE_EQ(call("log10", {0.01}), -2.0);
  EXPECT_EQ(call("log2", {1024.0}), 10.0);
  EXPECT_EQ(call("log2", {0.125}), -3.0);
}

TEST(BuiltinPowers, Hypot) {
  EXPECT_EQ(call("hypot", {3.0, 4.0}), 5.0);
  EXPECT_EQ(call("hypot", {-5.0, 12.0}), 13.0);
  EXPECT_DOUBLE_EQ(call("hypot", {1e300, 1e300}), 1e300 * std::numbers::sqrt2);  // no overflow
}

// ---- Rounding and sign --------------------------------------------------------------

TEST(BuiltinRounding, Values) {
  EXPECT_EQ(call("abs", {-2.5}), 2.5);
  EXPECT_EQ(call("abs", {2.5}), 2.5);
  EXPECT_EQ(call("floor", {-1.5}), -2.0);
  EXPECT_EQ(call("floor", {1.5}), 1.0);
  EXPECT_EQ(call("ceil", {-1.5}), -1.0);
  EXPECT_EQ(call("ceil", {1.2}), 2.0);
  EXPECT_EQ(call("round", {2.5}), 3.0);
  EXPECT_EQ(call("round", {-2.5}), -3.0);
  EXPECT_EQ(call("round", {2.4}), 2.0);
  EXPECT_EQ(call("round", {0.49999999999999994}), 0.0);
  EXPECT_EQ(call("trunc", {-1.7}), -1.0);
  EXPECT_EQ(call("trunc", {1.7}), 1.0);
}

TEST(BuiltinRounding, Fract) {
  EXPECT_EQ(call("fract", {1.25}), 0.25);
  EXPECT_EQ(call("fract", {-0.25}), 0.75);
  EXPECT_EQ(call("fract", {-3.0}), 0.0);
  EXPECT_EQ(call("fract", {7.0}), 0.0);
  for (double x = -10.0; x < 10.0; x += 0.37) {
    const double f = call("fract", {x});
    EXPECT_GE(f, 0.0) << x;
    EXPECT_LT(f, 1.0) << x;
  }
}

TEST(BuiltinRounding, Fmod) {
  EXPECT_EQ(call("fmod", {7.0, 3.0}), 1.0);
  EXPECT_EQ(call("fmod", {-7.0, 3.0}), -1.0);  // the sign of x
  EXPECT_EQ(call("fmod", {7.0, -3.0}), 1.0);
  EXPECT_EQ(call("fmod", {5.5, 2.0}), 1.5);
  EXPECT_TRUE(std::isnan(call("fmod", {1.0, 0.0})));
}

TEST(BuiltinRounding, Sign) {
  EXPECT_EQ(call("sign", {-3.0}), -1.0);
  EXPECT_EQ(call("sign", {-1e-300}), -1.0);
  EXPECT_EQ(call("sign", {0.0}), 0.0);
  EXPECT_EQ(call("sign", {-0.0}), 0.0);
  EXPECT_EQ(call("sign", {2.0}), 1.0);
  EXPECT_EQ(call("sign", {kInf}), 1.0);
  EXPECT_EQ(call("sign", {-kInf}), -1.0);
  EXPECT_TRUE(std::isnan(call("sign", {kNaN})));
}

// ---- Ranges and interpolation -------------------------------------------------------

TEST(BuiltinRanges, MinMaxAreVariadic) {
  EXPECT_EQ(call("min", {3.0, 1.0}), 1.0);
  EXPECT_EQ(call("min", {1.0, 3.0}), 1.0);
  EXPECT_EQ(call("min", {3.0, 1.0, 2.0}), 1.0);
  EXPECT_EQ(call("min", {5.0, 4.0, 3.0, 2.0, -1.0, 6.0, 7.0}), -1.0);
  EXPECT_EQ(call("min", {-kInf, 0.0}), -kInf);
  EXPECT_EQ(call("max", {3.0, 1.0}), 3.0);
  EXPECT_EQ(call("max", {3.0, 7.0, 2.0, 5.0}), 7.0);
  EXPECT_EQ(call("max", {-5.0, -4.0, -3.0, -2.0, -6.0}), -2.0);
  EXPECT_EQ(call("max", {kInf, 0.0}), kInf);
  // The last argument is read, too.
  EXPECT_EQ(call("min", {2.0, 3.0, 4.0, 1.0}), 1.0);
  EXPECT_EQ(call("max", {2.0, 1.0, 0.0, 9.0}), 9.0);
}

TEST(BuiltinRanges, MinMaxPropagateNaN) {
  EXPECT_TRUE(std::isnan(call("min", {kNaN, 1.0})));
  EXPECT_TRUE(std::isnan(call("min", {1.0, kNaN})));
  EXPECT_TRUE(std::isnan(call("min", {1.0, 2.0, kNaN})));
  EXPECT_TRUE(std::isnan(call("max", {kNaN, 1.0})));
  EXPECT_TRUE(std::isnan(call("max", {1.0, kNaN})));
  EXPECT_TRUE(std::isnan(call("max", {1.0, kNaN, 2.0})));
}

TEST(BuiltinRanges, Clamp) {
  EXPECT_EQ(call("clamp", {5.0, 0.0, 1.0}), 1.0);
  EXPECT_EQ(call("clamp", {-5.0, 0.0, 1.0}), 0.0);
  EXPECT_EQ(call("clamp", {0.3, 0.0, 1.0}), 0.3);
  EXPECT_EQ(call("clamp", {0.0, 0.0, 1.0}), 0.0);
  EXPECT_EQ(call("clamp", {1.0, 0.0, 1.0}), 1.0);
  EXPECT_EQ(call("clamp", {-kInf, -2.0, 2.0}), -2.0);
  // Reversed bounds are defined, as min(max(x, lo), hi).
  EXPECT_EQ(call("clamp", {0.5, 1.0, 0.0}), 0.0);
  EXPECT_EQ(call("clamp", {5.0, 1.0, 0.0}), 0.0);
  EXPECT_TRUE(std::isnan(call("clamp", {kNaN, 0.0, 1.0})));
}

TEST(BuiltinRanges, Lerp) {
  EXPECT_EQ(call("lerp", {2.0, 4.0, 0.25}), 2.5);
  EXPECT_EQ(call("lerp", {2.0, 4.0, 0.0}), 2.0);
  EXPECT_EQ(call("lerp", {2.0, 4.0, 1.0}), 4.0);
  EXPECT_EQ(call("lerp", {0.1, 0.7, 1.0}), 0.7);  // exact at t = 1
  EXPECT_EQ(call("lerp", {0.0, 10.0, 1.5}), 15.0);
  EXPECT_EQ(call("lerp", {4.0, 2.0, 0.5}), 3.0);
}

TEST(BuiltinRanges, Step) {
  EXPECT_EQ(call("step", {1.0, 0.5}), 0.0);
  EXPECT_EQ(call("step", {1.0, 1.0}), 1.0);
  EXPECT_EQ(call("step", {1.0, 2.0}), 1.0);
  EXPECT_EQ(call("step", {-1.0, -2.0}), 0.0);
}

TEST(BuiltinRanges, Smoothstep) {
  EXPECT_EQ(call("smoothstep", {0.0, 1.0, 0.5}), 0.5);
  EXPECT_EQ(call("smoothstep", {0.0, 1.0, -1.0}), 0.0);
  EXPECT_EQ(call("smoothstep", {0.0, 1.0, 0.0}), 0.0);
  EXPECT_EQ(call("smoothstep", {0.0, 1.0, 1.0}), 1.0);
  EXPECT_EQ(call("smoothstep", {0.0, 1.0, 2.0}), 1.0);
  EXPECT_DOUBLE_EQ(call("smoothstep", {0.0, 2.0, 0.5}), 0.15625);
  EXPECT_DOUBLE_EQ(call("smoothstep", {1.0, 0.0, 0.25}), 0.84375);  // reversed edges
  // Equal edges: a step, not a division by zero.
  EXPECT_EQ(call("smoothstep", {1.0, 1.0, 0.5}), 0.0);
  EXPECT_EQ(call("smoothstep", {1.0, 1.0, 1.0}), 1.0);
  // Monotonic between the edges.
  double previous = 0.0;
  for (double x = 0.0; x <= 1.0; x += 0.01) {
    const double value = call("smoothstep", {0.0, 1.0, x});
    EXPECT_GE(value, previous);
    previous = value;
  }
}

// ---- Bessel -------------------------------------------------------------------------

TEST(BuiltinBessel, KnownValues) {
  // Reference values from mpmath at 30 digits.
  EXPECT_NEAR(call("besselj", {0.0, 2.404825557695773}), 0.0, 1e-12);  // first zero of J0
  EXPECT_NEAR(call("besselj", {1.0, 1.0}), 0.4400505857449335, 1e-15);
  EXPECT_NEAR(call("besselj", {0.0, 1.0}), 0.7651976865579666, 1e-15);
  EXPECT_NEAR(call("besselj", {2.0, 1.0}), 0.11490348493190048, 1e-15);
  EXPECT_NEAR(call("besselj", {3.0, 2.0}), 0.12894324947440205, 1e-15);
  EXPECT_NEAR(call("besselj", {0.0, 10.0}), -0.24593576445134834, 1e-14);
  EXPECT_NEAR(call("besselj", {1.0, 10.0}), 0.043472746168861437, 1e-14);
  EXPECT_NEAR(call("besselj", {10.0, 20.0}), 0.18648255802394508, 1e-13);
  EXPECT_NEAR(call("besselj", {0.0, 2000.0}), 0.0070983418331996168, 1e-12);
  EXPECT_NEAR(call("besselj", {50.0, 1.0}) / 2.9060049481732394e-80, 1.0, 1e-12);
  EXPECT_EQ(call("besselj", {0.0, 0.0}), 1.0);
  EXPECT_EQ(call("besselj", {3.0, 0.0}), 0.0);
}

TEST(BuiltinBessel, RealOrders) {
  EXPECT_NEAR(call("besselj", {2.3, 5.0}), 0.16944146976981293, 1e-14);
  EXPECT_NEAR(call("besselj", {7.5, 30.0}), 0.13142029812318965, 1e-13);
  // Half-integer orders are elementary: J_{1/2}(x) = sqrt(2 / (pi x)) sin x.
  for (double x : {0.1, 0.5, 2.0, 7.0, 40.0}) {
    EXPECT_NEAR(call("besselj", {0.5, x}), std::sqrt(2.0 / (kPi * x)) * std::sin(x), 1e-13) << x;
  }
  EXPECT_NEAR(call("besselj", {0.5, 2.0}), 0.51301613656182775, 1e-15);
}

TEST(BuiltinBessel, RecurrenceHolds) {
  // J_{n-1}(x) + J_{n+1}(x) = (2n / x) J_n(x), over the library's different methods
  // (series, continued fraction, asymptotic expansion).
  for (double n : {1.0, 2.0, 2.3, 5.5, 12.0}) {
    for (double x : {0.7, 3.0, 15.0, 80.0, 1500.0}) {
      const double sum = call("besselj", {n - 1, x}) + call("besselj", {n + 1, x});
      const double scaled = 2.0 * n / x * call("besselj", {n, x});
      EXPECT_NEAR(sum, scaled, 1e-10) << "n=" << n << " x=" << x;
    }
  }
}

TEST(BuiltinBessel, NegativeIntegerOrder) {
  EXPECT_NEAR(call("besselj", {-1.0, 1.0}), -0.4400505857449335, 1e-15);
  EXPECT_EQ(call("besselj", {-2.0, 1.0}), call("besselj", {2.0, 1.0}));
  EXPECT_EQ(call("besselj", {-3.0, 2.0}), -call("besselj", {3.0, 2.0}));
  EXPECT_EQ(call("besselj", {-0.0, 1.0}), call("besselj", {0.0, 1.0}));
}

TEST(BuiltinBessel, NegativeArgumentForIntegerOrder) {
  EXPECT_EQ(call("besselj", {2.0, -1.0}), call("besselj", {2.0, 1.0}));
  EXPECT_NEAR(call("besselj", {2.0, -1.0}), 0.11490348493190048, 1e-15);
  EXPECT_EQ(call("besselj", {1.0, -1.0}), -call("besselj", {1.0, 1.0}));
  EXPECT_EQ(call("besselj", {0.0, -10.0}), call("besselj", {0.0, 10.0}));
  EXPECT_EQ(call("besselj", {3.0, -2.0}), -call("besselj", {3.0, 2.0}));
  // Both negative: J_{-n}(-x) = J_n(x).
  EXPECT_EQ(call("besselj", {-3.0, -2.0}), call("besselj", {3.0, 2.0}));
  EXPECT_EQ(call("besselj", {-2.0, -1.0}), call("besselj", {2.0, 1.0}));
}

TEST(BuiltinBessel, UndefinedCasesAreNaN) {
  EXPECT_TRUE(std::isnan(call("besselj", {2.5, -1.0})));   // complex
  EXPECT_TRUE(std::isnan(call("besselj", {-0.5, 1.0})));   // negative non-integer order
  EXPECT_TRUE(std::isnan(call("besselj", {kNaN, 1.0})));
  EXPECT_TRUE(std::isnan(call("besselj", {1.0, kNaN})));
  EXPECT_TRUE(std::isnan(call("besselj", {kInf, 1.0})));
}

TEST(BuiltinBessel, DecaysAtInfinity) {
  EXPECT_EQ(call("besselj", {0.0, kInf}), 0.0);
  EXPECT_EQ(call("besselj", {2.5, kInf}), 0.0);
  EXPECT_EQ(call("besselj", {1.0, -kInf}), 0.0);
}

// ---- Random draws -------------------------------------------------------------------

// Draws n values of a stochastic built-in and returns their mean and variance.
struct Moments {
  double mean = 0.0;
  double variance = 0.0;
  double min = kInf;
  double max = -kInf;
};

Moments draw(std::string_view name, std::initializer_list<double> args, int n, uint64_t key) {
  RandomStream random(key);
  EvalEnvironment env{.random = &random, .seed = 0};
  double sum = 0.0, sumSquares = 0.0;
  Moments moments;
  for (int i = 0; i < n; ++i) {
    const double value = call(name, args, env);
    sum += value;
    sumSquares += value * value;
    moments.min = std::min(moments.min, value);
    moments.max = std::max(moments.max, value);
  }
  moments.mean = sum / n;
  moments.variance = sumSquares / n - moments.mean * moments.mean;
  return moments;
}

TEST(BuiltinRandom, UniformRanges) {
  const Moments unit = draw("uniform", {}, 100000, 1);
  EXPECT_GE(unit.min, 0.0);
  EXPECT_LT(unit.max, 1.0);
  EXPECT_NEAR(unit.mean, 0.5, 0.01);

  const Moments upTo = draw("uniform", {4.0}, 100000, 2);
  EXPECT_GE(upTo.min, 0.0);
  EXPECT_LT(upTo.max, 4.0);
  EXPECT_NEAR(upTo.mean, 2.0, 0.04);

  const Moments between = draw("uniform", {2.0, 5.0}, 100000, 3);
  EXPECT_GE(between.min, 2.0);
  EXPECT_LT(between.max, 5.0);
  EXPECT_NEAR(between.mean, 3.5, 0.03);
  EXPECT_NEAR(between.variance, 9.0 / 12.0, 0.02);

  const Moments ran = draw("ran", {10.0}, 100000, 4);
  EXPECT_GE(ran.min, 0.0);
  EXPECT_LT(ran.max, 10.0);
  EXPECT_NEAR(ran.mean, 5.0, 0.1);
}

TEST(BuiltinRandom, UniformNeverReachesTheUpperBound) {
  // The range is a single ulp: a + (b - a) u would round to b for u near 1.
  const double lo = 1.0, hi = std::nextafter(1.0, 2.0);
  const Moments tiny = draw("uniform", {lo, hi}, 10000, 5);
  EXPECT_EQ(tiny.min, lo);
  EXPECT_EQ(tiny.max, lo);
}

TEST(BuiltinRandom, EmptyRangeGivesItsBound) {
  const Moments empty = draw("uniform", {3.0, 3.0}, 100, 6);
  EXPECT_EQ(empty.min, 3.0);
  EXPECT_EQ(empty.max, 3.0);
  EXPECT_EQ(draw("ran", {0.0}, 100, 6).max, 0.0);
}

TEST(BuiltinRandom, Gaussian) {
  const Moments standard = draw("gaussian", {}, 100000, 7);
  EXPECT_NEAR(standard.mean, 0.0, 0.02);
  EXPECT_NEAR(standard.variance, 1.0, 0.02);

  const Moments shifted = draw("gaussian", {10.0}, 100000, 8);
  EXPECT_NEAR(shifted.mean, 10.0, 0.02);
  EXPECT_NEAR(shifted.variance, 1.0, 0.02);

  const Moments scaled = draw("gaussian", {10.0, 2.0}, 100000, 9);
  EXPECT_NEAR(scaled.mean, 10.0, 0.04);
  EXPECT_NEAR(scaled.variance, 4.0, 0.08);

  const Moments degenerate = draw("gaussian", {3.0, 0.0}, 100, 10);
  EXPECT_EQ(degenerate.min, 3.0);
  EXPECT_EQ(degenerate.max, 3.0);
}

TEST(BuiltinRandom, Bernoulli) {
  const Moments third = draw("bernoulli", {0.3}, 100000, 11);
  EXPECT_NEAR(third.mean, 0.3, 0.01);
  EXPECT_EQ(third.min, 0.0);
  EXPECT_EQ(third.max, 1.0);
  // Each draw is exactly 0 or 1: the variance of a 0/1 variable is mean (1 - mean).
  EXPECT_NEAR(third.variance, third.mean * (1.0 - third.mean), 1e-9);

  const Moments never = draw("bernoulli", {0.0}, 1000, 12);
  EXPECT_EQ(never.max, 0.0);
  const Moments always = draw("bernoulli", {1.0}, 1000, 13);
  EXPECT_EQ(always.min, 1.0);
  EXPECT_EQ(draw("bernoulli", {-0.5}, 100, 14).max, 0.0);
  EXPECT_EQ(draw("bernoulli", {1.5}, 100, 15).min, 1.0);
}

TEST(BuiltinRandom, DrawsAreDeterminedByTheStream) {
  for (std::string_view name : {"uniform", "ran", "gaussian", "bernoulli"}) {
    RandomStream a(mixKey(99, 1)), b(mixKey(99, 1)), c(mixKey(99, 2));
    EvalEnvironment envA{.random = &a, .seed = 0};
    EvalEnvironment envB{.random = &b, .seed = 1};  // the seed does not matter
    EvalEnvironment envC{.random = &c, .seed = 0};
    std::vector<double> fromA, fromB, fromC;
    for (int i = 0; i < 50; ++i) {
      fromA.push_back(call(name, {0.5}, envA));
      fromB.push_back(call(name, {0.5}, envB));
      fromC.push_back(call(name, {0.5}, envC));
    }
    EXPECT_EQ(fromA, fromB) << name;
    EXPECT_NE(fromA, fromC) << name;
  }
}

TEST(BuiltinRandom, UniformUsesTheStreamsUniform) {
  RandomStream stream(123), reference(123);
  EvalEnvironment env{.random = &stream, .seed = 0};
  EXPECT_EQ(call("uniform", {}, env), reference.uniform());
  EXPECT_EQ(call("uniform", {2.0, 4.0}, env), 2.0 + 2.0 * reference.uniform());
  EXPECT_EQ(call("gaussian", {}, env), reference.gaussian());
}

#ifdef NDEBUG
TEST(BuiltinRandom, MissingStreamGivesZeroInRelease) {
  EvalEnvironment env{.random = nullptr, .seed = 0};
  for (std::string_view name : {"uniform", "ran", "gaussian", "bernoulli"}) {
    EXPECT_EQ(call(name, {0.5}, env), 0.0) << name;
  }
}
#else
TEST(BuiltinRandomDeathTest, MissingStreamIsAProgrammingError) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EvalEnvironment env{.random = nullptr, .seed = 0};
  for (std::string_view name : {"uniform", "ran", "gaussian", "bernoulli"}) {
    EXPECT_DEATH(call(name, {0.5}, env), "random stream") << name;
  }
}
#endif

// ---- Noise --------------------------------------------------------------------------

TEST(BuiltinNoise, MissingCoordinatesAreZero) {
  EvalEnvironment env{.random = nullptr, .seed = 77};
  EXPECT_EQ(call("noise", {0.3}, env), smoothNoise(0.3, 0.0, 0.0, 77));
  EXPECT_EQ(call("noise", {0.3, 1.7}, env), smoothNoise(0.3, 1.7, 0.0, 77));
  EXPECT_EQ(call("noise", {0.3, 1.7, -2.2}, env), smoothNoise(0.3, 1.7, -2.2, 77));
}

TEST(BuiltinNoise, FollowsTheRunsSeed) {
  EvalEnvironment first{.random = nullptr, .seed = 1};
  EvalEnvironment again{.random = nullptr, .seed = 1};
  EvalEnvironment second{.random = nullptr, .seed = 2};
  int differing = 0;
  for (int i = 0; i < 20; ++i) {
    const double x = 0.37 + 1.13 * i, y = 0.5 * i + 0.21;
    EXPECT_EQ(call("noise", {x, y}, first), call("noise", {x, y}, again));
    if (call("noise", {x, y}, first) != call("noise", {x, y}, second)) ++differing;
  }
  EXPECT_GE(differing, 18);
}

}  // namespace
}  // namespace ontogen
