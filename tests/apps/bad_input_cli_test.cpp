// The executable facing bad input: numeric flags, program files that are no files,
// floods of errors, text that is no UTF-8, unknown commands. Every case ends in a short
// message and a documented exit code, never an abort or a hang.

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "tests/apps/cli_support.h"

namespace ontogen::test {
namespace {

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

struct BadFlag {
  std::string args;     ///< after the command's FILE
  std::string message;  ///< the one line it must print
};

TEST(BadInput, EveryNumericFlagRejectsWhatIsNotItsNumberWithOneShortLine) {
  const std::string piston = modelPath("piston.cell");
  const std::vector<std::pair<std::string, BadFlag>> cases = {
      {"run", {"--step nan", "--step: 'nan' is not a number > 0"}},
      {"run", {"--step 0", "--step: '0' is not a number > 0"}},
      {"run", {"--step 1e999", "--step: '1e999' is not a number > 0"}},
      {"word", {"--at nan", "--at: 'nan' is not a number ≥ 0"}},
      {"statics", {"--at nan", "--at: 'nan' is not a number ≥ 0"}},
      {"statics", {"--at inf", "--at: 'inf' is not a number ≥ 0"}},
      {"word", {"--at 1,inf", "--at: 'inf' is not a number ≥ 0"}},
      {"word", {"--at -1", "--at: '-1' is not a number ≥ 0"}},
      {"word", {"--at 1,,2", "--at: '1,,2' has an empty item: write the values with one comma between each"}},
      {"word", {"--at=1,", "--at: '1,' has an empty item: write the values with one comma between each"}},
      {"run", {"--format ,obj", "--format: ',obj' has an empty item: write the values with one comma between each"}},
      {"run", {"--until nan", "--until: 'nan' is not a number ≥ 0"}},
      {"timeline", {"--out x.svg --until -2", "--until: '-2' is not a number ≥ 0"}},
      {"run", {"--view nan,nan", "--view: 'nan' is not a number -360 to 360"}},
      {"run", {"--view 10,95", "--view: '95' is not a number -90 to 90"}},
      {"run", {"--seed -5", "--seed: '-5' is not a whole number ≥ 0"}},
      {"run", {"--seed 18446744073709551616", "--seed: '18446744073709551616' is not a whole number ≥ 0"}},
      {"run", {"--max-cells -1", "--max-cells: '-1' is not a whole number ≥ 1"}},
      {"run", {"--max-cells 1.5", "--max-cells: '1.5' is not a whole number ≥ 1"}},
      {"run", {"--max-events 0", "--max-events: '0' is not a whole number ≥ 1"}},
      {"run", {"--max-memory 17592186044416", "--max-memory: '17592186044416' is not a whole number 1 to 17592186044415"}},
      {"run", {"--threads -1", "--threads: '-1' is not a whole number 0 to 4096"}},
      {"run", {"--frames 0", "--frames: '0' is not a whole number 1 to 1000000"}},
      {"run", {"--size 800x800junk", "--size: '800x800junk' is not WIDTHxHEIGHT in pixels, each 1 to 8192, as in 800x600"}},
      {"run", {"--look neon", "--look: 'neon' is no look (known: light, dark, paper)"}},
      {"run", {"--fps 0", "--fps: '0' is not a number 1 to 240"}},
      {"run", {"--speed 0", "--speed: '0' is not a number > 0"}},
      {"run", {"--frames 3 --speed 1", "--frames and --speed both say how many frames the run has; give one"}},
      {"run", {"--up x", "--up: 'x' is no up axis: y (ontogen's own) or z (Blender, most PLY viewers)"}},
      {"run", {"--size 0x10", "--size: '0x10' is not WIDTHxHEIGHT in pixels, each 1 to 8192, as in 800x600"}},
      {"word", {"--at 1 --precision 18", "--precision: '18' is not a whole number 1 to 17"}},
      {"timeline", {"--out x.svg --max-rows 0", "--max-rows: '0' is not a whole number 1 to 10000000"}},
      {"check", {"--max-errors many", "--max-errors: 'many' is not a whole number 0 to 1000000"}},
      {"check", {"--max-source 0", "--max-source: '0' is not a whole number 1 to 4095"}},
      {"run", {"--interpret= --stats", "--interpret= has no value: write --interpret=VALUE or --interpret VALUE"}},
  };
  for (const auto& [command, bad] : cases) {
    CliResult result = runOntogen(command + " " + piston + " " + bad.args);
    EXPECT_EQ(result.exitCode, 2) << command << " " << bad.args << "\n" << result.err;
    EXPECT_EQ(result.err.substr(0, result.err.find('\n')), "ontogen: error: " + bad.message) << bad.args;
    EXPECT_LT(result.err.size(), 200u) << bad.args;
  }
}

// A value in range but far past what a run can do is refused at once, in a message of a
// few significant digits: never hundreds of digits, an "inf", or hours of stepping first.
TEST(BadInput, HugeValuesAreRefusedAtOnceInAFewDigits) {
  const std::string piston = modelPath("piston.cell");
  const fs::path svg = scratchDir("huge_values") / "t.svg";
  const std::vector<std::pair<std::string, int>> cases = {
      {"statics " + piston + " --at 1e300", 3},
      {"statics " + piston + " --at 1e308 --json", 3},
      {"word " + piston + " --at 1e300", 3},
      {"run " + piston + " --until 1e300 --format none", 3},
      {"run " + piston + " --step 1e-300 --until 1 --format none", 3},
      {"run " + piston + " --speed 1e-300 --format none", 2},
      {"timeline " + piston + " --out " + svg.string() + " --until 1e9", 3},
  };
  for (const auto& [args, exitCode] : cases) {
    CliResult result = runOntogen(args, 20);
    EXPECT_EQ(result.exitCode, exitCode) << args << "\n" << result.err;
    // (after the line end that closes a progress line, where the error reaches main)
    EXPECT_LE(result.err.find("ontogen: error: "), 1u) << args << "\n" << result.err;
    EXPECT_LT(result.err.size(), 250u) << args << "\n" << result.err;
    size_t run = 0, longest = 0;
    for (char c : result.err) longest = std::max(longest, run = std::isdigit(static_cast<unsigned char>(c)) ? run + 1 : 0);
    EXPECT_LE(longest, 9u) << args << "\n" << result.err;
    for (const char* nonFinite : {"inf", "nan"}) EXPECT_EQ(result.err.find(nonFinite), std::string::npos) << result.err;
  }
  EXPECT_FALSE(fs::exists(svg));
}

TEST(BadInput, FlagsTakeTheEdgesOfTheirRanges) {
  CliResult result = runOntogen("word " + modelPath("piston.cell") +
                                " --at 0,+1.04 --max-memory 17592186044415 --seed 18446744073709551615 --max-cells 1000");
  EXPECT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(count(result.out, "t = "), 2u);
}

TEST(BadInput, AFloodOfErrorsStopsAtTheLimitAndEachLineIsClipped) {
  fs::path dir = scratchDir("flood");
  fs::path flood = writeFile(dir / "flood.cell", std::string(100000, '?'));
  CliResult result = runOntogen("check " + flood.string());
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(count(result.err, ": error: unexpected character '?'"), 20u);
  EXPECT_NE(result.err.find("20 errors in " + flood.string() +
                            "; stopped at the error limit (--max-errors N changes it, 0 reports every error)"),
            std::string::npos);
  EXPECT_LT(result.err.size(), 20u * 300u);  // each echo is a window of 80 columns, not the 100,000
  EXPECT_EQ(count(runOntogen("check " + flood.string() + " --max-errors 3").err, ": error: "), 3u);
  fs::path fifty = writeFile(dir / "fifty.cell", std::string(50, '?'));
  EXPECT_EQ(count(runOntogen("check " + fifty.string() + " --max-errors 0").err, ": error: "), 50u);
}

TEST(BadInput, AProgramFileMustBeARegularFile) {
  fs::path dir = scratchDir("not_regular");
  const fs::path fifo = dir / "fifo.cell";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& path : {std::string("/dev/zero"), std::string("/dev/urandom"), fifo.string()}) {
    CliResult result = runOntogen("check " + path, 20);
    EXPECT_EQ(result.exitCode, 2) << path << "\n" << result.err;
    EXPECT_EQ(result.err, "ontogen: error: cannot read '" + path +
                              "': it is not a regular file (a device, a FIFO or a socket); a program is read from a file\n");
  }
}

TEST(BadInput, AnImportMustBeARegularFileAndIsReportedWhereItIsWritten) {
  fs::path dir = scratchDir("import_not_regular");
  const fs::path fifo = dir / "fifo.cell";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  fs::create_directories(dir / "folder.cell");
  for (const std::string& import : {std::string("/dev/zero"), std::string("/dev/urandom"), fifo.string(),
                                    (dir / "folder.cell").string()}) {
    fs::path program = writeFile(dir / "program.cell", "import \"" + import + "\";\nlsystem a { axiom A }\n");
    CliResult result = runOntogen("check " + program.string(), 20);
    EXPECT_EQ(result.exitCode, 1) << import << "\n" << result.err;
    EXPECT_EQ(result.err.rfind(program.string() + ":1:1: error: cannot import '" + import + "': it is ", 0), 0u)
        << result.err;
  }
}

TEST(BadInput, SourceTextHasASizeLimitForTheFileAndItsImportsTogether) {
  fs::path dir = scratchDir("source_limit");
  const std::string comment = "// " + std::string(700 * 1024, 'x') + "\n";
  fs::path big = writeFile(dir / "big.cell", comment + comment + "lsystem a { axiom A }\n");
  CliResult tooBig = runOntogen("check " + big.string() + " --max-source 1");
  EXPECT_EQ(tooBig.exitCode, 2);
  EXPECT_EQ(tooBig.err, "ontogen: error: cannot read '" + big.string() +
                            "': it is larger than the limit of 1 MiB of source text (1.4 MiB)\n");
  EXPECT_EQ(runOntogen("check " + big.string() + " --max-source 2").exitCode, 0);
  // 700 KiB here and 700 KiB imported: each fits, together they do not.
  writeFile(dir / "lib.cell", comment);
  fs::path importer = writeFile(dir / "importer.cell", comment + "import \"lib.cell\";\nlsystem a { axiom A }\n");
  CliResult together = runOntogen("check " + importer.string() + " --max-source 1");
  EXPECT_EQ(together.exitCode, 1) << together.err;
  EXPECT_NE(together.err.find(importer.string() + ":2:1: error: cannot import 'lib.cell': it is larger than the limit"),
            std::string::npos)
      << together.err.substr(0, 300);
}

TEST(BadInput, InvalidUtf8IsAnErrorAtItsByteAndAByteOrderMarkIsSkipped) {
  fs::path dir = scratchDir("utf8");
  fs::path bad = writeFile(dir / "bad.cell", "lsystem a {\n  axiom A\n  A -> B\xFF\n}\n");
  CliResult result = runOntogen("word " + bad.string() + " --at 1 --json");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(result.out, "");
  EXPECT_EQ(result.err.rfind(bad.string() + ":3:9: error: invalid UTF-8: byte 0xFF starts no character", 0), 0u)
      << result.err;
  EXPECT_NE(result.err.find("  A -> B?\n"), std::string::npos);  // echoed without the raw byte
  fs::path bom = writeFile(dir / "bom.cell", "\xEF\xBB\xBFlsystem a {\n  axiom A\n  A -> B\n}\n");
  CliResult withBom = runOntogen("word " + bom.string() + " --at 1");
  EXPECT_EQ(withBom.exitCode, 0) << withBom.err;
  EXPECT_EQ(withBom.out, "t = 1: B\n");
}

TEST(BadInput, AnUnknownCommandSuggestsTheNearestOne) {
  CliResult result = runOntogen("chek x.cell");
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.err, "ontogen: error: unknown command 'chek'; did you mean 'check'? "
                        "(commands: check, run, word, statics, timeline, sweep, evolve, studio, midi-ports, convert, help)\n");
  EXPECT_NE(runOntogen("timelin").err.find("did you mean 'timeline'?"), std::string::npos);
  // Nothing near: no suggestion.
  EXPECT_EQ(runOntogen("frobnicate").err, "ontogen: error: unknown command 'frobnicate' "
                                          "(commands: check, run, word, statics, timeline, sweep, evolve, studio, midi-ports, convert, help)\n");
}

TEST(BadInput, AnUnknownFlagSuggestsTheNearestFlagOfItsCommand) {
  CliResult result = runOntogen("run " + modelPath("piston.cell") + " --stpe 1");
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.err, "ontogen: error: unknown flag '--stpe' for 'run'; did you mean '--step'? "
                        "(ontogen run --help lists them)\n");
  EXPECT_EQ(runOntogen("word " + modelPath("piston.cell") + " --at 1 --jsn").err,
            "ontogen: error: unknown flag '--jsn' for 'word'; did you mean '--json'? (ontogen word --help lists them)\n");
  EXPECT_EQ(runOntogen("check " + modelPath("piston.cell") + " --frobnicate").err,
            "ontogen: error: unknown flag '--frobnicate' for 'check' (ontogen check --help lists them)\n");
}

TEST(BadInput, VersionComesFromTheProject) {
  CliResult result = runOntogen("--version");
  EXPECT_EQ(result.exitCode, 0);
  EXPECT_EQ(result.out, "ontogen " ONTOGEN_VERSION "\n");
}

TEST(BadInput, HelpKeepsEverySignatureApartFromItsDocAndListsEveryCommand) {
  CliResult result = runOntogen("help");
  ASSERT_EQ(result.exitCode, 0);
  for (const char* glued : {"disc(inner, outer)draw", "tropism(x, y, z, e)before", "obstaclesphere(x, y, z, r)environment",
                            "[--json] print"})
    EXPECT_EQ(result.out.find(glued), std::string::npos) << glued;
  EXPECT_NE(result.out.find("  disc(inner, outer)    draw an annulus"), std::string::npos);
  EXPECT_NE(result.out.find("  obstaclebox(x0, y0, z0, x1, y1, z1)\n                        environment:"),
            std::string::npos);
  for (const char* command : {"check", "run", "word", "statics", "timeline", "midi-ports", "convert", "help", "--version"})
    EXPECT_NE(result.out.find(std::string("  ontogen ") + command), std::string::npos) << command;
}

}  // namespace
}  // namespace ontogen::test
