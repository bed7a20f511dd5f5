// cpfg's functions func(n, x), sampled from the function files the view file names
// (lang/convert/cpfg_function.cpp).

#include "lang/convert/cpfg_function.h"

#include <gtest/gtest.h>

#include "tests/lang/convert/convert_test_support.h"

namespace ontogen::convert {
namespace {

// Four control points make one cubic Bézier segment: x(t) = t (x of the points 0, 1/4,
// 3/4, 1 is 0.5 at t = 0.5 exactly), y(0.5) = (2 + 3 * 2 + 3 * 4 + 4) / 8 = 3.
constexpr const char* kBezier =
    "fver 1 1\nname: bezier\nsamples: 3\nflip: off\npoints: 4\n"
    "0.000000 2.000000 1\n0.250000 2.000000 1\n0.750000 4.000000 1\n1.000000 4.000000 1\n";

TEST(CpfgFunction, SamplesAreTheCurvesValuesWhereItsXIsTheSample) {
  std::string error;
  auto samples = sampleFunctionFile(kBezier, error);
  ASSERT_TRUE(samples) << error;
  ASSERT_EQ(samples->size(), 3u);
  EXPECT_EQ((*samples)[1], 3.0);
  // At the ends the search stops within 0.001 of x = 0 and x = 1: y is within a few
  // millionths of 2 and 4 (y - 2 is 6 t^2 - 4 t^3 there).
  EXPECT_GT((*samples)[0], 2.0);
  EXPECT_LT((*samples)[0], 2.00001);
  EXPECT_LT((*samples)[2], 4.0);
  EXPECT_GT((*samples)[2], 3.99999);
}

TEST(CpfgFunction, APointsMultiplicityRepeatsIt) {
  // y of 5 everywhere: twice the same point keeps the curve at 5.
  std::string error;
  auto samples = sampleFunctionFile(
      "fver 1 1\nname: flat\nsamples: 5\nflip: off\npoints: 4\n0 5 2\n0.3 5\n0.6 5\n1 5 1\n", error);
  ASSERT_TRUE(samples) << error;
  ASSERT_EQ(samples->size(), 5u);
  for (double value : *samples) EXPECT_NEAR(value, 5.0, 1e-12);
}

TEST(CpfgFunction, ValuesBetweenSamplesAreTheLineBetweenThem) {
  SampledFunction function;
  function.file = "f.func";
  function.samples = {2, 3, 0};
  EXPECT_EQ(sampledValue(function, "x"),
            "((2) * max(0, 1 - abs(clamp(x, 0, 1) * 2 - 0)) + (3) * max(0, 1 - abs(clamp(x, 0, 1) * 2 - 1)))");
}

TEST(CpfgFunction, FilesItCannotReadSayWhy) {
  std::string error;
  EXPECT_FALSE(sampleFunctionFile("range: 0 1\npoints: 4\n", error));
  EXPECT_NE(error.find("format 'fver 1 1'"), std::string::npos) << error;
  EXPECT_FALSE(sampleFunctionFile("fver 1 1\nname: f\nsamples: 2\nflip: off\npoints: 4\n", error));
  EXPECT_NE(error.find("3 to 1024 samples"), std::string::npos) << error;
  EXPECT_FALSE(sampleFunctionFile("fver 1 1\nname: f\nsamples: 5\nflip: off\npoints: 4\n0 0\n1 1\n", error));
  EXPECT_NE(error.find("fewer points"), std::string::npos) << error;
  // x never reaches 1: cpfg would search for ever.
  EXPECT_FALSE(
      sampleFunctionFile("fver 1 1\nname: f\nsamples: 3\nflip: off\npoints: 4\n0 0\n0.1 0\n0.2 0\n0.3 0\n", error));
  EXPECT_NE(error.find("does not reach 0.5"), std::string::npos) << error;
}

TEST(CpfgFunction, TheViewFileNamesTheFunctionsInOrder) {
  auto functions = viewFunctions("angle factor: 8\nfunction: a.func 100\nfunction: b.func 100\n",
                                 [](const std::string& name) -> std::optional<std::string> {
                                   if (name == "a.func") return std::string(kBezier);
                                   return std::nullopt;
                                 });
  ASSERT_EQ(functions.size(), 2u);
  EXPECT_EQ(functions[0].file, "a.func");
  EXPECT_EQ(functions[0].samples.size(), 3u);
  EXPECT_EQ(functions[1].error, "the function file 'b.func' cannot be read");
}

// In a cpfg file: func(1, 0.5) is the middle sample; func(2, x) of a view file that names
// one function, a function file that cannot be read and an argument that draws are
// errors at the call.
TEST(CpfgFunction, CallsOfAFileAreTheirValuesOrErrorsAtTheCall) {
  auto reader = [](const std::string& name) -> std::optional<std::string> {
    if (name == "a.func") return std::string(kBezier);
    return std::nullopt;
  };
  auto convert = [&](const std::string& text, const std::string& view) {
    SourceFile file("a.l", text);
    DiagnosticSink sink;
    ConvertResult result = convertFile(file, Dialect::Cpfg, view, sink, kDefaultMaxSourceBytes, reader);
    std::string error;
    for (const Diagnostic& d : sink.diagnostics())
      if (d.severity != Severity::Warning)
        error = std::to_string(d.span.line()) + ":" + std::to_string(d.span.column()) + ": " + d.message;
    return std::make_pair(result.program.value_or(""), error);
  };
  auto [program, error] = convert("Axiom: A\nA --> F(func(1, 0.5))\n", "function: a.func 100\n");
  ASSERT_EQ(error, "");
  EXPECT_NE(program.find("A -> F(((2.0000"), std::string::npos) << program;
  EXPECT_NE(program.find("(3) * max(0, 1 - abs(clamp(0.5, 0, 1) * 2 - 1))"), std::string::npos) << program;
  EXPECT_EQ(convert("Axiom: A\nA --> F(func(2, 0.5))\n", "function: a.func 100\n").second,
            "2:9: func(2, x): the view file names 1 functions ('function: FILE N' lines), which func(1, x) and on "
            "read in order");
  EXPECT_EQ(convert("Axiom: A\nA --> F(func(1, 0.5))\n", "function: b.func 100\n").second,
            "2:9: func(1, x): the function file 'b.func' cannot be read");
  EXPECT_EQ(convert("Axiom: A\nA --> F(func(1, ran(1)))\n", "function: a.func 100\n").second.substr(0, 70),
            "2:17: an argument of func that draws a random number: the converter wr");
}

// A function set (.fset, `function set:` in the view file): the editor's gallery of
// functions, `func(n, x)` by number or by the name cpfg defines for each; a `function:`
// line after it keeps the numbers but not the names.
TEST(CpfgFunction, AFunctionSetsFunctionsAreCalledByNumberOrName) {
  const std::string flat = "fver 1 1\nname: FLAT.func\nsamples: 3\nflip: off\npoints: 4\n0 5\n0.3 5\n0.6 5\n1 5\n";
  const std::string set = "funcgalleryver 1 1\nitems: 2\n" + flat + std::string(kBezier);
  auto reader = [&](const std::string& name) -> std::optional<std::string> {
    if (name == "f.fset") return set;
    if (name == "bad.fset") return std::string("funcgalleryver 1 1\nitems: 2\n") + flat;
    return std::nullopt;
  };
  auto convert = [&](const std::string& text, const std::string& view) {
    SourceFile file("a.l", text);
    DiagnosticSink sink;
    ConvertResult result = convertFile(file, Dialect::Cpfg, view, sink, kDefaultMaxSourceBytes, reader);
    std::string error;
    for (const Diagnostic& d : sink.diagnostics())
      if (d.severity != Severity::Warning)
        error = std::to_string(d.span.line()) + ":" + std::to_string(d.span.column()) + ": " + d.message;
    return std::make_pair(result.program.value_or(""), error);
  };
  auto functions = viewFunctions("function set: f.fset\n", reader);
  ASSERT_EQ(functions.size(), 2u);
  EXPECT_EQ(functions[0].name, "FLAT");  // cpfg drops the name's '.func'
  EXPECT_EQ(functions[1].name, "bezier");
  EXPECT_EQ(functions[1].samples[1], 3.0);
  auto [program, error] = convert("Axiom: A\nA --> F(func(bezier, 0.5)) F(func(1, 0))\n", "function set: f.fset\n");
  ASSERT_EQ(error, "");
  EXPECT_NE(program.find("A -> F(((2.0000"), std::string::npos) << program;
  EXPECT_NE(program.find(") F(((5) * max(0, 1 - abs(clamp(0, 0, 1) * 2 - 0))"), std::string::npos) << program;
  // After a function: line the names are gone, the numbers stay.
  auto after = viewFunctions("function set: f.fset\nfunction: g.func 100\n", reader);
  ASSERT_EQ(after.size(), 3u);
  EXPECT_EQ(after[0].name, "");
  EXPECT_EQ(convert("Axiom: A\nA --> F(func(bezier, 0.5))\n", "function set: f.fset\nfunction: g.func 100\n").second,
            "2:14: the number of cpfg's function, func(n, x), is a whole number written in the file or a macro of one");
  EXPECT_EQ(convert("Axiom: A\nA --> F(func(1, 0.5))\n", "function set: bad.fset\n").second,
            "2:9: func(1, x): the function set 'bad.fset': its function 2: it is no function file of the format "
            "'fver 1 1' (the one the function editor writes)");
  EXPECT_EQ(convert("Axiom: A\nA --> F(func(1, 0.5))\n", "function set: none.fset\n").second,
            "2:9: func(1, x): the function set 'none.fset' cannot be read");
}

}  // namespace
}  // namespace ontogen::convert
