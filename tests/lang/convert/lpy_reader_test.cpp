// L-Py's .lpy files read into cell-language text (lang/convert/lpy_reader.cpp).

#include "lang/convert/lpy_reader.h"

#include <gtest/gtest.h>

#include "tests/lang/convert/convert_test_support.h"

namespace ontogen::convert {
namespace {

using test::convertText;

std::string body(const std::string& program) {
  const size_t open = program.find("{\n"), close = program.rfind("}");
  return program.substr(open + 2, close - open - 2);
}

TEST(LPyReader, ConstantsModulesAndPythonExpressions) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "# a comment\nR = 1.5 ** 2  # trailing\nmodule Apex, Leaf\n"
                       "Axiom: Apex(1) LeafAB _(0.1)\nderivation length: 2\nproduction:\n"
                       "Apex(x) : x < R and not x == 0 --> F(math.sqrt(x)) Apex(x + 1)\nendlsystem\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #define R 1.5 ^ 2\n  #angle 60\n  #until 2\n  axiom Apex(1) Leaf A B _(0.1)\n  production:\n"
            "  Apex(x) : x < R && !(x == 0) -> F(sqrt(x)) Apex(x + 1)\n");
}

TEST(LPyReader, ConditionalExpressionsBecomeIf) {
  auto c = convertText(Dialect::LPy, "a.lpy", "Axiom: B(1)\nB(i) --> B(2 if i % 2 else 3)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #angle 60\n  #until 1\n  axiom B(1)\n  B(i) -> B(if(fmod(fmod(i, 2) + 2, 2), 2, 3))\n");
}

// Python's remainder has the sign of the divisor (the cell language's '%' is C's fmod),
// '//' floors, and comparisons chain; the rest keeps its order and precedence.
TEST(LPyReader, PythonsRemainderFloorDivisionAndChainedComparisons) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "Axiom: A(1)\nA(x) : 0 <= x < 5 == 1 or not x % 2 --> "
                       "B(-x % 3 * 2, (x + 1) // -2 ** 2, f(x % y, 2) + 1, 2 ** -x % 4)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #angle 60\n  #until 1\n  axiom A(1)\n"
            "  A(x) : (0 <= x && x < 5 && 5 == 1) || !(fmod(fmod(x, 2) + 2, 2)) -> "
            "B(fmod(fmod(-x, 3) + 3, 3) * 2, floor((x + 1) / -2 ^ 2), f(fmod(fmod(x, y) + y, y), 2) + 1, "
            "fmod(fmod(2 ^ -x, 4) + 4, 4))\n");
  // A divisor, or the middle of a chain, that draws would be drawn again by each copy.
  auto divisor = convertText(Dialect::LPy, "a.lpy", "Axiom: A(1)\nA(x) --> B(x % random.uniform(1, 2))\n");
  EXPECT_EQ(divisor.line, 2);
  EXPECT_EQ(divisor.column, 14);
  EXPECT_TRUE(divisor.untranslatable);
  EXPECT_NE(divisor.error.find("Python's '%' of a divisor that draws a random number"), std::string::npos)
      << divisor.error;
  auto chain = convertText(Dialect::LPy, "a.lpy", "Axiom: A(1)\nA(x) : 0 < random() < x --> B\n");
  EXPECT_EQ(chain.line, 2);
  EXPECT_EQ(chain.column, 21);
  EXPECT_NE(chain.error.find("a chained comparison whose middle operand draws"), std::string::npos) << chain.error;
  // The remainder of a dividend that draws is written once: translated.
  auto dividend = convertText(Dialect::LPy, "a.lpy", "Axiom: A(1)\nA(x) --> B(random() % 1)\n");
  ASSERT_EQ(dividend.error, "");
  EXPECT_NE(dividend.program.find("B(fmod(fmod(uniform(), 1) + 1, 1))"), std::string::npos) << dividend.program;
}

TEST(LPyReader, NewContextsWildcardsAndAProduceBody) {
  auto c = convertText(Dialect::LPy, "a.lpy", "Axiom: A B\nproduction:\nA << B >> * --> C\nB :\n    produce D\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  #angle 60\n  #until 1\n  axiom A B\n  production:\n  A << B >> * -> C\n  B -> D\n");
}

// L-Py's wildcard names the label first, *(name, x); the cell language's binds the
// parameters alone. Its or(...) in a context is the cell language's alternatives.
TEST(LPyReader, WildcardParametersAndAlternatives) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "Axiom: C(1)B(2)A(3)\nproduction:\nC(x)*(n,y) < A(z) --> M(x,y,z)\n"
                       "*(n) < B(y) --> B(y)\nA > or( B(x)C(y)D(z), E(i), F(j)G(k) ) --> H\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #angle 60\n  #until 1\n  axiom C(1) B(2) A(3)\n  production:\n  C(x) *(y) < A(z) -> M(x, y, z)\n"
            "  *() < B(y) -> B(y)\n  A > (B(x) C(y) D(z) | E(i) | F(j) G(k)) -> H\n");
  auto variadic = convertText(Dialect::LPy, "a.lpy", "Axiom: A\nA > *(*args) --> B\n");
  EXPECT_EQ(variadic.line, 2);
  EXPECT_EQ(variadic.column, 7);
  EXPECT_NE(variadic.error.find("L-Py's '*args' takes any number of parameters"), std::string::npos) << variadic.error;
  auto predecessor = convertText(Dialect::LPy, "a.lpy", "Axiom: A\nproduction:\n*(n,x) --> B\n");
  EXPECT_EQ(predecessor.line, 3);
  EXPECT_EQ(predecessor.column, 1);
  EXPECT_TRUE(predecessor.untranslatable);
  EXPECT_NE(predecessor.error.find("a wildcard predecessor"), std::string::npos) << predecessor.error;
}

TEST(LPyReader, TheEditorsInitialisationSectionIsNotRead) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "Axiom: A\n###### INITIALISATION ######\ndef __initialiseContext__(context):\n\tpass\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  #angle 60\n  #until 1\n  axiom A\n");
}

// A function of several lines: each way's returned value, its locals put in, joined by
// if(); docstrings, pass and print read over. A way that returns nothing, a random local
// read twice, a loop over a parameter and a while are refused where they stand.
TEST(LPyReader, HelperFunctionsOfSeveralLinesAreOneExpression) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "M = 5\ndef size(s, t):\n  \"\"\" the size \"\"\"\n  y = s * 2\n  if t < M:\n"
                       "    y += t\n    return y / M\n  elif t == M: pass\n  else:\n    print(t)\n  return y\n"
                       "Axiom: A(size(1, 2))\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #define M 5\n  #angle 60\n  #until 1\n"
            "  axiom A((if(2 < M, (((1 * 2) + (2)) / M), if(2 == M, ((1 * 2)), ((1 * 2))))))\n");
  auto none = convertText(Dialect::LPy, "a.lpy", "def f(x):\n  if x > 1:\n    return 2\n  x = 3\nAxiom: A(f(1))\n");
  EXPECT_EQ(none.line, 4);
  EXPECT_EQ(none.column, 3);
  EXPECT_NE(none.error.find("a way through this helper function ends here and returns no value"), std::string::npos)
      << none.error;
  auto twice = convertText(Dialect::LPy, "a.lpy",
                           "from random import *\ndef f(x):\n  r = random()\n  return r * r\nAxiom: A(f(1))\n");
  EXPECT_EQ(twice.line, 4);
  EXPECT_NE(twice.error.find("the random value 'r' read a second time"), std::string::npos) << twice.error;
  auto loop = convertText(Dialect::LPy, "a.lpy",
                          "def f(x):\n  for i in range(x):\n    x += i\n  return x\nAxiom: A(f(1))\n");
  EXPECT_EQ(loop.line, 2);
  EXPECT_EQ(loop.column, 18);
  EXPECT_NE(loop.error.find("a range over a value that is no written number"), std::string::npos) << loop.error;
  auto other = convertText(Dialect::LPy, "a.lpy", "def f(x):\n  while x > 1:\n    x -= 1\n  return x\nAxiom: A(f(3))\n");
  EXPECT_EQ(other.line, 2);
  EXPECT_NE(other.error.find("'while' in a helper function"), std::string::npos) << other.error;
}

// Python runs a function only where it is called: a helper of several lines the
// converter cannot translate stops the conversion where a value calls it, and nowhere
// else (a production's call, the axiom's, another helper's).
TEST(LPyReader, AHelperFunctionNothingCallsIsNotTranslated) {
  const std::string helper = "def f(x):\n  while x > 1:\n    x -= 1\n  return x\n";
  auto unused = convertText(Dialect::LPy, "a.lpy", helper + "Axiom: A(1)\nA(x) --> B(x)\n");
  ASSERT_EQ(unused.error, "");
  EXPECT_EQ(unused.warnings.size(), 0u);
  EXPECT_NE(unused.program.find("  A(x) -> B(x)\n"), std::string::npos) << unused.program;
  auto called = convertText(Dialect::LPy, "a.lpy", helper + "Axiom: A(1)\nA(x) --> B(f(x))\n");
  EXPECT_EQ(called.program, "");
  EXPECT_EQ(called.line, 2);
  EXPECT_EQ(called.column, 3);
  EXPECT_TRUE(called.untranslatable);
  EXPECT_NE(called.error.find("'while' in a helper function"), std::string::npos) << called.error;
  auto through = convertText(Dialect::LPy, "a.lpy", helper + "def g(y):\n  return f(y) + 1\nAxiom: A(g(2))\n");
  EXPECT_EQ(through.line, 2);
  EXPECT_NE(through.error.find("'while' in a helper function"), std::string::npos) << through.error;
}

// A name of the file that is one of the cell language's built-in functions (`step`,
// `max`) is the file's own constant or parameter, written with a trailing '_'; a call of
// the function keeps its name.
TEST(LPyReader, NamesOfBuiltInFunctionsAreTheFilesOwn) {
  auto c = convertText(Dialect::LPy, "a.lpy", "step = 0.3\nAxiom: A(step)\nA(max) --> F(max(max, step))\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #define step_ 0.3\n  #angle 60\n  #until 1\n  axiom A(step_)\n  A(max_) -> F(max(max_, step_))\n");
  // A helper's parameter named as a cell's state (time) takes the call's argument.
  auto helper = convertText(Dialect::LPy, "a.lpy", "def f(time):\n  return time * 2\nAxiom: A(1)\nA(x) --> B(f(x + 1))\n");
  ASSERT_EQ(helper.error, "");
  EXPECT_NE(helper.program.find("  A(x) -> B(((x + 1) * 2))\n"), std::string::npos) << helper.program;
}

// L-Py's Label of str(x): the Label holds the number, with a warning at the parameter;
// str() anywhere else stays Python the converter refuses.
TEST(LPyReader, StrOfANumberInALabelIsTheNumber) {
  auto c = convertText(Dialect::LPy, "a.lpy", "Axiom: A(2)\nA(x) --> @L(str(x + 1)) Label(str(x)) B\n");
  ASSERT_EQ(c.error, "");
  EXPECT_NE(c.program.find("  A(x) -> Label(x + 1) Label(x) B\n"), std::string::npos) << c.program;
  bool warned = false;
  for (const std::string& w : c.warnings)
    warned = warned || w.rfind("2:13: L-Py's Label shows the text of a number", 0) == 0;
  EXPECT_TRUE(warned) << testing::PrintToString(c.warnings);
  auto elsewhere = convertText(Dialect::LPy, "a.lpy", "Axiom: A(2)\nA(x) --> B(str(x))\n");
  EXPECT_EQ(elsewhere.line, 2);
  EXPECT_EQ(elsewhere.column, 12);
  EXPECT_NE(elsewhere.error.find("Python's 'str'"), std::string::npos) << elsewhere.error;
  auto more = convertText(Dialect::LPy, "a.lpy", "Axiom: A(2)\nA(x) --> @L(str(x) + 'a')\n");
  EXPECT_NE(more.error, "");
  // Rounded and cut, directly or through a helper function of one line (L-Py's tutorials'
  // `def txt(val): return str(round(val,2))[:5]`): still the number.
  auto cut = convertText(Dialect::LPy, "a.lpy",
                         "def txt(val):\n  return str(round(val,2))[:5]\nAxiom: A(2)\n"
                         "A(x) --> @L(str(round(x / 3, 2))[:4]) @L(txt(x * 2))\n");
  ASSERT_EQ(cut.error, "");
  EXPECT_NE(cut.program.find("  A(x) -> Label(x / 3) Label(((x * 2)))\n"), std::string::npos) << cut.program;
  auto elsewhere2 = convertText(Dialect::LPy, "a.lpy",
                                "def txt(val):\n  return str(round(val,2))[:5]\nAxiom: A(2)\nA(x) --> B(txt(x))\n");
  EXPECT_EQ(elsewhere2.line, 2);
  EXPECT_NE(elsewhere2.error.find("Python's 'str'"), std::string::npos) << elsewhere2.error;
}

// A string alone on a line is dropped, as Python drops it, even holding an arrow; a
// name given a string is no constant of the block: where a value reads it, the compiler
// finds a name the block does not define, at the line that reads it.
TEST(LPyReader, StringsAloneAndStringConstantsAreNoStatements) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "' --> B'\nu\"produce C\"\nt = 'A --> B'\nAxiom: A\nA :\n  'produce B'\n  produce C\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  #angle 60\n  #until 1\n  axiom A\n  A -> C\n");
  auto read = convertText(Dialect::LPy, "a.lpy", "t = 'a'\nAxiom: A(t)\n");
  ASSERT_EQ(read.error, "");
  EXPECT_NE(read.program.find("axiom A(t)"), std::string::npos) << read.program;
  EXPECT_EQ(read.program.find("#define t"), std::string::npos) << read.program;
  auto more = convertText(Dialect::LPy, "a.lpy", "t = 'a' + 'b'\nAxiom: A\n");
  EXPECT_EQ(more.line, 1);
  EXPECT_NE(more.error, "");
}

// PlantGL's vectors as module parameters: written as their components; a sum of vectors
// times numbers one expression per component, v[k] a component. A product of two vectors
// (PlantGL's dot product), a vector read as a number, compared or passed to a function,
// an index out of its range and a vector where the file gave a number are refused.
TEST(LPyReader, VectorParametersAreWrittenAsTheirComponents) {
  const std::string head = "Axiom: P(Vector3(1, 2, 3), 4)\nproduction:\n";
  auto c = convertText(Dialect::LPy, "a.lpy", head + "P(v, s) --> P(v * s - (v + Vector3(0,0,1)) / 2, v[2]) F(v[0])\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #angle 60\n  #until 1\n  axiom P(1, 2, 3, 4)\n  production:\n"
            "  P(v_0, v_1, v_2, s) -> P(v_0 * s - (v_0 + (0)) / 2, v_1 * s - (v_1 + (0)) / 2, v_2 * s - (v_2 + (1)) / 2, "
            "v_2) F(v_0)\n");
  struct Case {
    const char* production;
    int column;
    const char* message;
  };
  const Case cases[] = {
      {"P(v, s) --> P(v * v, s)\n", 15, "a vector parameter given other than a sum of vectors times numbers"},
      {"P(v, s) --> P(v / s + 1, s)\n", 15, "a vector parameter given other than a sum"},
      {"P(v, s) --> P(sqrt(v), s)\n", 15, "a vector parameter given other than a sum"},
      {"P(v, s) --> F(v)\n", 15, "the vector 'v' read as a number"},
      {"P(v, s) --> F(v[3])\n", 17, "an index of the vector 'v' other than a written 0 to 2"},
      {"P(v, s) --> P(s, s)\n", 15, "a vector parameter given other than a sum"},
      {"P(v, s) --> A(1) A(Vector2(1, 2))\n", 20, "a vector where the file gave this parameter of 'A' a number"},
  };
  for (const Case& k : cases) {
    auto r = convertText(Dialect::LPy, "a.lpy", head + k.production);
    EXPECT_EQ(r.program, "") << k.production;
    EXPECT_EQ(r.line, 3) << k.production << r.error;
    EXPECT_EQ(r.column, k.column) << k.production << r.error;
    EXPECT_NE(r.error.find(k.message), std::string::npos) << k.production << r.error;
  }
}

// A constant set again at the top level is one #define of its last value, the earlier
// value put in where the new one reads it; set again after a value, the axiom or the
// derivation length read it (Python read the earlier value there), it is refused; an
// augmented assignment of a name never set is Python the converter does not read.
TEST(LPyReader, AConstantSetAgainIsOneDefineOfItsLastValue) {
  auto c = convertText(Dialect::LPy, "a.lpy", "R = 1.5\nK = 3\nR *= R\nR = R + K\nAxiom: A(1)\nA(x) --> B(R)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #define K 3\n  #define R ((1.5) * ((1.5))) + K\n  #angle 60\n  #until 1\n  axiom A(1)\n"
            "  A(x) -> B(R)\n");
  for (const char* text : {"N = 2\nM = N\nN = 3\nAxiom: A\n", "N = 2\nAxiom: A(N)\nN = 3\n",
                           "N = 2\nderivation length: N\nN = 3\nAxiom: A\n"}) {
    auto read = convertText(Dialect::LPy, "a.lpy", text);
    EXPECT_EQ(read.line, 3) << text << read.error;
    EXPECT_NE(read.error.find("'N' set again after the file's values, axiom or derivation length read it"),
              std::string::npos)
        << read.error;
  }
  auto unset = convertText(Dialect::LPy, "a.lpy", "x += 1\nAxiom: A\n");
  EXPECT_EQ(unset.line, 1);
  EXPECT_NE(unset.error.find("'x': Python code"), std::string::npos) << unset.error;
}

// A loop over a range of written numbers in a helper function is written out turn by
// turn, as in a production body; a parameter may be changed as a local.
TEST(LPyReader, HelperFunctionsLoopOverRangesOfWrittenNumbers) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "def f(x):\n  s = 0\n  for i in range(1, 4):\n    s += i * x\n  x *= 2\n  return s + x\n"
                       "Axiom: A(f(2))\n");
  ASSERT_EQ(c.error, "");
  // 2 + 4 + 6 + 4: 16, as Python computes f(2).
  EXPECT_EQ(body(c.program),
            "  #angle 60\n  #until 1\n  axiom A(((((((0) + (1 * 2)) + (2 * 2)) + (3 * 2)) + (2 * (2)))))\n");
}

// A helper function reads the file's globals, whatever its caller binds: where a
// production's parameter or a body's local has the name of a global the function reads,
// writing the function's value into the production would read the parameter (L-Py's
// f(2) is 7 here, not 3), so it is refused at the call. A name the function binds
// itself is its own.
TEST(LPyReader, AHelperFunctionReadsTheGlobalsNotItsCallersNames) {
  const std::string functions = "n = 5\ndef f(x): return x + n\ndef g(x):\n  n = 1\n  return x + n\n"
                                "Axiom: A(1)\nproduction:\n";
  auto parameter = convertText(Dialect::LPy, "a.lpy", functions + "A(n) --> B(f(2))\n");
  EXPECT_EQ(parameter.line, 8);
  EXPECT_EQ(parameter.column, 12);
  EXPECT_NE(parameter.error.find("'f' reads the global 'n', which is a parameter or local here"), std::string::npos)
      << parameter.error;
  auto local = convertText(Dialect::LPy, "a.lpy", functions + "A(x) :\n  n = x\n  produce B(f(2))\n");
  EXPECT_EQ(local.line, 10);
  EXPECT_EQ(local.column, 13);
  EXPECT_NE(local.error.find("'f' reads the global 'n'"), std::string::npos) << local.error;
  auto own = convertText(Dialect::LPy, "a.lpy", functions + "A(n) --> B(g(2))\nC(x) --> D(f(x))\n");
  ASSERT_EQ(own.error, "");
  EXPECT_NE(own.program.find("A(n) -> B(((2 + (1))))\n  C(x) -> D((x + n))"), std::string::npos) << own.program;
}

TEST(LPyReader, PythonCodeIsAnErrorAtItsLine) {
  auto def = convertText(Dialect::LPy, "a.lpy", "Axiom: A(f(1))\n\ndef f(x):\n    global y\n    return x\n");
  EXPECT_EQ(def.line, 4);
  EXPECT_EQ(def.column, 5);
  EXPECT_TRUE(def.untranslatable);
  EXPECT_NE(def.error.find("'global' in a helper function: Python"), std::string::npos) << def.error;

  auto body = convertText(Dialect::LPy, "a.lpy", "Axiom: A\nA :\n    while True:\n        produce C\n");
  EXPECT_EQ(body.line, 3);
  EXPECT_EQ(body.column, 5);

  auto identity = convertText(Dialect::LPy, "a.lpy", "Axiom: A(1)\nA(x) --> A(x is None)\n");
  EXPECT_EQ(identity.line, 2);
  EXPECT_EQ(identity.column, 14);
  EXPECT_NE(identity.error.find("Python's 'is'"), std::string::npos) << identity.error;

  auto query = convertText(Dialect::LPy, "a.lpy", "Axiom: F ?R(1)\n");
  EXPECT_EQ(query.line, 1);
  EXPECT_EQ(query.column, 10);
  EXPECT_NE(query.error.find("L-Py's query '?R' has no cell-language counterpart"), std::string::npos) << query.error;

  auto import = convertText(Dialect::LPy, "a.lpy", "from numpy import random\nAxiom: A\n");
  EXPECT_EQ(import.line, 1);
  EXPECT_EQ(import.column, 19);
  EXPECT_NE(import.error.find("'random' imported from numpy: a name the converter reads as Python's or the cell "
                              "language's own"),
            std::string::npos)
      << import.error;
}

// A functional axiom is written when its body has one way, with no test and no random
// choice; else it is refused at the body. A global only a hook sets is one L-Py cannot
// read where it loads the file (the axiom, the derivation length, the top level).
TEST(LPyReader, FunctionalAxiomsOfOneWayAndTheValuesAtLoading) {
  auto c = convertText(Dialect::LPy, "a.lpy", "Axiom:\n  for i in range(2): nproduce B(i)\n  produce A\nB(x) --> C\n");
  ASSERT_EQ(c.error, "");
  EXPECT_NE(c.program.find("  axiom B(0) B(1) A\n"), std::string::npos) << c.program;
  const struct {
    const char* text;
    int line, column;
    const char* message;
  } refused[] = {
      {"n = 1\nAxiom:\n  if n > 1: produce A\n  else: produce B\n", 3, 3,
       "a functional axiom whose word depends on a test"},
      {"Axiom:\n  if random() < 0.5: produce A\n  produce B\n", 2, 3,
       "a functional axiom whose word depends on a test"},
      {"Axiom:\n  pass\n", 2, 3, "a functional axiom that produces nothing"},
      {"def Start():\n  global n\n  n = 2\nAxiom: A(n)\n", 4, 1, "a global that only a hook of L-Py sets"},
      {"def Start():\n  global n\n  n = 2\nAxiom: A\nderivation length: n\n", 5, 1,
       "a global that only a hook of L-Py sets"},
  };
  for (const auto& r : refused) {
    auto bad = convertText(Dialect::LPy, "a.lpy", r.text);
    EXPECT_EQ(bad.line, r.line) << r.text;
    EXPECT_EQ(bad.column, r.column) << r.text;
    EXPECT_NE(bad.error.find(r.message), std::string::npos) << r.text << bad.error;
  }
}

// What L-Py refuses or reads as nothing is a located error in the file, never a block
// without an axiom that only `check` finds: `#(` in a word (L-Py reads '#' as a comment
// and refuses '#('), an empty axiom, no axiom.
TEST(LPyReader, SharpModulesAndEmptyAxiomsAreLocatedErrors) {
  const struct {
    const char* text;
    int line, column;
    const char* message;
  } refused[] = {
      {"Axiom: #(0.001)F(1)\n", 1, 8, "'#(' in a word: L-Py reads '#' as the start of a comment and refuses '#('"},
      {"Axiom: F\nF --> F #  (2) F\n", 2, 9, "'#(' in a word"},
      {"Axiom: F\nF :\n  produce F #(2)\n", 3, 13, "'#(' in a word"},
      {"Axiom: \nderivation length: 1\n", 1, 1, "an empty axiom: L-Py starts from the empty word"},
      {"Axiom:  # (a comment)\nF --> F\n", 1, 9, "'#(' in a word"},
      {"\nderivation length: 1\nproduction:\nA --> B\n", 2, 1,
       "no Axiom: in this file: L-Py starts from the empty word"},
  };
  for (const auto& r : refused) {
    auto bad = convertText(Dialect::LPy, "a.lpy", r.text);
    EXPECT_EQ(bad.line, r.line) << r.text;
    EXPECT_EQ(bad.column, r.column) << r.text;
    EXPECT_NE(bad.error.find(r.message), std::string::npos) << r.text << bad.error;
  }
  // A comment that opens no parenthesis is a comment, as in L-Py.
  auto c = convertText(Dialect::LPy, "a.lpy", "Axiom: F # the start\nF --> F F # doubles (each step)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_NE(c.program.find("  axiom F\n  F -> F F\n"), std::string::npos) << c.program;
}

// The editor's curves and patches are refused at the name that reads them, where they
// were unknown names of the converted text; a parameter of that name is the one read.
TEST(LPyReader, TheEditorsObjectsAreRefusedWhereTheyAreRead) {
  const std::string editor =
      "###### INITIALISATION ######\ndef __initialiseContext__(context):\n"
      "\timport openalea.plantgl.all as pgl\n\tpath = pgl.NurbsCurve2D(\n\t    ctrlPointList = [(0, 0, 1)])\n"
      "\tpatch = NurbsPatch([[(0, 0, 0, 1)]])\n\tpath.name = \"path\"\n";
  auto axiom = convertText(Dialect::LPy, "a.lpy", "Axiom: SetGuide(path, 10) A\n" + editor);
  EXPECT_EQ(axiom.line, 1);
  EXPECT_EQ(axiom.column, 17);
  EXPECT_NE(axiom.error.find("'path', a NurbsCurve2D of L-Py's editor (its INITIALISATION section), which the "
                             "converter does not translate"),
            std::string::npos)
      << axiom.error;
  auto method = convertText(Dialect::LPy, "a.lpy", "Axiom: A(1)\nA(x) --> A(patch.getPointAt(x))\n" + editor);
  EXPECT_EQ(method.line, 2);
  EXPECT_EQ(method.column, 12);
  EXPECT_NE(method.error.find("'patch', a NurbsPatch of L-Py's editor"), std::string::npos) << method.error;
  auto parameter = convertText(Dialect::LPy, "a.lpy", "Axiom: A(1)\nA(path) --> A(path + 1)\n" + editor);
  EXPECT_EQ(parameter.error, "");
}

// getIterationNb() is 0 while L-Py loads the file: in the axiom, the derivation length
// and the top level's values; a production reads the step it derives from.
TEST(LPyReader, TheIterationNumberIsZeroWhereLPyLoadsTheFile) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "k = getIterationNb() + 2\nAxiom: A(getIterationNb())\nderivation length: getIterationNb() + 1\n"
                       "A(x) --> B(x, getIterationNb(), k)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_NE(c.program.find("  #define k 0 + 2\n  #angle 60\n  #until 0 + 1\n  axiom A(0)\n"
                           "  A(x) -> B(x, (time - 1), k)\n"),
            std::string::npos)
      << c.program;
  auto helper =
      convertText(Dialect::LPy, "a.lpy", "def f(x):\n  y = x + getIterationNb()\n  return y\nAxiom: A(f(1))\n");
  EXPECT_EQ(helper.line, 4);
  EXPECT_NE(helper.error.find("getIterationNb() read through a helper function where L-Py loads the file"),
            std::string::npos)
      << helper.error;
}

// Imports of other modules are read over where the names they bind mean nothing to the
// converter (a name read later is then an unknown name, located); a name it translates
// bound to another module's, or names it cannot know, are refused at the import.
TEST(LPyReader, ImportsOfOtherModulesBindNoTranslatedName) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "import warnings\nimport time as t, os.path\nfrom time import clock as c, sleep\n"
                       "from openalea.lpy.__lpyfuture__ import *\nAxiom: A\n");
  EXPECT_EQ(c.error, "");
  const struct {
    const char* text;
    int column;
    const char* message;
  } refused[] = {
      {"import numpy as math\n", 8,
       "'import numpy' binds the name 'math', which the converter reads as Python's module math"},
      {"import random as rd\nimport numpy as rd\n", 8,
       "binds the name 'rd', which the converter reads as Python's module random"},
      {"from numpy import (sqrt)\n", 20, "'sqrt' imported from numpy"},
      {"from numpy.random import normal as gauss\n", 36, "'gauss' imported from numpy.random"},
      {"from matplotlib.pyplot import *\n", 31,
       "'from matplotlib.pyplot import *' gives names the converter cannot know"},
      {"import t as\n", 9, "Python code"},
  };
  for (const auto& r : refused) {
    auto bad = convertText(Dialect::LPy, "a.lpy", std::string(r.text) + "Axiom: A\n");
    const int line = std::string(r.text).find('\n') + 1 == std::string(r.text).size() ? 1 : 2;
    EXPECT_EQ(bad.line, line) << r.text;
    EXPECT_EQ(bad.column, r.column) << r.text;
    EXPECT_NE(bad.error.find(r.message), std::string::npos) << r.text << bad.error;
  }
  // The name an import binds, read, is unknown: `t.time()` is an attribute.
  auto read = convertText(Dialect::LPy, "a.lpy", "import time as t\nAxiom: A(t.time())\n");
  EXPECT_EQ(read.line, 2);
  EXPECT_NE(read.error.find("the attribute 't.time'"), std::string::npos) << read.error;
}

// At the top level `global` changes nothing, an `assert` is a warning at its place,
// and backward() or forward() is the direction of every step: a block whose productions
// read a new context of the other direction is refused at the call.
TEST(LPyReader, TopLevelGlobalAssertAndDirection) {
  auto c = convertText(Dialect::LPy, "a.lpy", "global n\nn = 2\nassert n > 1\nbackward()\nAxiom: A\nA >> B --> C\n");
  ASSERT_EQ(c.error, "");
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0].rfind("3:1: 'assert' at L-Py's top level is not checked", 0), 0u) << c.warnings[0];
  for (const char* text : {"backward()\nAxiom: A\nA << B --> C\n", "forward()\nAxiom: A\nA >> B --> C\n"}) {
    auto other = convertText(Dialect::LPy, "a.lpy", text);
    EXPECT_EQ(other.line, 1) << text;
    EXPECT_EQ(other.column, 1) << text;
    EXPECT_NE(other.error.find("on every step, where a production has a new context of the other direction"),
              std::string::npos)
        << other.error;
  }
  // A hook's direction is set after the file's top level: it is the one that holds.
  auto hook = convertText(Dialect::LPy, "a.lpy", "backward()\ndef Start():\n  forward()\nAxiom: A\nA << B --> C\n");
  EXPECT_EQ(hook.error, "");
}

TEST(LPyReader, TheToolIsKnownByTheExtension) {
  EXPECT_EQ(dialectOfPath("a/b.lpy"), Dialect::LPy);
  EXPECT_EQ(dialectOfPath("b.l"), Dialect::Cpfg);
  EXPECT_EQ(dialectOfPath("b.cell"), std::nullopt);
}

}  // namespace
}  // namespace ontogen::convert

namespace ontogen::convert {
namespace {

// The turtle's angle set from Python, and the editor's scalars, which the file's own
// constants override.
TEST(LPyReader, AngleIncrementAndTheEditorsScalars) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "context().turtle.setAngleIncrement(90)\nN = 4\nAxiom: A(N, M, B, F)\n"
                       "###### INITIALISATION ######\ndef __initialiseContext__(context):\n"
                       "\tscalars = [('N', 'Integer', 10, 1, 20), ('M', 'Float', 0.5, 0., 1.), ('B', 'Bool', True), "
                       "('C', 'Category', None), ('F', 'Bool', False)]\n\tcontext[\"__scalars__\"] = scalars\n");
  ASSERT_EQ(c.error, "");
  const size_t open = c.program.find("{\n"), close = c.program.rfind("}");
  EXPECT_EQ(c.program.substr(open + 2, close - open - 2),
            "  #define N 4\n  #define M 0.5\n  #define B 1\n  #define F 0\n  #angle 90\n  #until 1\n"
            "  axiom A(N, M, B, F)\n");
  // Older editors wrote no type: (name, value, min, max), a category (name, None).
  auto untyped = convertText(Dialect::LPy, "a.lpy",
                             "N = 4\nAxiom: A(N, L, B, D)\n###### INITIALISATION ######\n"
                             "def __initialiseContext__(context):\n\tscalars = [('T', None), ('L', 29, 0, 99), "
                             "('N', 7, 0, 9), ('B', False, False, True), ('D', 42.85, 0.0, 99.99, 2)]\n");
  ASSERT_EQ(untyped.error, "");
  EXPECT_NE(untyped.program.find("  #define N 4\n  #define L 29\n  #define B 0\n  #define D 42.85\n  #angle 60\n"),
            std::string::npos)
      << untyped.program;
}

}  // namespace
}  // namespace ontogen::convert

namespace ontogen::convert {
namespace {

TEST(LPyReader, SeedAndPrintAtTheTopLevel) {
  auto c = convertText(Dialect::LPy, "a.lpy", "from random import seed\nseed(3)\nprint('hello')\nAxiom: A\n");
  ASSERT_EQ(c.error, "");
  EXPECT_NE(c.program.find("  #seed 3\n"), std::string::npos) << c.program;
}

}  // namespace
}  // namespace ontogen::convert

namespace ontogen::convert {
namespace {

// A helper function of one expression is inlined where it is called, its parameters
// replaced by the call's arguments; it may be defined after its use, as Python allows.
TEST(LPyReader, HelperFunctionsOfOneExpressionAreInlined) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "import random as rd\nAxiom: A(1)\nA(n) --> B(f(n + 1, 2) * g(), rd.uniform(0, n))\n"
                       "def f(x, y): return x ** y % 3\ndef g():\n    return f(2, 1)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #angle 60\n  #until 1\n  axiom A(1)\n"
            "  A(n) -> B((fmod(fmod((n + 1) ^ 2, 3) + 3, 3)) * ((fmod(fmod(2 ^ 1, 3) + 3, 3))), uniform(0, n))\n");
  // A call with another number of arguments, and an argument that draws read twice.
  auto count = convertText(Dialect::LPy, "a.lpy", "def f(x): return x\nAxiom: A(f(1, 2))\n");
  EXPECT_EQ(count.line, 2);
  EXPECT_EQ(count.column, 10);
  EXPECT_NE(count.error.find("the function 'f' takes 1 parameters; this call gives 2"), std::string::npos)
      << count.error;
  auto twice = convertText(Dialect::LPy, "a.lpy", "def f(x): return x * x\nAxiom: A(f(random()))\n");
  EXPECT_EQ(twice.line, 2);
  EXPECT_EQ(twice.column, 10);
  EXPECT_NE(twice.error.find("an argument that draws a random number, read 2 times by 'f'"), std::string::npos)
      << twice.error;
  // A hook that returns stays Python.
  auto hook = convertText(Dialect::LPy, "a.lpy", "def StartEach(): return 1\nAxiom: A\n");
  EXPECT_EQ(hook.line, 1);
  EXPECT_EQ(hook.column, 18);
  EXPECT_NE(hook.error.find("'return', which gives L-Py a new word, in L-Py's StartEach()"), std::string::npos)
      << hook.error;
}

}  // namespace
}  // namespace ontogen::convert

namespace ontogen::convert {
namespace {

// A conditional inside parentheses or among a call's arguments is read as one of its own.
TEST(LPyReader, ConditionalsInsideParentheses) {
  auto c = convertText(Dialect::LPy, "a.lpy", "Axiom: A(1)\nA(x) --> B((1 if x > 0 else 2) + 1, max(0 if x else 1, 3))\n");
  ASSERT_EQ(c.error, "");
  EXPECT_NE(c.program.find("B((if(x > 0, 1, 2)) + 1, max(if(x, 0, 1), 3))"), std::string::npos) << c.program;
  auto cpfg = convertText(Dialect::Cpfg, "a.l", "Axiom: A(1)\nA(x) --> B(2 * (x > 0 ? 1 : 2), max(x ? 0 : 1, 3))\n");
  ASSERT_EQ(cpfg.error, "");
  EXPECT_NE(cpfg.program.find("B(2 * (if(x > 0, 1, 2)), max(if(x, 0, 1), 3))"), std::string::npos) << cpfg.program;
}

}  // namespace
}  // namespace ontogen::convert

namespace ontogen::convert {
namespace {

// Text that nests or grows without bound is a located error, read in linear time.
TEST(LPyReader, DeepParenthesesAndGrowingRewritesAreBounded) {
  std::string deep = "Axiom: A(";
  for (int k = 0; k < 300; ++k) deep += "(";
  deep += "1 if x else 2";
  for (int k = 0; k < 300; ++k) deep += ")";
  auto parentheses = convertText(Dialect::LPy, "a.lpy", deep + ")\n");
  EXPECT_EQ(parentheses.line, 1);
  EXPECT_EQ(parentheses.column, 210);
  EXPECT_NE(parentheses.error.find("nested too deeply (more than 200 parentheses)"), std::string::npos)
      << parentheses.error;
  std::string chain = "Axiom: A(";
  for (int k = 0; k < 20000; ++k) chain += "x % ";
  auto remainders = convertText(Dialect::LPy, "a.lpy", chain + "3)\n");
  EXPECT_EQ(remainders.line, 1);
  EXPECT_NE(remainders.error.find("this expression grows past 256 KiB"), std::string::npos) << remainders.error;
  std::string calls;
  for (int k = 0; k < 40; ++k)
    calls += "def f" + std::to_string(k) + "(x): return f" + std::to_string(k + 1) + "(x) + f" +
             std::to_string(k + 1) + "(x)\n";
  auto inlined = convertText(Dialect::LPy, "a.lpy", calls + "def f40(x): return x\nAxiom: A(f0(1))\n");
  EXPECT_NE(inlined.error.find("the calls of helper functions or macros write more than 4 MiB"), std::string::npos)
      << inlined.error;
}

}  // namespace
}  // namespace ontogen::convert
