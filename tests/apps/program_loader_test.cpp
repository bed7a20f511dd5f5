// Reading a program for the commands (apps/program_loader.h over lang/program_file.h): a
// file of another tool is held to the source and memory limits before it is converted, as
// a cell-language file is before it is checked, and the studio reads through the same
// limits.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "apps/program_loader.h"
#include "tests/test_files.h"

namespace ontogen::app {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) { return test::scratchDir(name, "program_loader_test"); }

using test::writeFile;

WorldLimits memoryLimit(uint64_t mebibytes) {
  WorldLimits limits;
  limits.maxMemoryBytes = mebibytes << 20;
  return limits;
}

// A cpfg file whose axiom is one line of `letters` F.
std::string cpfgWithAxiomOf(size_t letters) {
  return "Lsystem: 1\nderivation length: 1\nAxiom: " + std::string(letters, 'F') + "\nF --> F\nendlsystem\n";
}

// A 10 MB line of a .l went through the converter (866 MB and 36 s) before the converted
// text's size refused it; the same text as a .cell was refused at once.
TEST(ProgramLoader, AFileOfAnotherToolIsHeldToTheMemoryLimitBeforeItIsConverted) {
  const fs::path dir = scratch("memory");
  const std::string text = cpfgWithAxiomOf(10'000'000);
  const std::string expected = "checking the " + std::to_string(text.size()) + " bytes of '";
  for (const char* name : {"big.l", "big.lpy", "big.cell"}) {
    const fs::path path = writeFile(dir / name, text);
    const ProgramText read = readProgramText(path.string(), kDefaultMaxSourceBytes, memoryLimit(100));
    EXPECT_FALSE(read.text) << name;
    EXPECT_EQ(read.exitCode, kExitModelError) << name;
    EXPECT_EQ(read.error, expected + path.string() + "' needs about 1221 MiB, past the memory limit of 100 MiB; "
                                                     "raise it with --max-memory MIB")
        << name;
  }
  // Within the limit it is converted as ever.
  const fs::path small = writeFile(dir / "small.l", cpfgWithAxiomOf(1000));
  const ProgramText read = readProgramText(small.string(), kDefaultMaxSourceBytes, memoryLimit(100));
  ASSERT_TRUE(read.text) << read.error;
  EXPECT_TRUE(read.converted);
  EXPECT_NE(read.text->find("axiom F F F"), std::string::npos);
}

// A cpfg file's view file counts with it: toward the source size limit and toward the
// memory that checking them takes.
TEST(ProgramLoader, AViewFileCountsWithItsFile) {
  const fs::path dir = scratch("view");
  const fs::path path = writeFile(dir / "tree.l", cpfgWithAxiomOf(600'000));
  writeFile(dir / "tree.v", "angle increment: 20\n" + std::string(600'000, ' ') + "\n");
  const uint64_t both = fs::file_size(path) + fs::file_size(dir / "tree.v");
  const ProgramText sized = readProgramText(path.string(), 1 << 20, memoryLimit(1000));
  EXPECT_FALSE(sized.text);
  EXPECT_EQ(sized.exitCode, kExitUsage);
  EXPECT_NE(sized.error.find("cannot read the view file '" + (dir / "tree.v").string() +
                             "': it is larger than the limit of "),
            std::string::npos)
      << sized.error;
  const ProgramText memory = readProgramText(path.string(), kDefaultMaxSourceBytes, memoryLimit(140));
  EXPECT_FALSE(memory.text);
  EXPECT_EQ(memory.exitCode, kExitModelError);
  EXPECT_EQ(memory.error, "checking the " + std::to_string(both) + " bytes of '" + path.string() +
                              "' needs about 147 MiB, past the memory limit of 140 MiB; raise it with --max-memory MIB");
}

// The studio reads its file through the limits of each read, its interactive ones: a
// file of another tool that grows past them while the studio watches it is refused, and
// says why; raised on the page, the same reader converts it.
TEST(ProgramLoader, TheStudioReadsThroughTheLimitsOfEachRead) {
  const fs::path dir = scratch("studio");
  const fs::path path = writeFile(dir / "grown.l", cpfgWithAxiomOf(10));
  const studio::StudioReader read = studioReader();
  const studio::StudioSource before = read(path.string(), kDefaultMaxSourceBytes, memoryLimit(8));
  ASSERT_TRUE(before.text) << before.error;
  ASSERT_TRUE(before.original);
  EXPECT_EQ(before.original->name(), path.string());
  // Checking 100,000 letters takes about 13 MiB.
  writeFile(path, cpfgWithAxiomOf(100'000));
  const studio::StudioSource after = read(path.string(), kDefaultMaxSourceBytes, memoryLimit(8));
  EXPECT_FALSE(after.text);
  EXPECT_NE(after.error.find("needs about 13 MiB, past the memory limit of 8 MiB"), std::string::npos) << after.error;
  const studio::StudioSource raised = read(path.string(), kDefaultMaxSourceBytes, memoryLimit(32));
  ASSERT_TRUE(raised.text) << raised.error;
  EXPECT_NE(raised.text->find("axiom F F F"), std::string::npos);
}

}  // namespace
}  // namespace ontogen::app
