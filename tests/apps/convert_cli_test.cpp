// `ontogen convert` and the commands that read cpfg (.l) and L-Py (.lpy) files by
// converting them first: words compared by value with models written in the cell
// language, and the located errors of code the converter cannot translate.

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/apps/ontogen_process.h"

namespace {

namespace fs = std::filesystem;

using Result = ontogen::test::OntogenRun;

Result ontogen(const std::string& args) { return ontogen::test::runOntogenShell(args); }

std::string file(const std::string& name) {
  return std::string(ONTOGEN_SOURCE_DIR) + "/tests/convert/" + name;
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// ABOP Fig. 1.24 (d) as cpfg and L-Py write it grows to the word of the model written
// in the cell language: after two steps the word as the book's productions give it, and
// after seven (the figure's n) 3^7 apices X and 4118 segments F.
TEST(Convert, Figure124dGrowsAlikeFromCpfgLPyAndTheCellLanguage) {
  Result two = ontogen("word " + file("fig1_24d.cell") + " --at 2");
  ASSERT_EQ(two.exitCode, 0) << two.err;
  EXPECT_EQ(two.out,
            "t = 2: F F [ + F [ + X ] F [ - X ] + X ] F F [ - F [ + X ] F [ - X ] + X ] + F [ + X ] F [ - X ] + X\n");
  Result cell = ontogen("word " + file("fig1_24d.cell") + " --at 7");
  ASSERT_EQ(cell.exitCode, 0) << cell.err;
  EXPECT_EQ(count(cell.out, "X"), 2187u);
  EXPECT_EQ(count(cell.out, "F"), 4118u);
  for (const char* name : {"fig1_24d.l", "fig1_24d.lpy"}) {
    for (const char* at : {"2", "7"}) {
      Result other = ontogen("word " + file(name) + " --at " + at);
      ASSERT_EQ(other.exitCode, 0) << name << "\n" << other.err;
      EXPECT_EQ(other.out, std::string(at) == "2" ? two.out : cell.out) << name;
      EXPECT_EQ(other.err, "") << name;
    }
  }
}

// ABOP Fig. 1.24 (b), edge rewriting, the same way: 5^5 segments after five steps.
TEST(Convert, Figure124bGrowsAlikeFromCpfgLPyAndTheCellLanguage) {
  Result cell = ontogen("word " + file("fig1_24b.cell") + " --at 5");
  ASSERT_EQ(cell.exitCode, 0) << cell.err;
  EXPECT_EQ(count(cell.out, "F"), 3125u);
  for (const char* name : {"fig1_24b.l", "fig1_24b.lpy"}) {
    Result other = ontogen("word " + file(name) + " --at 5");
    ASSERT_EQ(other.exitCode, 0) << name << "\n" << other.err;
    EXPECT_EQ(other.out, cell.out) << name;
    EXPECT_EQ(other.err, "") << name;
  }
}

TEST(Convert, PrintsTheCellLanguageProgram) {
  Result cpfg = ontogen("convert " + file("fig1_24b.l"));
  ASSERT_EQ(cpfg.exitCode, 0) << cpfg.err;
  EXPECT_EQ(cpfg.out,
            "// Converted by ontogen convert from fig1_24b.l (cpfg)\n"
            "lsystem fig1_24b {\n"
            "  #angle 20\n"
            "  #until 5\n"
            "  axiom F\n"
            "  F -> F [ + F ] F [ - F ] [ F ]\n"
            "}\n");
  Result lpy = ontogen("convert " + file("fig1_24b.lpy"));
  ASSERT_EQ(lpy.exitCode, 0) << lpy.err;
  EXPECT_EQ(lpy.out,
            "// Converted by ontogen convert from fig1_24b.lpy (L-Py)\n"
            "lsystem fig1_24b {\n"
            "  #angle 60\n"
            "  #until 5\n"
            "  axiom F\n"
            "  production:\n"
            "  F -> F [ + F ] F [ - F ] [ F ]\n"
            "}\n");
}

// More of ABOP's chapter 1 through both readers, by their expected words, and L-Py's
// new contexts and patterns as its tests state them.
TEST(Convert, AbopChapterOneCasesGrowAsTheBookPrintsThem) {
  struct Case {
    const char* file;
    const char* times;
    const char* words;
  };
  const Case cases[] = {
      {"fig1_5_digits.l", "1,3",
       "t = 1: 1 [ 0 ] 0\n"
       "t = 3: 1 1 1 1 [ 1 1 [ 1 [ 0 ] 0 ] 1 [ 0 ] 0 ] 1 1 [ 1 [ 0 ] 0 ] 1 [ 0 ] 0\n"},
      {"signal.lpy", "1,2,3", "t = 1: a b a a a\nt = 2: a a b a a\nt = 3: a a a b a\n"},
      {"signal.l", "1,2,3", "t = 1: a + b - a a\nt = 2: a + a - b a\nt = 3: a + a - a b\n"},
      {"parametric_1_35.l", "1,2,3,4",
       "t = 1: B(1) B(4) A(1, 0)\nt = 2: B(0) B(3) A(2, 1)\nt = 3: C B(2) A(4, 3)\nt = 4: C B(1) A(8, 7)\n"},
      {"parametric_1_35.lpy", "1,2,3,4",
       "t = 1: B(1) B(4) A(1, 0)\nt = 2: B(0) B(3) A(2, 1)\nt = 3: C B(2) A(4, 3)\nt = 4: C B(1) A(8, 7)\n"},
      {"python_body.lpy", "1,2", "t = 1: A(1)\nt = 2: A(2)\n"},
      {"c_block.l", "1,2", "t = 1: A(2)\nt = 2: A(3)\n"},
      // MAX(a,b) and HALF(x) replaced as C would: A(5), A(3) grow, A(1) fails MAX(1,2) > 2.
      {"c_macro.l", "1,3", "t = 1: B(2.5) A(3)\nt = 3: B(2.5) B(1.5) C(1)\n"},
      // Start: {b = 1 - C; a = b / 2;} as constants: b = 0.5, a = 0.25.
      {"c_start.l", "1,2", "t = 1: B(0.25) A(1.5)\nt = 2: B(0.25) B(0.25) A(2)\n"},
      {"continued.l", "1,2", "t = 1: B [ C ] A\nt = 2: B [ C ] B [ C ] A\n"},
      // k = 3 from a Start: block over three lines; x of each production's own block; C
      // rewritten without a condition ('*'), y = 4.
      {"c_lines.l", "1,2", "t = 1: B(3) A(2) D(4)\nt = 2: B(4) B(6) A(3) D(4)\n"},
      // Python bodies: if/elif/else, nproduce, locals, math, a word over lines, return,
      // and random choices of chance 1 and 0, as L-Py derives them.
      {"python_branches.lpy", "1,2,3",
       "t = 1: A(2) A(2) G(1) B(2) K C(2) D(5) R T S T\n"
       "t = 2: F(3) [ +(3) ] E F(3) [ +(3) ] E G(1) B(1) K K C(4) D(9) R T T S T T\n"
       "t = 3: F(3) [ +(3) ] E F(3) [ +(3) ] E G(1) B(0) K K K C(8) D(9) R T T T S T T T\n"},
      // Python's x % y has the sign of y, x // y floors, -5 < x < 0 chains: the words
      // Python gives (C's fmod would give B(-1, ...) from t = 2 and no C).
      {"python_operators.lpy", "1,4",
       "t = 1: B(2, 1, -2) A(-1)\n"
       "t = 4: B(2, 1, -2) C B(2, -1, -1) C B(2, -2, 0) B(2, -4, -3) A(-10)\n"},
      // Helper functions inlined: alpha(n) = 30 - 10 n, long(n) = 2 - n / 4.
      {"python_functions.lpy", "1,2",
       "t = 1: F(1.75) [ +(20) A(2) ] [ -(20) A(2) ]\n"
       "t = 2: F(1.75) [ +(20) F(1.5) [ +(10) A(3) ] [ -(10) A(3) ] ] [ -(20) F(1.5) [ +(10) A(3) ] [ -(10) A(3) ] ]\n"},
      {"new_contexts.lpy", "1", "t = 1: B A S B A S C(1) B(2) M(1, 2, 3) H(4) E(4) H(11) F(5) G(6) H(0) K\n"},
      // Multiscale modules (L-Py's test_axial_msmatch): a = 1, c = 0, d = 5.
      {"multiscale.lpy", "1", "t = 1: A(1) [ A(2) C(0) ] B(2) M(1, 0, 5) [ A(3) C(0) [ D(1) C(1) ] ] A(5) D(5)\n"},
  };
  for (const Case& c : cases) {
    Result result = ontogen(std::string("word ") + file(c.file) + " --at " + c.times);
    ASSERT_EQ(result.exitCode, 0) << c.file << "\n" << result.err;
    EXPECT_EQ(result.out, c.words) << c.file;
    Result check = ontogen(std::string("check ") + file(c.file));
    EXPECT_EQ(check.exitCode, 0) << c.file << "\n" << check.err;
  }
}

// Code of the other tool is named at its file:line:col, with exit code 6.
TEST(Convert, CodeItCannotTranslateIsAnErrorAtItsPlace) {
  struct Case {
    const char* file;
    const char* where;
    const char* message;
  };
  const Case cases[] = {
      {"python_code.lpy",
       "python_code.lpy:5:5: error: ", "'global' in a helper function: Python which ontogen convert does not translate"},
      {"python_loop.lpy",
       "python_loop.lpy:4:20: error: ", "a range over a value that is no written number: the converter writes out"},
      {"c_code.l", "c_code.l:3:1: error: ", "a C block (Start:, End:, StartEach:, EndEach: or '{ ... }'): C code"},
      {"c_condition.l", "c_condition.l:4:20: error: ", "a statement other than an assignment in a C block: C code"},
  };
  for (const Case& c : cases) {
    for (const char* command : {"convert", "run", "word", "check"}) {
      const std::string args =
          std::string(command) + " " + file(c.file) + (std::string(command) == "word" ? " --at 1" : "");
      Result result = ontogen(args + (std::string(command) == "run"
                                          ? " --out " + std::string(ONTOGEN_BINARY_DIR) + "/convert_cli_test/out"
                                          : ""));
      EXPECT_EQ(result.exitCode, 6) << args << "\n" << result.err;
      EXPECT_EQ(result.out, "") << args;
      EXPECT_NE(result.err.find(std::string(c.where) + c.message), std::string::npos) << args << "\n" << result.err;
    }
  }
}

// Constructs the cell language is gaining convert as text: sections, maximum depth,
// groups, cut, query modules, the empty word.
TEST(Convert, SectionsGroupsCutAndQueriesConvertAsText) {
  Result result = ontogen("convert " + file("sections.lpy"));
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "// Converted by ontogen convert from sections.lpy (L-Py)\n"
            "lsystem sections {\n"
            "  #angle 60\n"
            "  #until 2\n"
            "  axiom A\n"
            "  ignore: +\n"
            "  production:\n"
            "  A -> B [ % C ] ?P(0, 0, 0)\n"
            "  group 1:\n"
            "  B -> ∅\n"
            "  group 0:\n"
            "  decomposition:\n"
            "  maximum depth: 2\n"
            "  B -> F F\n"
            "  homomorphism:\n"
            "  C -> F\n"
            "}\n");
}

// Issue 37, defect 7: a view file that is a FIFO or a link to /dev/zero is refused at
// once (exit 2), neither waited on nor read without end.
TEST(Convert, AViewFileThatIsNoRegularFileIsRefused) {
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "convert_cli_test" / "view";
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy_file(file("fig1_24b.l"), dir / "fifo.l");
  ASSERT_EQ(mkfifo((dir / "fifo.v").c_str(), 0600), 0);
  fs::copy_file(file("fig1_24b.l"), dir / "zero.l");
  fs::create_symlink("/dev/zero", dir / "zero.v");
  for (const char* name : {"fifo", "zero"}) {
    for (const char* command : {"convert", "check"}) {
      Result result = ontogen(std::string(command) + " " + (dir / (std::string(name) + ".l")).string());
      EXPECT_EQ(result.exitCode, 2) << name << " " << command << "\n" << result.err;
      EXPECT_NE(result.err.find("cannot read the view file"), std::string::npos) << result.err;
      EXPECT_NE(result.err.find("it is not a regular file"), std::string::npos) << result.err;
    }
  }
}

// A 10 MB line of a .l reached 866 MB and 36 s in the converter under --max-memory 100
// before the converted text's size refused it: it is refused before it is converted, as
// the same text as a .cell is before it is checked (exit 3, the limit named).
TEST(Convert, AFileTooLargeToCheckWithinTheMemoryLimitIsRefusedBeforeItIsConverted) {
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "convert_cli_test" / "memory";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string text = "Lsystem: 1\nderivation length: 1\nAxiom: " + std::string(10'000'000, 'F') + "\nF --> F\nendlsystem\n";
  for (const char* name : {"big.l", "big.cell"}) {
    const fs::path path = dir / name;
    std::ofstream(path) << text;
    const Result result = ontogen("run " + path.string() + " --max-memory 100 --format none");
    EXPECT_EQ(result.exitCode, 3) << name << "\n" << result.err;
    EXPECT_EQ(result.err, "ontogen: error: checking the 10000059 bytes of '" + path.string() +
                              "' needs about 1221 MiB, past the memory limit of 100 MiB; raise it with --max-memory MIB\n")
        << name;
  }
}

// An error the compiler finds in converted text is shown at the line of the file.
// `if random() < 0.25` in an L-Py body is a choice of chance 0.25: of 400 modules about
// 100 take it (the count is fixed by the seed; 60 to 140 is 4.6 standard deviations).
TEST(Convert, ARandomTestInAPythonBodyChoosesWithItsChance) {
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "convert_cli_test" / "chance";
  fs::create_directories(dir);
  std::string axiom;
  for (int i = 0; i < 400; ++i) axiom += " R";
  std::ofstream(dir / "chance.lpy") << "from random import *\nAxiom:" << axiom
                                    << "\nproduction:\nR :\n  if random() < 0.25: produce X\n  else: produce Y\n";
  Result result = ontogen("word " + (dir / "chance.lpy").string() + " --at 1");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const size_t x = count(result.out, " X"), y = count(result.out, " Y");
  EXPECT_EQ(x + y, 400u) << result.out;
  EXPECT_GE(x, 60u);
  EXPECT_LE(x, 140u);
}

TEST(Convert, ErrorsInTheConvertedTextAreShownAtTheFilesLine) {
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "convert_cli_test" / "mapped";
  fs::create_directories(dir);
  std::ofstream(dir / "mapped.lpy") << "Axiom: A(1)\n\nproduction:\nA(x) --> A(nodelength(x))\n";
  Result result = ontogen("check " + (dir / "mapped.lpy").string());
  EXPECT_EQ(result.exitCode, 1) << result.err;
  EXPECT_NE(result.err.find("mapped.lpy:4:1: error: "), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("(in the converted line 'A(x) -> A(nodelength(x))', column"), std::string::npos)
      << result.err;
  EXPECT_EQ(result.err.find("(converted):"), std::string::npos) << result.err;
}

// What a multiscale block does not match (a wildcard in its context) is refused at the
// file's line, not matched otherwise than L-Py would.
TEST(Convert, AMultiscaleContextItDoesNotMatchIsAnErrorAtTheFilesLine) {
  Result result = ontogen("check " + file("multiscale_wildcard.lpy"));
  EXPECT_EQ(result.exitCode, 1) << result.err;
  EXPECT_NE(result.err.find("multiscale_wildcard.lpy:10:1: error: the wildcard '*' in a multiscale L-system"),
            std::string::npos)
      << result.err;
}

// A converted file never means something else: cpfg's macros are C's textual
// replacement (2*X with X 1+2 is 4, not 6; a macro naming a parameter is its value
// where it is used), its ^ binds looser than a unary minus and from the left, its % is
// the remainder of ints, its angles are degrees. The word is what cpfg computes.
TEST(Convert, CpfgExpressionsMeanWhatCpfgComputes) {
  Result result = ontogen("word " + file("c_textual.l") + " --at 1");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "t = 1: B(4, 3, 4, 6, 5, 6, 7, 0.666667) P(1, 4, 64, 0.5) M(1, -1) T(1, -1, 90, 45, 2)\n");
  // A conditional's text would take the operators around it into its branches.
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "convert_cli_test" / "macro";
  fs::create_directories(dir);
  std::ofstream(dir / "conditional.l") << "#define C x>1?5:7\nLsystem: 1\nAxiom: A(3)\nA(x) --> B(C) B(2*C)\n";
  Result refused = ontogen("convert " + (dir / "conditional.l").string());
  EXPECT_EQ(refused.exitCode, 6) << refused.err;
  EXPECT_NE(refused.err.find("conditional.l:4:19: error: the macro 'C' is replaced as text by C"), std::string::npos)
      << refused.err;
}

// cpfg's blocks around each step: a counter of StartEach: is its step (n = k at step
// k), one of EndEach: the step before (m = 10 - (k - 1)), a value of StartEach: reads
// them as they stand there (p = 2 * m + 1); a production's parameter x is its own
// beside a block that assigns an x. The words as cpfg derives them, step by step.
TEST(Convert, CpfgStepCountersGrowAsCpfgCountsTheSteps) {
  Result result = ontogen("word " + file("c_step_blocks.l") + " --at 1,2,3,4");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "t = 1: B(1, 10, 21) A(1)\n"
            "t = 2: B(1, 10, 21) B(2, 9, 19) A(2)\n"
            "t = 3: B(1, 10, 21) B(2, 9, 19) C(3, 8, 17) D(2)\n"
            "t = 4: B(1, 10, 21) B(2, 9, 19) C(3, 8, 17) E(4)\n");
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "convert_cli_test" / "steps";
  fs::create_directories(dir);
  // The homomorphism reads the word after k steps, each ended by EndEach: n and m are
  // both k there (cpfg interprets after EndEach:), where a production of step k reads m
  // as k - 1.
  std::ofstream(dir / "after.l") << "Lsystem: 1\nderivation length: 2\nStart: {n = 0; m = 0;}\n"
                                    "StartEach: {n = n + 1;}\nEndEach: {m = m + 1;}\nAxiom: A\nA --> A\n"
                                    "homomorphism\nA --> B(n)C(m)\n";
  Result after = ontogen("word --interpreted " + (dir / "after.l").string() + " --at 0,1,2");
  ASSERT_EQ(after.exitCode, 0) << after.err;
  EXPECT_EQ(after.out, "t = 0: B(0) C(0)\nt = 1: B(1) C(1)\nt = 2: B(2) C(2)\n");
  // A value of StartEach: that EndEach: sets too is refused there.
  std::ofstream(dir / "end.l") << "Lsystem: 1\nStartEach: {s = 0;}\nEndEach: {s = 1;}\nAxiom: A\n"
                                  "homomorphism\nA --> C(s)\n";
  Result end = ontogen("convert " + (dir / "end.l").string());
  EXPECT_EQ(end.exitCode, 6) << end.err;
  EXPECT_NE(end.err.find("end.l:6:9: error: the variable 's', which cpfg's EndEach: block changes"),
            std::string::npos)
      << end.err;
}

// rot(x) of c_macro_text.l between + and *: phi = 2 + 3 * 1 * 0.5 * 4 / 0.5 = 14 in
// the homomorphism of the axiom, which derivation length 0 leaves as it is.
TEST(Convert, ACpfgMacroReplacedAsTextAndTheAxiomAlone) {
  Result result = ontogen("word --interpreted " + file("c_macro_text.l") + " --at 0,1");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, "t = 0: F(14)\nt = 1: F(14)\n");
  Result word = ontogen("word " + file("c_macro_text.l") + " --at 1");
  EXPECT_EQ(word.out, "t = 1: C(1, 2)\n");
}

// cpfg's @Tx and @Ts stay modules (Texture, SetElasticity) that contexts read as cpfg
// does; '=]' lets A's context [B=]C match the branch [+BD] (+ ignored, D skipped), the
// ignore: list's digit 0 names no module; func(1, 0.5) is the view file's function's
// middle sample, 3 (cpfg_vocabulary.func: a Bézier segment whose y(0.5) is 3). The words
// as cpfg derives them.
TEST(Convert, CpfgModulesContextsAndFunctionsGrowAsCpfgDerivesThem) {
  Result result = ontogen("word " + file("cpfg_vocabulary.l") + " --at 1,2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "t = 1: Texture(2) SetElasticity(1, 0) A(0.5) [ + B D ] C F(3)\n"
            "t = 2: Texture(2) SetElasticity(1, 0) SetElasticity(1, 0.5) A(1) [ + B D D ] C F(3) F(3)\n");
  EXPECT_EQ(count(result.err, ": warning: "), 2u) << result.err;
}

// L-Py's hooks: Start's globals are constants (n = 3, not the file's 1); StartEach
// chooses group 1 at steps 0 and 3 (getIterationNb() % 3 == 0), else group 2, counts k
// from Start's 10 by 2 before each step and sets half = getIterationNb() // 2; B gets
// an E at step 2; End only checks. The words are L-Py's: k is 12 at step 0, 18 at step 3.
TEST(Convert, LPyHooksChooseGroupsAndSetValuesAsLPyRunsThem) {
  Result result = ontogen("word " + file("lpy_hooks.lpy") + " --at 1,2,3,4");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "t = 1: A B(3, 12)\n"
            "t = 2: A C(14, 0) B(3, 12)\n"
            "t = 3: A C(16, 1) C(14, 0) B(3, 12) E\n"
            "t = 4: A B(3, 18) C(16, 1) C(14, 0) B(3, 12) E\n");
  Result converted = ontogen("convert " + file("lpy_hooks.lpy"));
  ASSERT_EQ(converted.exitCode, 0) << converted.err;
  EXPECT_NE(converted.out.find("  use group: if(fmod(fmod(time, 3) + 3, 3) == 0, 1, 2)\n"), std::string::npos)
      << converted.out;
}

// cpfg's Define: arrays: color[n + 1.7] reads element 1 at n = 0 (C casts the index to
// int), len[2] is 0 (an initialiser's missing elements). A Define: statement other than
// an array of constants, and an index that draws, are refused at their place.
TEST(Convert, CpfgDefineArraysAreReadAsCIndexesThem) {
  Result result = ontogen("word " + file("c_define.l") + " --at 1,2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "t = 1: B(1, 0.85, 3) A(1)\n"
            "t = 2: B(1, 0.85, 3) B(3, 0, 2) A(2)\n");
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "convert_cli_test" / "define";
  fs::create_directories(dir);
  std::ofstream(dir / "int.l") << "Lsystem: 1\nDefine: { array c[2] = {1, 2}; int k; }\nAxiom: A\nA --> B(c[1])\n";
  Result other = ontogen("convert " + (dir / "int.l").string());
  EXPECT_EQ(other.exitCode, 6) << other.err;
  EXPECT_NE(other.err.find("int.l:2:32: error: a statement of a Define: block other than an array of constants"),
            std::string::npos)
      << other.err;
  std::ofstream(dir / "drawn.l") << "Lsystem: 1\nDefine: { array c[2] = {1, 2}; }\nAxiom: A\nA --> B(c[ran(2)])\n";
  Result drawn = ontogen("convert " + (dir / "drawn.l").string());
  EXPECT_EQ(drawn.exitCode, 6) << drawn.err;
  EXPECT_NE(drawn.err.find("drawn.l:4:11: error: an index that draws a random number"), std::string::npos)
      << drawn.err;
}

// L-Py's list of constants read by index (color[-1] from the end), `MAX_AGE, dr = 3, 0.5`
// and a helper function of ifs, a local and returns: the words Python derives (t % 3
// picks 1, 3, 2; -1 - t % 2 picks 2, 3; size(t) is t * 0.5 below 3, else 1.5).
TEST(Convert, LPyListsTuplesAndFunctionsOfSeveralLinesMeanWhatPythonComputes) {
  Result result = ontogen("word " + file("python_lists.lpy") + " --at 2,4");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "t = 2: B(1, 2, 0) B(3, 3, 0.5) A(2)\n"
            "t = 4: B(1, 2, 0) B(3, 3, 0.5) B(2, 2, 1) B(1, 3, 1.5) A(4)\n");
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "convert_cli_test" / "lists";
  fs::create_directories(dir);
  std::ofstream(dir / "swap.lpy") << "a = 1\nb = 2\na, b = b, a\nAxiom: A(a)\n";
  Result swap = ontogen("convert " + (dir / "swap.lpy").string());
  EXPECT_EQ(swap.exitCode, 6) << swap.err;
  EXPECT_NE(swap.err.find("swap.lpy:3:8: error: a value naming 'b', which this line sets"), std::string::npos)
      << swap.err;
}

// L-Py's `for i in range(...)` over written numbers in a production body, written out
// turn by turn: the words L-Py derives (i is 0, 1, 2 and B is drawn at i == 1; j counts
// down 4, 2; i is 2 after its loop). A loop over a parameter is refused at its range.
TEST(Convert, LPyLoopsOverRangesOfNumbersAreWrittenOutTurnByTurn) {
  Result result = ontogen("word " + file("python_range.lpy") + " --at 1,2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "t = 1: F(2) F(3) [ + B(2) ] F(4) C(4) C(2) A(4)\n"
            "t = 2: F(2) F(3) [ + B(2) ] F(4) C(4) C(2) F(4) F(5) [ + B(4) ] F(6) C(4) C(2) A(6)\n");
}

// A name Python finds first is the one read: a production's parameter, a helper
// function's parameter and a local of a body hide L-Py's list of the same name, and each
// holds a number in the cell language, of which an element cannot be read: a located
// error, never the list's element. Where no parameter hides it, the list is read.
TEST(Convert, LPyParametersAndLocalsHideAListOfTheSameName) {
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "convert_cli_test" / "hidden";
  fs::create_directories(dir);
  const std::string list = "pts = [5, 7]\nAxiom: P(1)\nderivation length: 1\nproduction:\n";
  std::ofstream(dir / "global.lpy") << list << "P(x) --> F(pts[x])\n";
  Result global = ontogen("word " + (dir / "global.lpy").string() + " --at 1");
  ASSERT_EQ(global.exitCode, 0) << global.err;
  EXPECT_EQ(global.out, "t = 1: F(7)\n");
  const struct {
    const char* name;
    const char* text;
    const char* where;
  } hidden[] = {
      {"parameter.lpy", "P(pts) --> F(pts[0])\n", "parameter.lpy:5:14: error: "},
      {"body.lpy", "P(pts) :\n  produce F(pts[1])\n", "body.lpy:6:13: error: "},
      {"local.lpy", "P(x) :\n  pts = x * 2\n  produce F(pts[1])\n", "local.lpy:7:13: error: "},
      {"function.lpy", "def first(pts): return pts[0]\nP(x) --> F(first(x))\n", "function.lpy:5:24: error: "},
  };
  for (const auto& h : hidden) {
    std::ofstream(dir / h.name) << list << h.text;
    Result result = ontogen("word " + (dir / h.name).string() + " --at 1");
    EXPECT_EQ(result.exitCode, 6) << h.name << "\n" << result.out << result.err;
    EXPECT_NE(result.err.find(std::string(h.where) + "an element of 'pts', which here is a parameter or local"),
              std::string::npos)
        << result.err;
  }
}

// A cpfg name that is a cell's internal state (a parameter `age`, a macro `time`) is
// the file's own, not the cell's age or the clock: A(5) steps down by 2. nran(3, 0) is
// cpfg's normal draw (deviation 0: 3); a macro that draws is drawn anew at each use, as
// C puts its text there: C's two parameters differ.
TEST(Convert, CpfgNamesOfTheCellsStateAreTheFilesOwn) {
  Result result = ontogen("word " + file("c_names.l") + " --at 2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  ASSERT_EQ(result.out.rfind("t = 2: A(1) B(3) C(", 0), 0u) << result.out;
  double a = -1, b = -1;
  ASSERT_EQ(std::sscanf(result.out.c_str(), "t = 2: A(1) B(3) C(%lf, %lf)", &a, &b), 2) << result.out;
  EXPECT_NE(a, b);
  for (double x : {a, b}) {
    EXPECT_GE(x, 0.0);
    EXPECT_LT(x, 1.0);
  }
}

// Python 3's round takes halves to the even neighbour, as L-Py computes it; a file of
// Python 2 has its round (halves away from zero) and its '/', which floors between
// integers: refused at its place unless a float stands beside it.
TEST(Convert, LPyRoundAndDivisionMeanWhatPythonComputes) {
  Result result = ontogen("word " + file("python_round.lpy") + " --at 1");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, "t = 1: B(2, 4, -2, 3, 0, 4, 8)\n");  // python3 -c 'print(round(2.5), ...)'
  Result python2 = ontogen("convert " + file("python2_division.lpy"));
  EXPECT_EQ(python2.exitCode, 6) << python2.err;
  EXPECT_NE(python2.err.find("python2_division.lpy:7:52: error: '/' in a file of Python 2 (line 6)"),
            std::string::npos)
      << python2.err;
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "convert_cli_test" / "python2";
  fs::create_directories(dir);
  std::ofstream(dir / "floats.lpy") << "Axiom: A(5)\nproduction:\nA(x) :\n  print x\n"
                                       "  produce B(x * 1.0 / 2, x // 2, round(x / 2.0))\n";
  Result floats = ontogen("word " + (dir / "floats.lpy").string() + " --at 1");
  ASSERT_EQ(floats.exitCode, 0) << floats.err;
  EXPECT_EQ(floats.out, "t = 1: B(2.5, 2, 3)\n");  // Python 2's round(2.5) is 3.0
  std::ofstream(dir / "future.lpy") << "from __future__ import division\nAxiom: A(5)\nproduction:\nA(x) :\n"
                                       "  print x\n  produce B(x / 2)\n";
  Result future = ontogen("word " + (dir / "future.lpy").string() + " --at 1");
  ASSERT_EQ(future.exitCode, 0) << future.err;
  EXPECT_EQ(future.out, "t = 1: B(2.5)\n");
}

// L-Py's top-level imports, `global`, `assert` and backward() change no word: the file
// grows as L-Py derives it right to left, each B reading its new right neighbour
// (B(0) B(0) B(0) -> B(2) B(1) B(0) -> B(5) B(2) B(0)), with a warning at the assert.
TEST(Convert, LPyTopLevelStatementsThatChangeNoWordAreReadOver) {
  Result result = ontogen("word " + file("lpy_top_level.lpy") + " --at 1,2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, "t = 1: B(2) B(1) B(0)\nt = 2: B(5) B(2) B(0)\n");
  EXPECT_NE(result.err.find("lpy_top_level.lpy:11:1: warning: 'assert' at L-Py's top level is not checked"),
            std::string::npos)
      << result.err;
}

// L-Py's functional axiom (a Python body under `Axiom:`) is the word its one way
// produces, C F(0) f F(2) f F(4) f A(2, 2); the axiom, the file's constants and the
// derivation length (2) read n as the file gives it (1), the productions as Start sets it
// (3): A(2, 2) -> A(5, 2) -> A(8, 2). The production body's assert is a warning.
TEST(Convert, LPyFunctionalAxiomAndLoadTimeValuesAreWhatLPyComputes) {
  Result result = ontogen("word " + file("lpy_axiom.lpy") + " --at 0,1,2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out,
            "t = 0: C F(0) f F(2) f F(4) f A(2, 2)\n"
            "t = 1: C F(0) f F(2) f F(4) f A(5, 2)\n"
            "t = 2: C F(0) f F(2) f F(4) f A(8, 2)\n");
  EXPECT_NE(result.err.find("lpy_axiom.lpy:22:3: warning: 'assert' in a production body is not checked"),
            std::string::npos)
      << result.err;
  Result converted = ontogen("convert " + file("lpy_axiom.lpy"));
  EXPECT_NE(converted.out.find("#until (1) + 1\n"), std::string::npos) << converted.out;
  // L-Py's own test of a functional axiom asserts a word of 20 modules after its step.
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "convert_cli_test" / "axiom";
  fs::create_directories(dir);
  std::ofstream(dir / "functional.lpy") << "Axiom:\n  for i in range(10):\n    nproduce F f\n\nderivation length: 1\n"
                                           "production:\ninterpretation:\nendlsystem\n";
  Result twenty = ontogen("word " + (dir / "functional.lpy").string() + " --at 1");
  ASSERT_EQ(twenty.exitCode, 0) << twenty.err;
  EXPECT_EQ(count(twenty.out, " F") + count(twenty.out, " f"), 20u) << twenty.out;
  EXPECT_EQ(count(twenty.out, "F f"), 10u) << twenty.out;
}

// `derivation length: 0` in a file of no productions: L-Py shows the axiom, and so is
// the word at the step the converted block makes.
TEST(Convert, LPyDerivationLengthZeroWithoutProductionsIsTheAxiom) {
  const fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "convert_cli_test" / "zero";
  fs::create_directories(dir);
  std::ofstream(dir / "shown.lpy")
      << "derivation length: 0\nAxiom: -(30)F(1)-(120)F(1)\ninterpretation:\nF(x) --> F(2 * x)\n";
  Result result = ontogen("word " + (dir / "shown.lpy").string() + " --at 1");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(result.out, "t = 1: -(30) F(1) -(120) F(1)\n");
}

TEST(Convert, OnlyReadsOtherToolsFiles) {
  Result result = ontogen("convert " + file("fig1_24d.cell"));
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_NE(result.err.find("convert reads cpfg files (.l) and L-Py files (.lpy)"), std::string::npos) << result.err;
}

TEST(Convert, HelpListsTheCommand) {
  Result result = ontogen("help");
  ASSERT_EQ(result.exitCode, 0);
  EXPECT_NE(result.out.find("ontogen convert FILE.l|FILE.lpy"), std::string::npos);
  EXPECT_NE(result.out.find("#letters"), std::string::npos);
}

}  // namespace
