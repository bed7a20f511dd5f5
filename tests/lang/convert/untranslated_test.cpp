// What the converter does not translate is never converted into something else: each
// construct is translated, kept with a located warning, or refused with a located error
// (lang/convert/foreign_syntax.cpp, lpy_reader.cpp, cpfg_reader.cpp).

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lang/convert/foreign_syntax.h"
#include "tests/lang/convert/convert_test_support.h"

namespace ontogen::convert {
namespace {

using test::convertText;

std::string body(const std::string& program) {
  const size_t open = program.find("{\n"), close = program.rfind("}");
  if (open == std::string::npos || close == std::string::npos) return program;
  return program.substr(open + 2, close - open - 2);
}

// The productions of a converted program: its lines from the first that holds "->".
std::string rules(const std::string& program) {
  const std::string b = body(program);
  size_t at = b.find("->");
  if (at == std::string::npos) return "";
  return b.substr(b.rfind('\n', at) + 1);
}

TEST(Untranslated, NoneInAContextIsNothingThere) {
  auto c = convertText(Dialect::LPy, "a.lpy", "Axiom: A\nproduction:\nNone < A > None --> M\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(rules(c.program), "  ∅ < A > ∅ -> M\n");
  auto successor = convertText(Dialect::LPy, "a.lpy", "Axiom: A\nA --> None\n");
  EXPECT_NE(successor.error, "");
  EXPECT_EQ(successor.line, 2);
}

TEST(Untranslated, RepetitionInAContextIsRefusedAtItsPlace) {
  auto c = convertText(Dialect::LPy, "a.lpy", "Axiom: I A\nproduction:\nx(I) < A --> B\n");
  EXPECT_EQ(c.program, "");
  EXPECT_EQ(c.line, 3);
  EXPECT_EQ(c.column, 1);
  EXPECT_TRUE(c.untranslatable);
  EXPECT_NE(c.error.find("L-Py's repetition x(...)"), std::string::npos) << c.error;
  // A module the file declares as x is its own.
  auto declared = convertText(Dialect::LPy, "a.lpy", "module x\nAxiom: x(1) A\nx(n) < A --> B\n");
  EXPECT_EQ(declared.error, "");
}

// L-Py's predefined modules are one module each, never split into letters: translated
// where ontogen's turtle has the command, kept by name with a warning where it has not.
TEST(Untranslated, LPyPredefinedModulesAreNeverLetters) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "Axiom: StartGC F nF(3, 1) EndGC SetHead(0,0,1,1,0,0) OLineTo(1,2,3) PinpointRel(1,0,0) "
                       "Sweep SetContour @O(2) @GcI ;(2) ; SetColor(3) Circle(1)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #angle 60\n  #until 1\n  axiom gcbegin F nF(3, 1) gcend SetHead(0, 0, 1, 1, 0, 0) OLineTo(1, 2, 3) "
            "PinpointRel(1, 0, 0) Sweep SetContour sphere(2) gcbegin I color(2) color color(3) disc(1)\n");
  ASSERT_EQ(c.warnings.size(), 6u);
  EXPECT_EQ(c.warnings[0].rfind("1:18: L-Py's module 'nF' has no counterpart in ontogen's turtle", 0), 0u)
      << c.warnings[0];
  EXPECT_NE(c.warnings[0].find("it draws nothing"), std::string::npos);
  auto frame = convertText(Dialect::LPy, "a.lpy", "Axiom: A ?F\n");
  EXPECT_EQ(frame.line, 1);
  EXPECT_EQ(frame.column, 10);
  EXPECT_TRUE(frame.untranslatable);
  // L-Py predefines no @Zq: it reads the modules @, Z and q(1) (lpy_parser.cpp's
  // ModuleClassTable::parse takes the longest name it knows, else one character).
  auto unknown = convertText(Dialect::LPy, "a.lpy", "Axiom: A @Zq(1)\n");
  ASSERT_EQ(unknown.error, "");
  EXPECT_EQ(body(unknown.program), "  #angle 60\n  #until 1\n  axiom A @ Z q(1)\n");
  ASSERT_EQ(unknown.warnings.size(), 1u);
  EXPECT_EQ(unknown.warnings[0].rfind("1:10: L-Py predefines no module '@Zq'", 0), 0u) << unknown.warnings[0];
  auto cpfg = convertText(Dialect::Cpfg, "a.l", "Lsystem: 1\nAxiom: A @Zq(1)\nendlsystem\n");
  EXPECT_EQ(cpfg.column, 10);
  EXPECT_NE(cpfg.error.find("'@Zq' is none ontogen can translate"), std::string::npos) << cpfg.error;
}

TEST(Untranslated, ASurfaceIsOneModuleNotATildeAndALetter) {
  for (Dialect dialect : {Dialect::Cpfg, Dialect::LPy}) {
    auto c = convertText(dialect, dialect == Dialect::Cpfg ? "a.l" : "a.lpy", "Axiom: F ~l(2) f\n");
    ASSERT_EQ(c.error, "");
    EXPECT_NE(c.program.find("axiom F Surface_l(2) f\n"), std::string::npos) << c.program;
    ASSERT_EQ(c.warnings.size(), 1u);
    EXPECT_EQ(c.warnings[0].rfind("1:10: ", 0), 0u) << c.warnings[0];
  }
}

// L-Py's scales: `scale N:` lines where the file matches contexts as a multiscale tree
// (option 3), `level N:` lines as a multi-level one (2); with its default axial matching
// the scales change no match, and the names are declared only. Base modules and
// plain-string matching (0) are refused at their place.
TEST(Untranslated, MultiscaleModulesConvertWhereTheFileMatchesAtScales) {
  const std::string init =
      "module U, E(x) : scale = 1\nmodule I : scale = 2\nAxiom: U I E(1)\n\n###### INITIALISATION ######\n\n"
      "def __initialiseContext__(context):\n\tcontext.options.setSelection('String matching',3)\n";
  auto multiscale = convertText(Dialect::LPy, "a.lpy", init);
  ASSERT_EQ(multiscale.error, "");
  EXPECT_EQ(body(multiscale.program), "  #angle 60\n  #until 1\n  axiom U I E(1)\n  scale 1: U E\n  scale 2: I\n");
  std::string axial = init;
  axial.replace(axial.find("',3)"), 4, "',1)");
  auto declared = convertText(Dialect::LPy, "a.lpy", axial);
  ASSERT_EQ(declared.error, "");
  EXPECT_EQ(body(declared.program), "  #angle 60\n  #until 1\n  axiom U I E(1)\n");
  std::string levels = init;
  levels.replace(levels.find("',3)"), 4, "',2)");
  auto multilevel = convertText(Dialect::LPy, "a.lpy", levels);
  ASSERT_EQ(multilevel.error, "");
  EXPECT_EQ(body(multilevel.program), "  #angle 60\n  #until 1\n  axiom U I E(1)\n  level 1: U E\n  level 2: I\n");
  auto base = convertText(Dialect::LPy, "a.lpy", "module A\nmodule B : base = A\nAxiom: B\n");
  EXPECT_EQ(base.line, 2);
  EXPECT_EQ(base.column, 12);
  EXPECT_TRUE(base.untranslatable);
  EXPECT_NE(base.error.find("base = A"), std::string::npos) << base.error;
  auto notWhole = convertText(Dialect::LPy, "a.lpy", "module A : scale = 1.5\nAxiom: A\n");
  EXPECT_EQ(notWhole.line, 1);
  EXPECT_EQ(notWhole.column, 20);
  EXPECT_NE(notWhole.error.find("a whole number from 0 to 255"), std::string::npos) << notWhole.error;
  std::string plain = init;
  plain.replace(plain.find("',3)"), 4, "',0)");
  auto matching = convertText(Dialect::LPy, "a.lpy", plain);
  EXPECT_EQ(matching.line, 8);
  EXPECT_EQ(matching.column, 31);
  EXPECT_NE(matching.error.find("'String matching' set to 'As String'"), std::string::npos) << matching.error;
}

TEST(Untranslated, AnAliasIsReadAsTheModuleItNames) {
  auto c = convertText(Dialect::LPy, "a.lpy", "module A(x), Bud = F\nAxiom: A(1) Bud\nA(x) --> A(x) Bud\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  #angle 60\n  #until 1\n  axiom F(1) F\n  F(x) -> F(x) F\n");
}

TEST(Untranslated, AQueryWithoutParametersHasTheThreeTheTurtleFills) {
  auto c = convertText(Dialect::LPy, "a.lpy", "Axiom: F(10) ?P\n");
  ASSERT_EQ(c.error, "");
  EXPECT_NE(c.program.find("axiom F(10) ?P(0, 0, 0)\n"), std::string::npos) << c.program;
  auto pattern = convertText(Dialect::LPy, "a.lpy", "Axiom: ?P A\n?P < A --> B\n");
  EXPECT_EQ(pattern.line, 2);
  EXPECT_EQ(pattern.column, 1);
}

TEST(Untranslated, LPysDerivationLengthIsOneUnlessSaid) {
  auto c = convertText(Dialect::LPy, "a.lpy", "Axiom: A\nA --> A A\n");
  ASSERT_EQ(c.error, "");
  EXPECT_NE(c.program.find("  #until 1\n"), std::string::npos) << c.program;
  auto zero = convertText(Dialect::LPy, "a.lpy", "Axiom: A\nderivation length: 0\nA --> A A\n");
  EXPECT_EQ(zero.line, 2);
  EXPECT_EQ(zero.column, 20);
  EXPECT_TRUE(zero.untranslatable);
  EXPECT_NE(zero.error.find("word --at 0"), std::string::npos) << zero.error;
  // A decomposition rewrites the word too.
  auto decomposed = convertText(Dialect::LPy, "a.lpy", "derivation length: 0\nAxiom: A\ndecomposition:\nA --> B\n");
  EXPECT_EQ(decomposed.line, 1);
  EXPECT_NE(decomposed.error.find("derivation length 0 (the word is the axiom) where productions would rewrite it"),
            std::string::npos)
      << decomposed.error;
  // With no production to rewrite it, every step's word is the axiom L-Py shows: one step.
  auto shown = convertText(Dialect::LPy, "a.lpy",
                           "derivation length: 0\nAxiom: A B\nproduction:\ninterpretation:\nA --> F\nendlsystem\n");
  ASSERT_EQ(shown.error, "");
  EXPECT_NE(shown.program.find("  #until 1\n  axiom A B\n  production:\n  homomorphism:\n  A -> F\n"),
            std::string::npos)
      << shown.program;
}

// Issue 37, defect 6: nesting 10,000 deep is an error at the level past the limit, not
// a stack overflow.
TEST(Untranslated, DeepNestingIsALocatedError) {
  std::string c = "Axiom: A(1)\nA(x) --> A(";
  for (int i = 0; i < 10000; ++i) c += "x?";
  c += "1";
  for (int i = 0; i < 10000; ++i) c += ":2";
  c += ")\n";
  auto cpfg = convertText(Dialect::Cpfg, "a.l", c);
  EXPECT_EQ(cpfg.line, 2);
  EXPECT_EQ(cpfg.column, 13 + 2 * kMaxConvertNesting);  // the first '?' past the limit
  EXPECT_NE(cpfg.error.find("nested too deeply"), std::string::npos) << cpfg.error;
  std::string p = "Axiom: A(1)\nA(x) --> A(";
  for (int i = 0; i < 10000; ++i) p += "1 if x else ";
  p += "2)\n";
  auto lpy = convertText(Dialect::LPy, "a.lpy", p);
  EXPECT_EQ(lpy.line, 2);
  EXPECT_NE(lpy.error.find("nested too deeply"), std::string::npos) << lpy.error;
  std::string alternatives = "Axiom: A\nA > ";
  for (int i = 0; i < 10000; ++i) alternatives += "or(B,";
  alternatives += "C" + std::string(10000, ')') + " --> D\n";
  auto nested = convertText(Dialect::LPy, "a.lpy", alternatives);
  EXPECT_EQ(nested.line, 2);
  EXPECT_NE(nested.error.find("nested too deeply"), std::string::npos) << nested.error;
}

TEST(Untranslated, TheConvertedTextIsHeldToTheSourceLimit) {
  SourceFile file("a.lpy", "Axiom: " + std::string(1000, 'F') + "\n");
  DiagnosticSink sink;
  ConvertResult result = convertFile(file, Dialect::LPy, "", sink, 1500);
  EXPECT_FALSE(result.program);
  ASSERT_EQ(sink.diagnostics().size(), 1u);
  EXPECT_NE(sink.diagnostics()[0].message.find("is larger than the limit of 1.5 KiB"), std::string::npos)
      << sink.diagnostics()[0].message;
}

// A file of a few lines whose C block (cpfg) or Python body (L-Py) multiplies a value ten
// times by four converts to 18.7 MiB: it was built whole before its size was compared
// with the limit (a file of twelve such lines reached 1.2 GB), and now the converter
// stops as its text passes the limit.
std::string quadrupled(Dialect dialect, int times) {
  if (dialect == Dialect::Cpfg) {
    std::string text = "Lsystem: 1\nderivation length: 1\nAxiom: A(1)\nA(x) : {a0=x+x+x+x;";
    for (int i = 1; i <= times; ++i)
      text += " a" + std::to_string(i) + "=a" + std::to_string(i - 1) + "+a" + std::to_string(i - 1) + "+a" +
              std::to_string(i - 1) + "+a" + std::to_string(i - 1) + ";";
    return text + "} 1 --> A(a" + std::to_string(times) + ")\nendlsystem\n";
  }
  std::string text = "Axiom: A(1)\nderivation length: 1\nproduction:\nA(x):\n  a = x+x+x+x\n";
  for (int i = 1; i <= times; ++i) text += "  a = a+a+a+a\n";
  return text + "  produce A(a)\nendlsystem\n";
}

TEST(Untranslated, TheConverterStopsAsSoonAsItsTextPassesTheLimit) {
  for (const Dialect dialect : {Dialect::Cpfg, Dialect::LPy}) {
    SourceFile file(dialect == Dialect::Cpfg ? "a.l" : "a.lpy", quadrupled(dialect, 10));
    DiagnosticSink sink;
    const ConvertResult stopped = convertFile(file, dialect, "", sink, 1 << 20);
    EXPECT_FALSE(stopped.program);
    EXPECT_TRUE(stopped.pastLimit);
    ASSERT_EQ(sink.diagnostics().size(), 1u);
    EXPECT_EQ(sink.diagnostics()[0].message,
              "the converted text is larger than the limit of 1 MiB of source text (the converter stopped where it "
              "passed it)");
    // Under a larger limit the same file converts whole.
    DiagnosticSink roomy;
    const ConvertResult whole = convertFile(file, dialect, "", roomy, 64 << 20);
    ASSERT_TRUE(whole.program) << (roomy.diagnostics().empty() ? "" : roomy.diagnostics()[0].message);
    EXPECT_FALSE(whole.pastLimit);
    size_t xs = 0;
    for (const char c : *whole.program) xs += c == 'x';
    EXPECT_EQ(xs, (size_t{1} << 22) + 2);  // 4^11 in the argument, one in the predecessor, one in "axiom"
  }
}

// Each line of the converted text knows the line of the file it came from.
TEST(Untranslated, TheLinesOfTheConvertedTextKnowTheirOrigin) {
  SourceFile file("a.lpy", "N = 2\nAxiom: A\n\nproduction:\nA :\n  produce B(N)\nB(x) --> B(vlen(x))\n");
  DiagnosticSink sink;
  ConvertResult result = convertFile(file, Dialect::LPy, "", sink);
  ASSERT_TRUE(result.program);
  const SourceFile converted("a.lpy (converted)", *result.program);
  const size_t at = result.program->find("vlen(x)");
  ASSERT_NE(at, std::string::npos);
  Diagnostic d{Severity::Error, SourceSpan{&converted, static_cast<uint32_t>(at), static_cast<uint32_t>(at + 4)},
               "unknown function 'vlen'"};
  Diagnostic mapped = mapToOriginal(d, file, result.lineOrigins);
  EXPECT_EQ(mapped.span.file, &file);
  EXPECT_EQ(mapped.span.line(), 7);
  EXPECT_EQ(mapped.span.column(), 1);
  EXPECT_EQ(mapped.message, "unknown function 'vlen' (in the converted line 'B(x) -> B(vlen(x))', column 11)");
  // A production of a head and a produce body spans both lines.
  const size_t produced = result.program->find("A -> B(N)");
  ASSERT_NE(produced, std::string::npos);
  d.span = SourceSpan{&converted, static_cast<uint32_t>(produced), static_cast<uint32_t>(produced + 1)};
  mapped = mapToOriginal(d, file, result.lineOrigins);
  EXPECT_EQ(mapped.span.line(), 5);
  EXPECT_EQ(formatDiagnostic(mapped).substr(0, 12), "a.lpy:5:1: e");
  const size_t define = result.program->find("#define N 2");
  d.span = SourceSpan{&converted, static_cast<uint32_t>(define), static_cast<uint32_t>(define + 1)};
  EXPECT_EQ(mapToOriginal(d, file, result.lineOrigins).span.line(), 1);
}

// L-Py's hooks: what the block cannot say is refused at its place in the hook, never
// read over: a group kept from the step before, state from step to step, the word,
// values set after each step, and Python the converter does not read.
TEST(Untranslated, LPyHooksThatCarryStateAreRefusedAtTheirPlace) {
  struct Case {
    std::string text;
    int line, column;
    std::string message;
  };
  const std::string rest = "Axiom: A\nproduction:\nA --> B(g)\n";
  for (const Case& k : std::vector<Case>{
           {"def StartEach():\n  if getIterationNb() == 2: useGroup(1)\n", 2, 3,
            "a way through the test that calls no useGroup, keeping the group of the step before"},
           {"g = 1\ndef StartEach():\n  global g\n  g = g * 2\n", 4, 3,
            "'g' set in L-Py's StartEach() from its own value of the step before"},
           {"def StartEach():\n  global g\n  g += getIterationNb()\n", 3, 3,
            "'g' set in L-Py's StartEach() from its own value of the step before"},
           {"def EndEach():\n  global g\n  g = 2\n", 3, 3,
            "'g' set in L-Py's EndEach(), after each step: state carried to the next step"},
           {"def StartEach():\n  seed(3)\n", 2, 3, "a seed set again at each step in L-Py's StartEach()"},
           {"def StartEach():\n  useGroup(getGroup() + 1)\n", 2, 12, "getGroup(), the group of the step before,"},
           {"def EndEach(lstring):\n  global g\n  g = lstring\n", 3, 7, "the word or scene 'lstring' read"},
           {"def End(lstring):\n  for m in lstring: print(m)\n", 2, 3, "'for' in L-Py's End()"},
           {"def StartInterpretation():\n  produce F\n", 2, 3, "'produce' in L-Py's StartInterpretation()"},
       }) {
    auto c = convertText(Dialect::LPy, "a.lpy", k.text + rest);
    EXPECT_EQ(c.program, "") << k.text;
    EXPECT_EQ(c.line, k.line) << k.text << c.error;
    EXPECT_EQ(c.column, k.column) << k.text << c.error;
    EXPECT_TRUE(c.untranslatable) << k.text;
    EXPECT_NE(c.error.find(k.message), std::string::npos) << k.text << c.error;
  }
  // A value of StartEach read by the interpretation, after the last step: refused there.
  auto drawn = convertText(Dialect::LPy, "a.lpy",
                           "def StartEach():\n  global g\n  g = getIterationNb()\nAxiom: A\n"
                           "interpretation:\nA --> F(g)\n");
  EXPECT_EQ(drawn.line, 6);
  EXPECT_NE(drawn.error.find("read in the interpretation"), std::string::npos) << drawn.error;
}

// What the hooks say that the block can: Start's constants replace the file's, a value
// of constants set at each step is a constant, and one of getIterationNb() is written
// where a production reads it (time - 1: a production's time is the step it makes).
TEST(Untranslated, LPyHooksConstantsAndValuesOfTheStep) {
  auto c = convertText(Dialect::LPy, "a.lpy",
                       "g = 1\ndef Start():\n  global g\n  g = 2\n  seed(7)\n"
                       "def StartEach():\n  global h, s\n  h = g + 1\n  s = getIterationNb() * 2\n"
                       "  if s > 2:\n    useGroup(1)\n  else: useGroup(0)\n"
                       "Axiom: A\nproduction:\nA(s) --> B(s, h)\nA --> B(s)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #define g 2\n  #define h g + 1\n  #angle 60\n  #seed 7\n  #until 1\n"
            "  use group: if((time * 2) > 2, 1, 0)\n  axiom A\n  production:\n  A(s) -> B(s, h)\n"
            "  A -> B(((time - 1) * 2))\n");
}

}  // namespace
}  // namespace ontogen::convert
