// L-Py's productions written as Python bodies, read as cell-language productions
// (lang/convert/python_body.cpp): each way through the tests one production, random
// choices weighted, anything else a located error.

#include "lang/convert/python_body.h"

#include <gtest/gtest.h>

#include <string>

#include "tests/lang/convert/convert_test_support.h"

namespace ontogen::convert {
namespace {

using test::convertText;

// The productions of a converted program: its lines after `production:`.
std::string rules(const std::string& program) {
  const size_t at = program.find("production:\n");
  if (at == std::string::npos) return program;
  const size_t close = program.rfind("}");
  return program.substr(at + 12, close - at - 12);
}

std::string lpy(const std::string& productions) {
  return "from math import *\nfrom random import *\nAxiom: A(1)\nproduction:\n" + productions + "endlsystem\n";
}

TEST(PythonBody, EveryWayThroughTheTestsIsAProduction) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       lpy("A(x) :\n  if x > 3:\n    nproduce F(x)\n    produce B\n  elif x > 1: produce C\n"
                           "  else:\n    produce D\n"));
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(rules(c.program),
            "  A(x) : x > 3 -> F(x) B\n  A(x) : !(x > 3) && x > 1 -> C\n  A(x) : !(x > 3) && !(x > 1) -> D\n");
}

TEST(PythonBody, LocalsAreSubstitutedAndTheWayGoesOnAfterAnIf) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       lpy("A(x) :\n  d = 1\n  if x > 1:\n    d = math.sqrt(x) * 2\n  d += x\n"
                           "  produce F(d, int(d), float(x), degrees(pi))\n"));
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(rules(c.program),
            "  A(x) : x > 1 -> F((sqrt(x) * 2) + (x), trunc(((sqrt(x) * 2) + (x))), (x), deg(pi))\n"
            "  A(x) : !(x > 1) -> F((1) + (x), trunc(((1) + (x))), (x), deg(pi))\n");
}

// `produce` ends the way; a way without it gives what was nproduced, or no production
// at all (L-Py then tries the next one): `return` and falling off the end alike.
TEST(PythonBody, AWayWithoutProduceGivesItsNProducedWordOrNothing) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       lpy("A(x) :\n  nproduce F\n  if x > 1: produce B\nC(x) :\n  if x > 1:\n    return\n"
                           "  print(x)\n  pass\n  produce D\nE(x) :\n  if x > 1: produce B\n"));
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(rules(c.program),
            "  A(x) : x > 1 -> F B\n  A(x) : !(x > 1) -> F\n  C(x) : !(x > 1) -> D\n  E(x) : x > 1 -> B\n");
}

// `for i in range(...)` over written numbers is written out turn by turn; a test of the
// turn alone is decided there (i == 0 holds on the first turn only), a test of a
// parameter splits the way as any test does; an empty range turns no time.
TEST(PythonBody, LoopsOverWrittenRangesAreWrittenOutTurnByTurn) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       lpy("A(x) :\n  for i in range(2):\n    if i == 0: nproduce F\n    elif x > i: nproduce G(i)\n"
                           "  for k in range(0): nproduce H\n  produce B(-i)\n"));
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(rules(c.program), "  A(x) : x > 1 -> F G(1) B(- 1)\n  A(x) : !(x > 1) -> F B(- 1)\n");
  // The range of an inner loop over the outer one's variable, and over a local holding a
  // written number, is read at the turn.
  auto nested = convertText(Dialect::LPy, "a.lpy",
                            lpy("A(x) :\n  n = 2\n  for i in range(n + 1):\n    for j in range(i, 0, -1): "
                                "nproduce F(i, j)\n  produce B\n"));
  ASSERT_EQ(nested.error, "");
  EXPECT_EQ(rules(nested.program), "  A(x) -> F(1, 1) F(2, 2) F(2, 1) B\n");
}

// `global n` in a body that only reads n changes nothing: Python reads the global
// anyway. A global the body sets is state between productions, refused (above).
TEST(PythonBody, AGlobalOnlyReadIsReadOver) {
  auto c = convertText(Dialect::LPy, "a.lpy", "n = 2\n" + lpy("A(x) :\n  global n\n  produce B(x * n)\n"));
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(rules(c.program), "  A(x) -> B(x * n)\n");
}

TEST(PythonBody, OneLineAndParenthesisedWords) {
  auto c = convertText(Dialect::LPy, "a.lpy", lpy("A(x) : produce B(x)\nB(x) :\n  produce (C\n    D(x)  # d\n  )\n"));
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(rules(c.program), "  A(x) -> B(x)\n  B(x) -> C D(x)\n");
}

// A uniform draw tested against a chance is a choice between weighted productions; the
// way that produces nothing keeps the module, as L-Py leaves it.
TEST(PythonBody, RandomTestsAreWeightedChoices) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       lpy("A(x) :\n  r = random()\n  if r <= min(1, x / 4):\n    produce B\n  produce C\n"
                           "B :\n  if x > 1 and 0.3 > random.uniform(0, 1):\n    produce D\nC :\n"
                           "  if 0.25 > uniform(0, 1): produce D(gauss(0, 1), uniform(2, 3))\n"));
  // `x > 1 and random() < p` mixes a test and a draw: refused, located.
  EXPECT_EQ(c.line, 11);
  EXPECT_EQ(c.column, 6);
  EXPECT_NE(c.error.find("a test of a random value other than a uniform draw compared with a chance"),
            std::string::npos)
      << c.error;
  auto ok = convertText(Dialect::LPy, "a.lpy",
                        lpy("A(x) :\n  r = random()\n  if r <= min(1, x / 4):\n    produce B\n  produce C\n"
                            "C :\n  if 0.25 > uniform(0, 1): produce D(gauss(0, 1), uniform(2, 3))\n"));
  ASSERT_EQ(ok.error, "");
  EXPECT_EQ(rules(ok.program),
            "  A(x) -> B : clamp(min(1, x / 4), 0, 1)\n  A(x) -> C : (1 - clamp(min(1, x / 4), 0, 1))\n"
            "  C -> D(gaussian(0, 1), uniform(2, 3)) : 0.25\n  C -> C : (1 - 0.25)\n");
}

TEST(PythonBody, ADrawAboveAChanceHoldsWithTheComplement) {
  auto c = convertText(Dialect::LPy, "a.lpy", lpy("A(x) :\n  if random() > x: produce B\n  else: produce C\n"));
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(rules(c.program),
            "  A(x) -> B : (1 - clamp(x, 0, 1))\n  A(x) -> C : (1 - (1 - clamp(x, 0, 1)))\n");
}

TEST(PythonBody, ARandomValueUsedTwiceIsRefused) {
  auto c = convertText(Dialect::LPy, "a.lpy", lpy("A(x) :\n  r = uniform(0, 1)\n  produce B(r) C(r)\n"));
  EXPECT_EQ(c.line, 7);
  EXPECT_EQ(c.column, 3);
  EXPECT_NE(c.error.find("the random value 'r' used a second time"), std::string::npos) << c.error;
  // Two tests of one draw are not two choices, unless against rising thresholds
  // (OneDrawAgainstRisingThresholdsIsAChoice).
  auto chain = convertText(Dialect::LPy, "a.lpy",
                           lpy("A(x) :\n  r = random()\n  if r < 0.3: produce B\n  elif r > 0.6: produce C\n"));
  EXPECT_EQ(chain.line, 7);
  EXPECT_NE(chain.error.find("the random value 'r' used a second time"), std::string::npos) << chain.error;
}

// L-Py tries a module's later productions where a body produces nothing; a weighted
// choice cannot, so a random way that keeps the module before another production of it
// is refused.
TEST(PythonBody, AKeptModuleBeforeALaterProductionIsRefused) {
  auto c = convertText(Dialect::LPy, "a.lpy", lpy("A(x) :\n  if random() < 0.5: produce B\nA(x) --> C\n"));
  EXPECT_EQ(c.line, 5);
  EXPECT_EQ(c.column, 1);
  EXPECT_NE(c.error.find("L-Py tries the later productions of A"), std::string::npos) << c.error;
  auto two = convertText(Dialect::LPy, "a.lpy",
                         lpy("A(x) :\n  if random() < 0.5: produce B\n  else: produce C\n"
                             "A(x) :\n  if random() < 0.5: produce D\n  else: produce E\n"));
  EXPECT_EQ(two.line, 8);
  EXPECT_EQ(two.column, 1);
  EXPECT_NE(two.error.find("a second body with a random choice for A"), std::string::npos) << two.error;
}

// L-Py's tests set a global in a body for their hooks to assert: nothing the word
// depends on reads it, so it is left out (the file's constant and the hooks' values of
// it too), with a warning at the body's `global` line. Read by a production, the axiom
// or a hook's group, it is state between productions: refused at that line.
TEST(PythonBody, AGlobalABodySetsIsLeftOutWhereOnlyAssertsReadIt) {
  const std::string hooks =
      "matched = None\ndef StartEach():\n  global matched\n  matched = None\n"
      "def EndEach():\n  if getIterationNb() == 1:\n    assert matched == 1\n  print(matched)\n";
  auto c = convertText(Dialect::LPy, "a.lpy",
                       hooks + "Axiom: I(2)\nderivation length: 3\nproduction:\nI(0) :\n  global matched\n"
                               "  matched = 1\n  produce *\nI(x) :\n  global matched\n  matched = 2\n"
                               "  produce I(x - 1) F(matched)\nendlsystem\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(c.program.find("matched"), std::string::npos) << c.program;
  EXPECT_NE(c.program.find("  I(0) -> ∅\n  I(x) -> I(x - 1) F(2)\n"), std::string::npos) << c.program;
  bool warned = false;
  for (const std::string& w : c.warnings)
    warned = warned || w.rfind("13:3: 'matched' set in a production body is read by nothing the word depends on", 0) == 0;
  EXPECT_TRUE(warned) << testing::PrintToString(c.warnings);

  const std::string body = "I(x) :\n  global n\n  n = x\n  produce I(x)\n";
  struct Reader {
    const char* text;
    int line;
  };
  const Reader readers[] = {
      {"n = 1\nAxiom: I(1)\nproduction:\nJ(y) --> J(n)\n", 6},
      {"n = 1\nAxiom: I(1)\nproduction:\nJ(y) : y > n --> J(y)\n", 6},
      {"n = 1\nm = n * 2\nAxiom: I(m)\nproduction:\n", 6},
      {"n = 1\ndef StartEach():\n  useGroup(n)\nAxiom: I(1)\nproduction:\n", 7},
  };
  for (const Reader& r : readers) {
    auto read = convertText(Dialect::LPy, "a.lpy", r.text + body);
    EXPECT_EQ(read.program, "") << r.text;
    EXPECT_EQ(read.line, r.line) << r.text << read.error;
    EXPECT_EQ(read.column, 3) << r.text << read.error;
    EXPECT_NE(read.error.find("'n' declared global and set in a production body, and read by"), std::string::npos)
        << read.error;
  }
}

// `n = randint(a, b)`: one way per whole number from a to b, each weighted 1/(b - a + 1),
// n that number on its way. Bounds that are no numbers, a bound a parameter hides, and
// randint elsewhere than alone in an assignment are refused at their place.
TEST(PythonBody, RandintChoosesAmongTheWholeNumbersOfItsRange) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       lpy("A(x) :\n  if x > 1:\n    n = random.randint(2, 4)\n    for i in range(n):\n"
                           "      nproduce F(i)\n  produce B(x)\n"));
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(rules(c.program),
            "  A(x) : x > 1 -> F(0) F(1) B(x) : 1 / 3\n  A(x) : x > 1 -> F(0) F(1) F(2) B(x) : 1 / 3\n"
            "  A(x) : x > 1 -> F(0) F(1) F(2) F(3) B(x) : 1 / 3\n  A(x) : !(x > 1) -> B(x)\n");
  auto one = convertText(Dialect::LPy, "a.lpy", lpy("A(x) :\n  n = randint(5, 5)\n  produce B(n)\n"));
  ASSERT_EQ(one.error, "");
  EXPECT_EQ(rules(one.program), "  A(x) -> B(5)\n");
  struct Case {
    const char* body;
    int line, column;
    const char* message;
  };
  const Case cases[] = {
      {"A(x) :\n  n = randint(1, x)\n  produce B(n)\n", 6, 18, "a bound of randint that is no whole number"},
      {"A(x) :\n  n = randint(1, 2.5)\n  produce B(n)\n", 6, 18, "a bound of randint that is no whole number"},
      {"A(x) :\n  n = randint(3, 1)\n  produce B(n)\n", 6, 7, "randint(a, b) with b below a"},
      {"A(x) :\n  n = randint(1, 100)\n  produce B(n)\n", 6, 7, "randint over more than 64 numbers"},
      {"A(x) :\n  n = randint(1, 2) + 1\n  produce B(n)\n", 6, 7, "Python's 'randint'"},
  };
  for (const Case& k : cases) {
    auto r = convertText(Dialect::LPy, "a.lpy", lpy(k.body));
    EXPECT_EQ(r.program, "") << k.body;
    EXPECT_EQ(r.line, k.line) << k.body << r.error;
    EXPECT_EQ(r.column, k.column) << k.body << r.error;
    EXPECT_NE(r.error.find(k.message), std::string::npos) << k.body << r.error;
  }
  // numpy's randint leaves out its upper bound: a randint of another module is refused.
  auto numpy = convertText(Dialect::LPy, "a.lpy", "from numpy.random import randint\nAxiom: A\n");
  EXPECT_EQ(numpy.line, 1);
  EXPECT_NE(numpy.error.find("'randint' imported from numpy.random"), std::string::npos) << numpy.error;
}

// A loop's range and randint's bounds read the file's constants (set once, before the
// body): the number is written out, and the constant in place of its name everywhere,
// with no #define. A constant a hook sets, set again, or hidden by a parameter is refused.
TEST(PythonBody, ConstantsWhereANumberIsWrittenOutAreWrittenInPlace) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "N = 2\nM = N + 1\nK = 7\nAxiom: A(N)\nderivation length: M\nproduction:\n"
                       "A(x) :\n  for i in range(M):\n    nproduce F(i * K)\n  produce A(x + N)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(c.program.substr(c.program.find("{\n") + 2),
            "  #define K 7\n  #angle 60\n  #until (3)\n  axiom A((2))\n  production:\n"
            "  A(x) -> F(0 * K) F(1 * K) F(2 * K) A(x + (2))\n}\n");
  const std::string loop = "Axiom: A(1)\nproduction:\nA(x) :\n  for i in range(N):\n    nproduce F\n  produce B\n";
  std::string hidden = "N = 2\n" + loop;
  hidden.replace(hidden.find("A(x) :"), 6, "A(N) :");
  struct Case {
    std::string text;
    int line, column;
    const char* message;
  };
  const Case cases[] = {
      {"N = 2\ndef Start():\n  global N\n  N = 3\n" + loop, 8, 18, "'N', which a hook of L-Py sets"},
      {"N = 2\n" + loop + "N = 3\n", 5, 18, "'N' is set more than once"},
      {hidden, 5, 18, "a range over a value that is no written number"},
      {loop + "N = 2\n", 4, 18, "a range over a value that is no written number"},
  };
  for (const Case& k : cases) {
    auto r = convertText(Dialect::LPy, "a.lpy", k.text);
    EXPECT_EQ(r.program, "") << k.text;
    EXPECT_EQ(r.line, k.line) << k.text << r.error;
    EXPECT_EQ(r.column, k.column) << k.text << r.error;
    EXPECT_NE(r.error.find(k.message), std::string::npos) << k.text << r.error;
  }
}

// `r = random()` then `if r <= p1: ... elif r <= p2: ... else: ...`: one draw, each
// branch a stochastic production of its chance. The draw read again after, or tested
// otherwise than on the left of `<` or `<=`, stays a second use, refused.
TEST(PythonBody, OneDrawAgainstRisingThresholdsIsAChoice) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       lpy("A(x) :\n  r = random()\n  if r <= 0.2: produce B\n  elif r < x: produce C\n"
                           "  produce D\n"));
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(rules(c.program),
            "  A(x) -> B : 0.2\n  A(x) -> C : max(0, clamp(x, 0, 1) - 0.2)\n"
            "  A(x) -> D : 1 - max(0.2, clamp(x, 0, 1))\n");
  auto again = convertText(Dialect::LPy, "a.lpy",
                           lpy("A(x) :\n  r = random()\n  if r <= 0.2: produce B\n  elif r < 0.5: produce C\n"
                               "  produce D(r)\n"));
  EXPECT_EQ(again.line, 9);
  EXPECT_NE(again.error.find("the random value 'r' used a second time"), std::string::npos) << again.error;
  auto both = convertText(Dialect::LPy, "a.lpy",
                          lpy("A(x) :\n  r = random()\n  if r <= 0.2 and x > 1: produce B\n"
                              "  elif r < 0.5: produce C\n"));
  EXPECT_NE(both.error.find("the random value 'r' used a second time"), std::string::npos) << both.error;
  auto right = convertText(Dialect::LPy, "a.lpy",
                           lpy("A(x) :\n  r = random()\n  if 0.2 > r: produce B\n  elif r < 0.5: produce C\n"));
  EXPECT_NE(right.error.find("the random value 'r' used a second time"), std::string::npos) << right.error;
}

TEST(PythonBody, OtherPythonIsALocatedError) {
  struct Case {
    const char* body;
    int line, column;
    const char* message;
  };
  const Case cases[] = {
      {"A(x) :\n  for i in [1, 2]:\n    nproduce F\n  produce B\n", 6, 12, "a 'for' over other than range(...)"},
      {"A(x) :\n  for i in range(x):\n    nproduce F\n  produce B\n", 6, 18, "a range over a value that is no written"},
      {"A(x) :\n  for i in range(1, 2.5):\n    nproduce F\n", 6, 21, "a range over a number that is not whole"},
      {"A(x) :\n  for i in range(0, 3, 0): nproduce F\n", 6, 12, "range() with a step of 0"},
      {"A(x) :\n  for i in range(300): nproduce F\n", 6, 12, "a range of more than 256 turns"},
      {"A(x) :\n  for i in range(20):\n    for j in range(20): nproduce F\n", 7, 5,
       "the loops of this body turn more than 256 times in all"},
      {"A(x) :\n  for i in range(3):\n    break\n", 7, 5, "'break': Python which ontogen"},
      {"A(x) :\n  for (i, j) in range(3): nproduce F\n", 6, 3, "a 'for' over other than one name"},
      {"A(x) :\n  while x > 1:\n    produce B\n", 6, 3, "'while': Python which ontogen"},
      {"A(x) :\n  global n, m\n  m += 1\n  produce B(m)\n", 6, 3, "'m' declared global and set in a production body"},
      {"A(x) :\n  return [B]\n", 6, 3, "a 'return' of a value"},
      {"A(x) :\n  produce B(randint(1, 3))\n", 6, 13, "Python's 'randint'"},
      {"A(x) :\n  a, b = 1, 2\n  produce B\n", 6, 3, "'a': Python which ontogen"},
      {"A(x) :\n  else:\n    produce B\n", 6, 3, "'elif' or 'else' without its 'if'"},
      {"A(x) :\n  if x > 1:\n      produce B\n    produce C\n", 8, 5, "unexpected indentation"},
      {"A(x) :\n", 5, 1, "a production head without a body"},
  };
  for (const Case& k : cases) {
    auto c = convertText(Dialect::LPy, "a.lpy", lpy(k.body));
    EXPECT_EQ(c.program, "") << k.body;
    EXPECT_EQ(c.line, k.line) << k.body << c.error;
    EXPECT_EQ(c.column, k.column) << k.body << c.error;
    EXPECT_NE(c.error.find(k.message), std::string::npos) << k.body << c.error;
  }
}

// Tests in a row double the ways through a body whether or not they produce: 13 give
// 8192, past the bound, where each way was followed before.
TEST(PythonBody, WaysThatProduceNothingAreBoundedToo) {
  std::string body = "A(x) :\n";
  for (int k = 0; k < 13; ++k) body += "  if x > " + std::to_string(k) + ": pass\n";
  auto c = convertText(Dialect::LPy, "a.lpy", lpy(body));
  EXPECT_EQ(c.program, "");
  EXPECT_EQ(c.line, 5);
  EXPECT_NE(c.error.find("this body has more than 4096 ways through its tests"), std::string::npos) << c.error;
}

TEST(PythonBody, QuietHooksAndImportsAreReadOver) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "import math\nfrom openalea.plantgl.all import *\ndef Start():\n  print('go')\n\n"
                       "def EndEach(lstring):\n  assert lstring == 'A'\n  pass\nAxiom: A\n");
  ASSERT_EQ(c.error, "");
  // backward() on every step is the direction a block with >> derives in; with <<, the
  // other direction, it is refused at the call.
  auto hook = convertText(Dialect::LPy, "a.lpy", "def StartEach():\n  backward()\nAxiom: A B\nA >> B --> C\n");
  EXPECT_EQ(hook.error, "");
  auto other = convertText(Dialect::LPy, "a.lpy", "def StartEach():\n  backward()\nAxiom: A B\nA << B --> C\n");
  EXPECT_EQ(other.line, 2);
  EXPECT_EQ(other.column, 3);
  EXPECT_NE(other.error.find("backward() on every step, where a production has a new context of the other"),
            std::string::npos)
      << other.error;
  auto switched = convertText(Dialect::LPy, "a.lpy",
                              "def StartEach():\n  if getIterationNb() > 2: backward()\nAxiom: A\n");
  EXPECT_EQ(switched.line, 2);
  EXPECT_NE(switched.error.find("a direction of derivation switched on one way of a test"), std::string::npos)
      << switched.error;
  auto numpy = convertText(Dialect::LPy, "a.lpy", "import numpy\nAxiom: A(numpy.pi)\n");
  EXPECT_EQ(numpy.line, 2);
  EXPECT_NE(numpy.error.find("the attribute 'numpy.pi'"), std::string::npos) << numpy.error;
}

// An `assert` in a hook is not checked by the converted block: a warning at each one,
// where it was read over in silence.
TEST(PythonBody, AnAssertInAHookIsAWarningAtItsPlace) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "def Start():\n  assert 1 > 0\ndef EndEach(lstring):\n  if getIterationNb() > 1:\n"
                       "    assert lstring == 'A'\n  pass\nAxiom: A\n");
  ASSERT_EQ(c.error, "");
  ASSERT_EQ(c.warnings.size(), 2u);
  EXPECT_EQ(c.warnings[0],
            "2:3: 'assert' in L-Py's Start() is not checked: the converted block runs on where L-Py stops at an "
            "assertion that fails");
  EXPECT_EQ(c.warnings[1].substr(0, 36), "5:5: 'assert' in L-Py's EndEach() is");
}

TEST(PythonBody, LogicalLinesJoinOpenParentheses) {
  const std::string text = "a(1,\n  2)\n\n  b [\nc\n";
  const std::vector<BodyLine> lines = logicalLines(text, 0, static_cast<uint32_t>(text.size()));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(text.substr(lines[0].begin, lines[0].end - lines[0].begin), "a(1,\n  2)");
  EXPECT_EQ(lines[1].indent, 2);
  EXPECT_EQ(text.substr(lines[1].begin, lines[1].end - lines[1].begin), "b [");
  EXPECT_EQ(lines[2].indent, 0);
}

}  // namespace
}  // namespace ontogen::convert
