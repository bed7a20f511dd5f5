// The growth limits from the command line, measured on the process: a model that passes
// a limit stops with exit 3 and the limit named, and its peak resident size (ru_maxrss of
// the child, a memory figure the kernel keeps) stays near the limit.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/apps/ontogen_process.h"

namespace {

namespace fs = std::filesystem;

// AddressSanitizer's shadow memory is part of the resident size: the sanitized build
// checks the exit codes and messages, the plain build the sizes too.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitized = true;
#elif defined(__has_feature)
constexpr bool kAddressSanitized = __has_feature(address_sanitizer);
#else
constexpr bool kAddressSanitized = false;
#endif

using Result = ontogen::test::OntogenRun;

fs::path scratch(const std::string& name) {
  fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "limits_cli_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

fs::path writeProgram(const fs::path& dir, const std::string& text, const std::string& name = "program.cell") {
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path;
}

// Runs ontogen with `args` (no shell), its output in files of `dir`.
Result ontogen(const fs::path& dir, std::vector<std::string> args) {
  return ontogen::test::runOntogen(dir, std::move(args));
}

// Systems nested `depth` levels, each holding two of the next: 2^depth - 1 worlds of a
// cell or two (16 levels: 65,535 worlds, 98,302 cells).
std::string nestedSystems(int depth) {
  std::string text;
  for (int i = 0; i + 1 < depth; ++i)
    text += "system s" + std::to_string(i) + " { pool linear; axiom s" + std::to_string(i + 1) + " s" +
            std::to_string(i + 1) + "; }\n";
  return text + "system s" + std::to_string(depth - 1) + " { pool linear; axiom A; }\ncell A { }\n";
}

// Every pool at every depth counts: the worlds of 65,535 nested systems took 711 MB while
// the limits saw 3 MiB of cells, and the cell limit was checked once all were made.
TEST(LimitsCli, NestedSystemsStopAtTheLimitsAsTheyAreMade) {
  const fs::path dir = scratch("nested");
  const std::string program = writeProgram(dir, nestedSystems(16)).string();
  const Result memory = ontogen(dir, {"run", program, "--format", "none", "--until", "2", "--max-memory", "100"});
  EXPECT_EQ(memory.exitCode, 3) << memory.err;
  EXPECT_NE(memory.err.find("passed 100 MiB, the memory limit; raise it with --max-memory MIB"), std::string::npos)
      << memory.err;
  if (!kAddressSanitized) {
    EXPECT_LT(memory.peakKib, 125u * 1024) << "KiB at the peak";
  }
  const Result cells = ontogen(dir, {"run", program, "--format", "none", "--until", "2", "--max-cells", "1000"});
  EXPECT_EQ(cells.exitCode, 3) << cells.err;
  EXPECT_NE(cells.err.find("grew past 1000 cells in all its systems"), std::string::npos) << cells.err;
  if (!kAddressSanitized) {
    EXPECT_LT(cells.peakKib, 50u * 1024) << "KiB at the peak";
  }
  // Within the limits, --stats counts every world: 10 levels hold 1534 cells of 24 bytes
  // (two system cells in each of 511 worlds, a cell in each of 512) and 1023 worlds of
  // 12 KiB (World::kWorldBytes), 12.02 MiB.
  const std::string smaller = writeProgram(dir, nestedSystems(10), "smaller.cell").string();
  const Result all = ontogen(dir, {"run", smaller, "--format", "none", "--until", "2", "--stats"});
  EXPECT_EQ(all.exitCode, 0) << all.err;
  EXPECT_NE(all.out.find("cells 1534, steps 2,"), std::string::npos) << all.out;
  EXPECT_NE(all.out.find(", held 12.0 MiB,"), std::string::npos) << all.out;
}


// A nested world keeps the word before its last step to write the next one into, and it
// counts: systems whose words double (two of two, a value a cell) peaked at 155 MB under
// --max-memory 100 while only their words counted, and --stats said what the words held.
TEST(LimitsCli, NestedWordsCountTheWordBeforeTheyKeep) {
  const fs::path dir = scratch("previous_word");
  const std::string doubling = "cell A(x = 0) { rules { -> A(x + 1) A(x); } }\n";
  const std::string program = writeProgram(dir, "system top { pool linear; axiom S S; }\n"
                                                "system S { pool linear; axiom T T; }\n"
                                                "system T { pool linear; axiom A; }\n" + doubling)
                                  .string();
  const Result memory = ontogen(dir, {"run", program, "--format", "none", "--until", "40", "--max-memory", "100"});
  EXPECT_EQ(memory.exitCode, 3) << memory.err;
  EXPECT_NE(memory.err.find("ontogen: error: the model's pools passed 100 MiB, the memory limit; raise it with "
                            "--max-memory MIB\n"),
            std::string::npos)
      << memory.err;
  if (!kAddressSanitized) {
    EXPECT_LT(memory.peakKib, 125u * 1024) << "KiB at the peak";
  }
  // After 16 steps the nested pool holds 65,536 cells of 32 bytes and the 32,768 of the
  // word before; the top pool its system cell twice over; and 2 worlds of 12 KiB:
  // 3,170,352 bytes, 3.0 MiB (the words alone: 2.0 MiB).
  const std::string one = writeProgram(dir, "system top { pool linear; axiom S; }\n"
                                            "system S { pool linear; axiom A; }\n" + doubling,
                                       "one.cell")
                              .string();
  const Result stats = ontogen(dir, {"run", one, "--format", "none", "--until", "16", "--stats"});
  EXPECT_EQ(stats.exitCode, 0) << stats.err;
  EXPECT_NE(stats.out.find("cells 65537, steps 16,"), std::string::npos) << stats.out;
  EXPECT_NE(stats.out.find(", held 3.0 MiB,"), std::string::npos) << stats.out;
}

// State that becomes an infinity or NaN stops `word` and `run` with exit 3 at the rate,
// and is printed only when the program allows it.
TEST(LimitsCli, NonFiniteStateStopsAtTheRateUnlessAllowed) {
  const fs::path dir = scratch("nonfinite");
  const std::string body = "cell A(x = 1) {\n  rules { rate(x) = x * x * 100; }\n}\nsystem s { pool linear; axiom A; }\n";
  const std::string program = writeProgram(dir, body).string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"word", program, "--at", "5"},
        std::vector<std::string>{"run", program, "--format", "none", "--until", "5"}}) {
    const Result stopped = ontogen(dir, args);
    EXPECT_EQ(stopped.exitCode, 3) << args[0] << "\n" << stopped.err;
    EXPECT_NE(stopped.err.find(program + ":2:11: error: 'A' holds x = "), std::string::npos) << stopped.err;
    EXPECT_NE(stopped.err.find("at t = 2, written by its rate"), std::string::npos) << stopped.err;
    EXPECT_EQ(stopped.out.find("inf"), std::string::npos) << stopped.out;
    EXPECT_EQ(stopped.out.find("nan"), std::string::npos) << stopped.out;
  }
  const std::string allowed = writeProgram(dir, "#allow nonfinite\n" + body, "allowed.cell").string();
  const Result word = ontogen(dir, {"word", allowed, "--at", "5"});
  EXPECT_EQ(word.exitCode, 0) << word.err;
  EXPECT_EQ(word.out, "t = 5: A(nan)\n");
  const Result overflow = ontogen(dir, {"check", writeProgram(dir, "#define K 1e308*10\n" + body, "k.cell").string()});
  EXPECT_EQ(overflow.exitCode, 1) << overflow.err;
  EXPECT_NE(overflow.err.find("k.cell:1:11: error: the value of #define K overflows to an infinity"), std::string::npos)
      << overflow.err;
}


// A grid far too large stops before its arrays are made, with the limit named: 400 M
// sites took 1.5 GB (its site index alone) before the check, or "the machine ran out of
// memory" where there was less.
TEST(LimitsCli, AGridTooLargeStopsBeforeItIsMade) {
  const fs::path dir = scratch("grid");
  const std::string program =
      writeProgram(dir, "cell U(u = 1) { rules { rate(u) = -u; } }\nsystem g { pool grid(20000, 20000); fill U(1); }\n")
          .string();
  const Result result = ontogen(dir, {"run", program, "--format", "none", "--until", "2", "--max-memory", "100"});
  EXPECT_EQ(result.exitCode, 3) << result.err;
  EXPECT_NE(result.err.find("the grid's 400000000 sites need more than the memory limit of 100 MiB; raise it with "
                            "--max-memory MIB"),
            std::string::npos)
      << result.err;
  if (!kAddressSanitized) {
    EXPECT_LT(result.peakKib, 125u * 1024) << "KiB at the peak";
  }
}

}  // namespace

namespace {

// A word or a colony that grows without end stops near the memory limit, not at twice
// it: arrays copied as they grow, the records a compact word is turned back into, the
// results of the colony's chunks merged into its next word and its spatial index count
// before they are made, and memory freed goes back to the system (at --max-memory 100 the
// parametric word peaked at 184 MB and the colony at 226 MB; still at 140 and 129 MiB
// while the records and the memory glibc kept went uncounted).
TEST(LimitsCli, RunawayGrowthStopsNearTheMemoryLimit) {
  const fs::path dir = scratch("runaway");
  const std::string word =
      writeProgram(dir, "lsystem runaway {\n  axiom A(1)\n  A(x) -> A(x + 1) B(x * 2, x)\n  B(x, y) -> A(x - y)\n}\n",
                   "word.cell")
          .string();
  const std::string colony = writeProgram(dir,
                                          "#until 40\n#dt 1\ncell C(x = 0, y = 0) { rules { -> me C(x + 0.1, y); } }\n"
                                          "system dish { pool spatial(1); axiom C(0, 0); }\n",
                                          "colony.cell")
                                 .string();
  for (const std::string& program : {word, colony}) {
    const Result result = ontogen(dir, {"run", program, "--format", "none", "--until", "60", "--max-memory", "100"});
    EXPECT_EQ(result.exitCode, 3) << program << ": " << result.err;
    EXPECT_NE(result.err.find("the memory limit; raise it with --max-memory MIB"), std::string::npos)
        << program << ": " << result.err;
    // The limit counts the model; the executable, its libraries and the pictures' buffers
    // are the rest (about 12 MB here).
    if (!kAddressSanitized) {
      EXPECT_LT(result.peakKib, 125u * 1024) << program << ": KiB at the peak";
    }
  }
}

// A .l or .lpy of a few lines whose C block or Python body multiplies a value twelve
// times by four converts to 299 MiB: it was built whole (1.2 GB at the peak) and then
// refused by the source limit (exit 1). The converter stops as its text passes what
// checking may take of the memory limit, which names the limit as for a .cell that large.
TEST(LimitsCli, AConvertedFileStopsAtTheMemoryLimitAsItsTextGrows) {
  const fs::path dir = scratch("converted");
  std::string cpfg = "Lsystem: 1\nderivation length: 1\nAxiom: A(1)\nA(x) : {a0=x+x+x+x;";
  std::string lpy = "Axiom: A(1)\nderivation length: 1\nproduction:\nA(x):\n  a = x+x+x+x\n";
  for (int i = 1; i <= 12; ++i) {
    const std::string before = "a" + std::to_string(i - 1);
    cpfg += " a" + std::to_string(i) + "=" + before + "+" + before + "+" + before + "+" + before + ";";
    lpy += "  a = a+a+a+a\n";
  }
  cpfg += "} 1 --> A(a12)\nendlsystem\n";
  lpy += "  produce A(a)\nendlsystem\n";
  for (const std::string& program : {writeProgram(dir, cpfg, "grows.l").string(), writeProgram(dir, lpy, "grows.lpy").string()}) {
    const Result result = ontogen(dir, {"word", program, "--at", "1", "--max-memory", "100"});
    EXPECT_EQ(result.exitCode, 3) << program << ": " << result.err;
    // 100 MiB / 128 bytes of checking a byte of text = 819200 bytes.
    EXPECT_EQ(result.err, "ontogen: error: checking the text converted from '" + program +
                              "' (more than 819200 bytes) needs about 101 MiB, past the memory limit of 100 MiB; "
                              "raise it with --max-memory MIB\n");
    if (!kAddressSanitized) {
      EXPECT_LT(result.peakKib, 40u * 1024) << program << ": KiB at the peak";
    }
  }
}

}  // namespace
