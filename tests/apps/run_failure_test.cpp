// The ontogen executable when a run goes wrong: every way it can end has a message and
// its exit code (never std::terminate), limits stop what would run for ever or take the
// machine's memory, and a run stopped by a signal leaves no temporary file behind.

#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/apps/ontogen_process.h"

namespace {

namespace fs = std::filesystem;

using Result = ontogen::test::OntogenRun;

fs::path scratch(const std::string& name) {
  fs::path dir = fs::path(ONTOGEN_BINARY_DIR) / "run_failure_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs `ontogen ARGS` through the shell, after `prefix` (e.g. a ulimit).
Result ontogen(const fs::path& dir, const std::string& args, const std::string& prefix = "") {
  return ontogen::test::runOntogenShell(args, prefix, dir);
}

// AddressSanitizer reserves terabytes of shadow address space at start-up and ends the
// process on a failed allocation instead of throwing std::bad_alloc, so an address-space
// limit cannot be put on a sanitized ontogen. The plain build runs these checks in the same
// test command; the sanitized build bounds the runaway cases by time instead.
// GCC says so with __SANITIZE_ADDRESS__, clang with __has_feature(address_sanitizer).
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAddressSanitized = true;
#elif defined(__has_feature)
constexpr bool kAddressSanitized = __has_feature(address_sanitizer);
#else
constexpr bool kAddressSanitized = false;
#endif

std::string addressSpaceLimit(int kib) {
  return kAddressSanitized ? std::string("timeout 60 ") : "ulimit -v " + std::to_string(kib) + "; ";
}

fs::path writeProgram(const fs::path& dir, const std::string& text, const std::string& name = "program.cell") {
  fs::path path = dir / name;
  std::ofstream(path) << text;
  return path;
}

TEST(RunFailure, ADivisionWithinOneStepStopsAtTheLimitsAsCellsAreMade) {
  const fs::path dir = scratch("burst");
  const fs::path program =
      writeProgram(dir, "cell A { lifetime 1e-9; rules { terminal: -> A A; } }\nsystem s { pool linear; axiom A; }\n");
  const Result result = ontogen(dir, "run " + program.string() + " --max-cells 1000 --max-memory 100 --out " +
                                         (dir / "out").string(),
                                addressSpaceLimit(1000000));
  EXPECT_EQ(result.exitCode, 3) << result.err;
  EXPECT_NE(result.err.find("the model grew past 1000 cells, the cell limit; raise it with --max-cells N"),
            std::string::npos)
      << result.err;
}

TEST(RunFailure, EndlessRunsStopWithTheStepLimitNamed) {
  const fs::path dir = scratch("endless");
  const fs::path plain = writeProgram(dir, "lsystem a {\n  axiom A\n  A -> A\n}\n");
  const fs::path until = writeProgram(dir, "#until 1e308\nlsystem a {\n  axiom A\n  A -> A\n}\n", "until.cell");
  const fs::path dt = writeProgram(dir, "#dt 1e-320\nlsystem a {\n  axiom A\n  A -> A\n}\n", "dt.cell");
  const std::string out = " --out " + (dir / "out").string();
  for (const std::string& args : {"run " + until.string() + out, "run " + dt.string() + out,
                                  "run " + plain.string() + " --step 1e-12" + out,
                                  "word " + plain.string() + " --at 5 --step 1e-12"}) {
    const Result result = ontogen(dir, args, "timeout 60 ");
    EXPECT_EQ(result.exitCode, 3) << args << "\n" << result.err;
    EXPECT_NE(result.err.find("past the step limit of 100000000; use a larger --step, or raise it with --max-steps N"),
              std::string::npos)
        << args << "\n" << result.err;
  }
  const Result raised = ontogen(dir, "run " + plain.string() + " --step 1e-6 --max-steps 20000000" + out, "timeout 60 ");
  EXPECT_EQ(raised.exitCode, 0) << raised.err;
}

// The machine's memory is a limit too: an allocation that fails is a message and exit 3,
// not std::terminate, in the run and before it (while the program is checked).
TEST(RunFailure, RunningOutOfMemoryIsAMessageAndExitCode3) {
  if (kAddressSanitized) GTEST_SKIP() << "needs std::bad_alloc, which AddressSanitizer never throws; the plain build runs it";
  const fs::path dir = scratch("memory");
  const fs::path program =
      writeProgram(dir, "cell A { lifetime 1e-9; rules { terminal: -> A A; } }\nsystem s { pool linear; axiom A; }\n");
  const Result run = ontogen(dir,
                             "run " + program.string() +
                                 " --max-memory 100000 --max-cells 10000000000 --max-events 100000000000 --out " +
                                 (dir / "out").string(),
                             "ulimit -v 600000; ");
  EXPECT_EQ(run.exitCode, 3) << run.err;
  EXPECT_NE(run.err.find("the machine ran out of memory; lower the limits with --max-memory MIB or --max-cells N"),
            std::string::npos)
      << run.err;
  EXPECT_EQ(run.err.find("terminate"), std::string::npos) << run.err;

  std::string axiom;
  for (int i = 0; i < 1'000'000; ++i) axiom += " F(1)";
  const fs::path large = writeProgram(dir, "lsystem a {\n axiom" + axiom + "\n F(x) -> F(x)\n}\n", "large.cell");
  // The address-space limit bounds the default memory limit (half of it, 146 MiB), so a
  // program too large to check under it is stopped with the limit named, before the
  // machine's memory runs out.
  const Result check = ontogen(dir, "check " + large.string(), "ulimit -v 300000; ");
  EXPECT_EQ(check.exitCode, 3) << check.err;
  EXPECT_NE(check.err.find("past the memory limit of 146 MiB"), std::string::npos) << check.err;
  const Result help = ontogen(dir, "run --help", "ulimit -v 300000; ");
  EXPECT_NE(help.out.find(", here 146)"), std::string::npos) << help.out;
}

// Checking a program takes about 100 bytes a byte of text: a text that could not be
// checked within the memory limit is stopped before, with the limit named.
TEST(RunFailure, AProgramTooLargeToCheckWithinTheMemoryLimitIsStopped) {
  const fs::path dir = scratch("source");
  std::string axiom;
  for (int i = 0; i < 250'000; ++i) axiom += " F(1)";
  const fs::path large = writeProgram(dir, "lsystem a {\n axiom" + axiom + "\n F(x) -> F(x)\n}\n");
  const Result result = ontogen(dir, "run " + large.string() + " --max-memory 100 --out " + (dir / "out").string());
  EXPECT_EQ(result.exitCode, 3) << result.err;
  EXPECT_NE(result.err.find("checking the 1250035 bytes of '" + large.string() +
                            "' needs about 153 MiB, past the memory limit of 100 MiB"),
            std::string::npos)
      << result.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
  EXPECT_EQ(ontogen(dir, "run " + large.string() + " --max-memory 400 --format obj --out " + (dir / "out").string())
                .exitCode,
            0);
}

// The temporaries of the outputs being written when SIGINT or SIGTERM arrives.
std::vector<fs::path> temporaries(const fs::path& dir) {
  std::vector<fs::path> found;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(dir, error))
    if (entry.path().filename().string().find(".tmp") != std::string::npos) found.push_back(entry.path());
  return found;
}

TEST(RunFailure, ASignalWhileWritingLeavesNoTemporaryFile) {
  for (int signal : {SIGTERM, SIGINT}) {
    const fs::path dir = scratch("signal_" + std::to_string(signal));
    // 8192 spheres: an OBJ of about 40 MB, written for a good part of a second.
    const fs::path program = writeProgram(
        dir, "lsystem big {\n  axiom A\n  A -> A A\n  interpret geometry A { F(1) + sphere(0.3) }\n}\n");
    const fs::path out = dir / "out";
    fs::create_directories(out);
    std::vector<std::string> args = {"run", program.string(), "--until", "13", "--format", "obj",
                                      "--out", out.string()};
    const pid_t pid = ontogen::test::startOntogen(args);
    ASSERT_GT(pid, 0);
    // Waits for the temporary to appear, then signals mid-write.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    bool writing = false;
    while (!writing && std::chrono::steady_clock::now() < deadline) {
      writing = !temporaries(out).empty();
      if (!writing) std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    ASSERT_TRUE(writing) << "the run never wrote a temporary";
    kill(pid, signal);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal)
        << "the process ends as the signal would have ended it, status " << status;
    EXPECT_TRUE(temporaries(out).empty()) << temporaries(out).front();
    EXPECT_FALSE(fs::exists(out / "big.obj")) << "nothing half-written either";
  }
}

// The folder of frames an .mp4 is encoded from goes with the run's other temporaries.
TEST(RunFailure, ASignalWhileDrawingMp4FramesLeavesNoFrameFolder) {
  for (int signal : {SIGTERM, SIGINT}) {
    const fs::path dir = scratch("mp4_signal_" + std::to_string(signal));
    // 50,000 frames: the run is still drawing them when signalled.
    const fs::path program = writeProgram(
        dir, "#until 100000\nlsystem movie {\n  axiom A\n  A -> A\n  interpret geometry A { F(1) }\n}\n", "movie.cell");
    const fs::path out = dir / "out";
    fs::create_directories(out);
    std::vector<std::string> args = {"run", program.string(), "--format", "mp4",
                                      "--size", "64x64", "--frames", "50000", "--out", out.string()};
    const pid_t pid = ontogen::test::startOntogen(args);
    ASSERT_GT(pid, 0);
    const fs::path frames = out / ".movie.mp4-frames";
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    bool drawing = false;
    while (!drawing && std::chrono::steady_clock::now() < deadline) {
      std::error_code error;
      drawing = fs::exists(frames / "frame_000010.png", error);
      if (!drawing) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    ASSERT_TRUE(drawing) << "the run never drew ten frames";
    kill(pid, signal);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal)
        << "the process ends as the signal would have ended it, status " << status;
    EXPECT_FALSE(fs::exists(frames)) << "the frames' folder is left behind";
    EXPECT_TRUE(temporaries(out).empty()) << temporaries(out).front();
  }
}

}  // namespace

namespace {

// Values an instruction cannot take are the model's errors (exit 3) at the instruction,
// not outputs that could not be written (exit 4).
TEST(RunFailure, InstructionValuesOutOfRangeExitWith3AndTheirPlace) {
  const fs::path dir = scratch("instructions");
  const fs::path pixel =
      writeProgram(dir, "cell C { interpret image { pixel(-5, -5, 1) } }\nsystem g { pool grid(4, 4) wrap moore; fill C; }\n",
                   "pixel.cell");
  const Result painted = ontogen(dir, "run " + pixel.string() + " --interpret image --out " + (dir / "out").string());
  EXPECT_EQ(painted.exitCode, 3) << painted.err;
  EXPECT_NE(painted.err.find("pixel.cell:1:28: error: pixel(-5, -5) is outside the picture"), std::string::npos)
      << painted.err;
  const fs::path note =
      writeProgram(dir, "lsystem m {\n  axiom A\n  interpret music A { note(1e308, 60) }\n  A -> A\n}\n", "note.cell");
  const Result played = ontogen(dir, "run " + note.string() + " --interpret music --out " + (dir / "out").string());
  EXPECT_EQ(played.exitCode, 3) << played.err;
  EXPECT_NE(played.err.find("note.cell:3:23: error: the note would end at beat 1e+308"), std::string::npos)
      << played.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "note.mid"));
}

}  // namespace
