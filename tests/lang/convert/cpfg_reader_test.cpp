// cpfg's .l files read into cell-language text (lang/convert/cpfg_reader.cpp).

#include "lang/convert/cpfg_reader.h"

#include <gtest/gtest.h>

#include "tests/lang/convert/convert_test_support.h"

namespace ontogen::convert {
namespace {

using test::convertText;

std::string body(const std::string& program) {
  // The lines of the block, without the comment and the braces.
  const size_t open = program.find("{\n"), close = program.rfind("}");
  return program.substr(open + 2, close - open - 2);
}

TEST(CpfgReader, ModulesAreOneCharacterEachAndParametersStayOnTheirModule) {
  auto c = convertText(Dialect::Cpfg, "a.l", "Lsystem: 1\nderivation length: 3\nAxiom: F(1)+AB(2,x*3)\nendlsystem\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  #until 3\n  axiom F(1) + A B(2, x * 3)\n");
}

TEST(CpfgReader, ProductionsKeepContextsConditionsProbabilitiesAndTheEmptyWord) {
  auto c = convertText(Dialect::Cpfg, "a.l",
                       "Lsystem: 1\nSeed: 7\n#define K 2\nAxiom: A\n"
                       "B < A(x) > C : x < K && x != 1 --> A(x+1)C : 0.5\n"
                       "A(x) : * --> *\nendlsystem\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #define K 2\n  #seed 7\n  axiom A\n"
            "  B < A(x) > C : x < K && x != 1 -> A(x + 1) C : 0.5\n"
            "  A(x) -> ∅\n");
}

TEST(CpfgReader, IgnoreConsiderSectionsAndTheViewFilesAngle) {
  auto c = convertText(Dialect::Cpfg, "a.l",
                       "/* a comment\n over lines */\nLsystem: 1\n#ignore +-\nconsider: AB\nAxiom: A\nA --> B\n"
                       "homomorphism no warnings\nmaximum depth: 3\nB --> F\nendlsystem\n",
                       "angle factor: 18\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #angle 360 / 18\n  axiom A\n  ignore: + -\n  consider: A B\n  A -> B\n  homomorphism:\n"
            "  maximum depth: 3\n  B -> F\n");
}

// cpfg reads its turn angle from the view file: the last of its angle lines, else its
// default of 45 degrees. Without a view file the angle is unknown: the first line that
// turns by it warns.
TEST(CpfgReader, TheViewFilesLastAngleElseCpfgsDefaultElseAWarning) {
  const std::string text = "Lsystem: 1\nAxiom: A\nA --> F(1)\nA --> F+F\nendlsystem\n";
  auto last = convertText(Dialect::Cpfg, "a.l", text, "angle increment: 30\nangle factor: 8\n");
  EXPECT_NE(last.program.find("  #angle 360 / 8\n"), std::string::npos) << last.program;
  EXPECT_TRUE(last.warnings.empty());
  auto none = convertText(Dialect::Cpfg, "a.l", text, "viewpoint: 0,0,1\n");
  EXPECT_NE(none.program.find("  #angle 45\n"), std::string::npos) << none.program;
  EXPECT_TRUE(none.warnings.empty());
  auto missing = convertText(Dialect::Cpfg, "tree.l", text);
  EXPECT_EQ(missing.program.find("#angle"), std::string::npos) << missing.program;
  ASSERT_EQ(missing.warnings.size(), 1u);
  EXPECT_EQ(missing.warnings[0].rfind("4:1: no view file (neither one that a cpfg command in the folder's "
                                      "'specifications' names with this file, nor 'tree.v' beside it)", 0),
            0u)
      << missing.warnings[0];
  EXPECT_NE(missing.warnings[0].find("ontogen's default of 90 degrees"), std::string::npos);
  // Turns given their angle need none.
  auto given = convertText(Dialect::Cpfg, "tree.l", "Axiom: A\nA --> F+(30)F|\n");
  EXPECT_TRUE(given.warnings.empty());
}

TEST(CpfgReader, ConditionalsBecomeIf) {
  auto c = convertText(Dialect::Cpfg, "a.l", "Axiom: A(1)\nA(x) --> A(x > 1 ? 1 : x < 0 ? 2 : 3)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  axiom A(1)\n  A(x) -> A(if(x > 1, 1, if(x < 0, 2, 3)))\n");
}

TEST(CpfgReader, DigitModulesGiveTheBlockLetters) {
  auto c = convertText(Dialect::Cpfg, "fig 1.5.l", "Axiom: 0\n0 --> 1[0]0\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(c.program,
            "// Converted by ontogen convert from fig 1.5.l (cpfg)\nlsystem fig_1_5 {\n  #letters\n  axiom 0\n"
            "  0 -> 1 [ 0 ] 0\n}\n");
}

TEST(CpfgReader, CCodeAndUnspellableModulesAreErrorsAtTheirPlace) {
  auto block = convertText(Dialect::Cpfg, "a.l", "Axiom: A\nEnd: { print(); }\n");
  EXPECT_EQ(block.line, 2);
  EXPECT_EQ(block.column, 1);
  EXPECT_TRUE(block.untranslatable);
  EXPECT_NE(block.error.find("C code"), std::string::npos) << block.error;

  auto assignment = convertText(Dialect::Cpfg, "a.l", "Axiom: A(1)\nA(x) --> A(x = 2)\n");
  EXPECT_EQ(assignment.line, 2);
  EXPECT_EQ(assignment.column, 14);
  EXPECT_NE(assignment.error.find("an assignment: C code"), std::string::npos) << assignment.error;

  auto quote = convertText(Dialect::Cpfg, "a.l", "Axiom: F'(2)F\n");
  EXPECT_EQ(quote.line, 1);
  EXPECT_EQ(quote.column, 9);
  EXPECT_NE(quote.error.find("the module ''' of cpfg has no cell-language spelling"), std::string::npos) << quote.error;

  // C replaces a macro as text: SQ(a+1) is a+1*a+1 there, which the converter will not
  // read as (a+1)*(a+1); nor 2*HALF(x) as 2*(x/2) where C reads 2*x/2 the same only by luck.
  auto argument = convertText(Dialect::Cpfg, "a.l", "#define SQ(x) x*x\nAxiom: A(SQ(1+2))\n");
  EXPECT_EQ(argument.line, 2);
  EXPECT_EQ(argument.column, 13);
  EXPECT_NE(argument.error.find("this argument, which is no single operand, would join the operators around 'x'"),
            std::string::npos)
      << argument.error;
  auto value = convertText(Dialect::Cpfg, "a.l", "#define D(x) x-1\nAxiom: A(2*D(3))\n");
  EXPECT_EQ(value.line, 2);
  EXPECT_EQ(value.column, 12);
  EXPECT_NE(value.error.find("its value, which is no single operand, would join the operators around this call"),
            std::string::npos)
      << value.error;

  auto pattern = convertText(Dialect::Cpfg, "a.l", "Axiom: A(3)\nA(x+1) --> B\n");
  EXPECT_EQ(pattern.line, 2);
  EXPECT_EQ(pattern.column, 3);
  EXPECT_NE(pattern.error.find("a pattern's parameter 'x+1' is neither a name nor a number"), std::string::npos)
      << pattern.error;

  auto unreadable = convertText(Dialect::Cpfg, "a.l", "Axiom: A\nthis is not cpfg\n");
  EXPECT_EQ(unreadable.line, 2);
  EXPECT_FALSE(unreadable.untranslatable);
}

// Value patterns, A(3) and B(-1.5), are the cell language's own.
TEST(CpfgReader, ValuePatternsAreTranslated) {
  auto c = convertText(Dialect::Cpfg, "a.l", "Axiom: A(3)B(-1.5)\nA(3) < B(-1.5) --> C\n");
  ASSERT_EQ(c.error, "");
  EXPECT_NE(c.program.find("  A(3) < B(-1.5) -> C\n"), std::string::npos) << c.program;
}

}  // namespace
}  // namespace ontogen::convert

namespace ontogen::convert {
namespace {

// cpfg's reader takes a line break followed by a tab as a space, and the C
// preprocessor it reads through removes `//` comments.
TEST(CpfgReader, TabbedLinesContinueAStatementAndSlashCommentsAreRemoved) {
  auto c = convertText(Dialect::Cpfg, "a.l",
                       "Lsystem: 1\nAxiom: A\nA --> B // a comment\n\tC\n\t[D]\nB --> E\n  \nendlsystem\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  axiom A\n  A -> B C [ D ]\n  B -> E\n");
}

// cpfg's generalized cylinders: @Gs starts one (gcbegin), @Ge ends it; its control
// points, tangents and 3D circle stay modules of a name, with a warning.
TEST(CpfgReader, GeneralizedCylinderModules) {
  auto c = convertText(Dialect::Cpfg, "a.l", "Lsystem: 1\nAxiom: @GsF@Gc(3)@Gt(1,2)@Gr(1)@Ge(4)@c(2)\nendlsystem\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  axiom gcbegin F ContinueSpline(3) SplineTangents(1, 2) RadiusTangents(1) gcend(4) Circle3D(2)\n");
  ASSERT_EQ(c.warnings.size(), 4u);
  EXPECT_EQ(c.warnings[0].substr(0, 5), "2:12:");
  // L-Py knows @Gc as StartGC, and not @Gs: it reads the modules @, G and s.
  auto lpy = convertText(Dialect::LPy, "a.lpy", "Axiom: @Gc F @Gs\n");
  ASSERT_EQ(lpy.error, "");
  EXPECT_NE(lpy.program.find("axiom gcbegin F @ G s\n"), std::string::npos) << lpy.program;
  ASSERT_EQ(lpy.warnings.size(), 1u);
  EXPECT_EQ(lpy.warnings[0].rfind("1:14: L-Py predefines no module '@Gs'", 0), 0u) << lpy.warnings[0];
}

TEST(CpfgReader, AMaximumDepthAboveTheLimitIsTheLimitWithAWarning) {
  auto c = convertText(Dialect::Cpfg, "a.l",
                       "Lsystem: 1\nAxiom: A\nhomomorphism\nmaximum depth: 1000\nA --> B\nendlsystem\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  axiom A\n  homomorphism:\n  maximum depth: 256\n  A -> B\n");
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0],
            "4:16: maximum depth 1000 is above ontogen's limit of 256: the block rewrites at most 256 deep, which "
            "differs only where the rules recurse deeper");
  auto within = convertText(Dialect::Cpfg, "a.l", "Lsystem: 1\nAxiom: A\nhomomorphism\nmaximum depth: 256\nendlsystem\n");
  EXPECT_TRUE(within.warnings.empty());
}

}  // namespace
}  // namespace ontogen::convert

namespace ontogen::convert {
namespace {

// cpfg's blocks of assignments before and after a condition are put in where they are
// read; a variable that other statements read holds state between productions, refused.
TEST(CpfgReader, AssignmentBlocksAroundAConditionAreSubstituted) {
  auto c = convertText(Dialect::Cpfg, "a.l",
                       "Lsystem: 1\n#define PL 1\nAxiom: A(3)\nA(t) : {t=t-PL;} t>0 {u=t*2;} --> I(u)A(t)\n"
                       "M(t) : 1 {x=0.5*t;} --> F(x)\nN : {x=2;} 1 --> F(x)\nendlsystem\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  #define PL 1\n  axiom A(3)\n  A(t) : (t - PL) > 0 -> I(((t - PL) * 2)) A((t - PL))\n"
            "  M(t) : 1 -> F((0.5 * t))\n  N : 1 -> F((2))\n");
  auto global = convertText(Dialect::Cpfg, "a.l",
                            "Lsystem: 1\nAxiom: A\nA : {x=1;} 1 --> B\nB --> C(x)\nendlsystem\n");
  EXPECT_EQ(global.line, 3);
  EXPECT_EQ(global.column, 6);
  EXPECT_NE(global.error.find("the variable 'x', which other statements of the file read"), std::string::npos)
      << global.error;
  auto code = convertText(Dialect::Cpfg, "a.l", "Lsystem: 1\nAxiom: A\nA : {printf(1);} 1 --> B\nendlsystem\n");
  EXPECT_EQ(code.line, 3);
  EXPECT_EQ(code.column, 6);
  EXPECT_NE(code.error.find("a statement other than an assignment in a C block"), std::string::npos) << code.error;
}

// A compound statement inside a block, `{{ y = 1; }}`, holds assignments as the block
// does; an `if` with its own block is a statement other than an assignment, refused at
// the `if`; a '{' that no '}' closes is refused at the '{'.
TEST(CpfgReader, BlocksWithinABlockAreItsStatements) {
  auto c = convertText(Dialect::Cpfg, "a.l",
                       "Lsystem: 1\nAxiom: A(3)\nA(x) : {{ y = x + 1; { z = y * 2; } }} y > 1 --> B(y, z)\n"
                       "endlsystem\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  axiom A(3)\n  A(x) : (x + 1) > 1 -> B((x + 1), ((x + 1) * 2))\n");
  auto test = convertText(Dialect::Cpfg, "a.l",
                          "Lsystem: 1\nAxiom: A(3)\nA(x) : { if (x > 0) { y = 1; } } 1 --> B(y)\nendlsystem\n");
  EXPECT_EQ(test.line, 3);
  EXPECT_EQ(test.column, 10);
  EXPECT_NE(test.error.find("a statement other than an assignment in a C block"), std::string::npos) << test.error;
  auto open = convertText(Dialect::Cpfg, "a.l", "Lsystem: 1\nAxiom: A(3)\nA(x) : {{ y = 1; } 1 --> B(y)\nendlsystem\n");
  EXPECT_EQ(open.line, 3);
  EXPECT_EQ(open.column, 8);
  EXPECT_NE(open.error.find("a C block '{' without its '}'"), std::string::npos) << open.error;
}

}  // namespace
}  // namespace ontogen::convert

namespace ontogen::convert {
namespace {

// C over several lines: a Start: block read to the line that closes its brace, and a
// variable that two productions set in their own blocks, read on their successors'
// continued lines (a line break and a tab), is each production's own.
TEST(CpfgReader, CBlocksAndStatementsOverSeveralLines) {
  auto c = convertText(Dialect::Cpfg, "a.l",
                       "Lsystem: 1\nStart: {k =\n\t3;\n}\nAxiom: A(1)\nA(t) : 1 {x = t * k;} -->\n\tB(x) A(t + 1)\n"
                       "B(t) : t < 5 {x = t + 1;} -->\n\tB(x)\nendlsystem\n");
  ASSERT_EQ(c.error, "") << c.line << ":" << c.column;
  EXPECT_EQ(body(c.program),
            "  #define k 3\n  axiom A(1)\n  A(t) : 1 -> B((t * k)) A(t + 1)\n  B(t) : t < 5 -> B((t + 1))\n");
  // cpfg's '*' before a block is no condition, as it is alone.
  auto star = convertText(Dialect::Cpfg, "a.l", "Lsystem: 1\nAxiom: C(2)\nC(a) : * {y = a * 2;} --> D(y)\nendlsystem\n");
  ASSERT_EQ(star.error, "");
  EXPECT_EQ(body(star.program), "  axiom C(2)\n  C(a) -> D((a * 2))\n");
  // A brace of a polygon that a successor opens and another closes joins no lines.
  auto polygon = convertText(Dialect::Cpfg, "a.l", "Lsystem: 1\nAxiom: A\nA --> {.B\nB --> .}\nendlsystem\n");
  ASSERT_EQ(polygon.error, "");
  EXPECT_NE(polygon.program.find("  B -> PP EP\n"), std::string::npos) << polygon.program;
}

// A predecessor of several modules (cpfg rewrites them together where they stand side by
// side) has no exact counterpart: refused at its place as cpfg's construct (exit 6).
TEST(CpfgReader, APredecessorOfSeveralModulesIsRefusedAsCpfgs) {
  auto c = convertText(Dialect::Cpfg, "a.l", "Lsystem: 0\nAxiom: XF(1)\nXF(x) --> F(x/3)+F(x/3)\nendlsystem\n");
  EXPECT_EQ(c.program, "");
  EXPECT_TRUE(c.untranslatable);
  EXPECT_EQ(c.line, 3);
  EXPECT_EQ(c.column, 1);
  EXPECT_EQ(c.error.rfind("cpfg's predecessor of 2 modules (XF(x)): the cell language rewrites one module", 0), 0u)
      << c.error;
}

// cpfg's macros with parameters, inlined where C's textual replacement reads the same:
// parameters that stand alone or in parentheses, values that are one operand, calls
// alone between delimiters, single-operand arguments.
TEST(CpfgReader, MacrosWithParametersAreInlined) {
  auto c = convertText(Dialect::Cpfg, "a.l",
                       "#define MAX(a,b) (((a)>(b))?(a):(b))\n#define SQ(x) x*x\n#define W(x) 0.5*pow(x,2)\n"
                       "Lsystem: 1\nAxiom: A(1)\nA(n) : MAX(n, 2) > 1 --> A(SQ(n), MAX(n+1,3)) B(W(n/2))\nendlsystem\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program),
            "  axiom A(1)\n"
            "  A(n) : ((if(((n) > (2)), (n), (2)))) > 1 -> A((n * n), ((if((((n + 1)) > (3)), ((n + 1)), (3))))) "
            "B((0.5 * pow((n / 2), 2)))\n");
}

}  // namespace
}  // namespace ontogen::convert

namespace ontogen::convert {
namespace {

// A Start: block of constants is #defines and the seed; a variable that a step block
// changes otherwise than by a constant step is state between steps, and the blocks stay
// C code.
TEST(CpfgReader, AStartBlockOfConstants) {
  auto c = convertText(Dialect::Cpfg, "a.l", "Start: {b = 1 - C; a = b/2; srand(SEED);}\nAxiom: A(a)\n");
  ASSERT_EQ(c.error, "");
  EXPECT_EQ(body(c.program), "  #define b 1 - C\n  #define a b / 2\n  #seed SEED\n  axiom A(a)\n");
  auto state = convertText(Dialect::Cpfg, "a.l", "Axiom: A\nStart: {n = 0;}\nEndEach: {n = n * 2;}\n");
  EXPECT_EQ(state.line, 2);
  EXPECT_EQ(state.column, 1);
  EXPECT_TRUE(state.untranslatable);
  EXPECT_NE(state.error.find("a C block (Start:"), std::string::npos) << state.error;
  // The message says why the blocks stay C code.
  EXPECT_NE(state.error.find("(the variable 'n', which EndEach: changes otherwise than by a constant step)"),
            std::string::npos)
      << state.error;
  auto call = convertText(Dialect::Cpfg, "a.l", "Axiom: A\nStart: {n = 0; fclose(fp);}\n");
  EXPECT_EQ(call.line, 2);
  EXPECT_NE(call.error.find("a C block (Start:"), std::string::npos) << call.error;
  EXPECT_NE(call.error.find("(the statement 'fclose(fp)', which is no assignment, printf or srand)"),
            std::string::npos)
      << call.error;
  auto shared = convertText(Dialect::Cpfg, "a.l", "Start: {c = 0;}\nAxiom: A\nA : 1 {c = c + 1;} --> A\n");
  EXPECT_NE(shared.error.find("(the variable 'c', which a production's block assigns too"), std::string::npos)
      << shared.error;
}

}  // namespace
}  // namespace ontogen::convert

namespace ontogen::convert {
namespace {

// Macros whose values name macros twice double at each level, as C's replacement does:
// 20 levels would write about 6 MiB, 64 levels 2^64 copies. They count against the same
// bound as helper functions, a located error, read in linear time.
TEST(CpfgReader, MacrosThatMultiplyAreBounded) {
  std::string text = "#define M0 x\n";
  for (int k = 1; k <= 20; ++k)
    text += "#define M" + std::to_string(k) + " M" + std::to_string(k - 1) + "+M" + std::to_string(k - 1) + "\n";
  auto c = convertText(Dialect::Cpfg, "a.l", text + "Lsystem: 1\nAxiom: A(1)\nA(x) --> A(M20)\nendlsystem\n");
  EXPECT_EQ(c.program, "");
  EXPECT_EQ(c.line, 13);  // the second M11 in M12's value, where the written text passes 4 MiB
  EXPECT_EQ(c.column, 17);
  EXPECT_EQ(c.error, "the calls of helper functions or macros write more than 4 MiB (calls within calls multiply)");
}

// Among modules too: an axiom of M24 whose macros each name the one below twice would be
// 2^24 modules (it ran for minutes and past 7 GB before the bound).
TEST(CpfgReader, MacrosOfModulesThatMultiplyAreBounded) {
  std::string text = "#define M0 F\n";
  for (int k = 1; k <= 24; ++k)
    text += "#define M" + std::to_string(k) + " M" + std::to_string(k - 1) + " M" + std::to_string(k - 1) + "\n";
  auto c = convertText(Dialect::Cpfg, "a.l", text + "Lsystem: 1\nAxiom: M24\nF --> F\nendlsystem\n");
  EXPECT_EQ(c.program, "");
  EXPECT_GE(c.line, 2);  // at a macro's use within another's value, where the bound passes
  EXPECT_LE(c.line, 27);
  EXPECT_EQ(c.error, "the calls of helper functions or macros write more than 4 MiB (calls within calls multiply)");
}

}  // namespace
}  // namespace ontogen::convert
