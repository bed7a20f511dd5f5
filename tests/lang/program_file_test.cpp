// Reading a program file (lang/program_file.h): a cell-language file as it is, another
// tool's converted, each held to the source limit and to the memory check before it is
// converted or checked, and why there is no text said in the result.

#include "lang/program_file.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/test_files.h"

namespace ontogen {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) { return test::scratchDir(name, "program_file_test"); }

using test::writeFile;

const std::string kCpfg = "Lsystem: 1\nderivation length: 1\nAxiom: FF\nF --> F\nendlsystem\n";

// Records what the memory check is asked, and refuses past `limit` bytes.
struct RecordingCheck {
  uint64_t limit = UINT64_MAX;
  std::vector<std::pair<std::string, uint64_t>> asked;
  MemoryCheck check() {
    return [this](const std::string& what, uint64_t bytes) -> std::optional<std::string> {
      asked.emplace_back(what, bytes);
      if (bytes > limit) return what + " is too much";
      return std::nullopt;
    };
  }
};

TEST(ProgramFile, ACellFileIsReadAsItIsAfterOneCheckOfItsMemory) {
  const fs::path path = writeFile(scratch("cell") / "tree.cell", "lsystem tree {\n  axiom F\n}\n");
  RecordingCheck memory;
  DiagnosticSink sink;
  const ProgramFileText read = readProgramFile(path.string(), {.memory = memory.check()}, sink);
  ASSERT_TRUE(read.text);
  EXPECT_EQ(*read.text, "lsystem tree {\n  axiom F\n}\n");
  EXPECT_EQ(read.name, path.string());
  EXPECT_FALSE(read.converted);
  EXPECT_EQ(read.failure, ProgramFileFailure::None);
  ASSERT_EQ(memory.asked.size(), 1u);
  EXPECT_EQ(memory.asked[0].first, "checking the 27 bytes of '" + path.string() + "'");
  EXPECT_EQ(memory.asked[0].second, 27 * kCheckBytesPerSourceByte);
}

TEST(ProgramFile, AnotherToolsFileIsCheckedBeforeAndAfterItIsConverted) {
  const fs::path path = writeFile(scratch("cpfg") / "tree.l", kCpfg);
  RecordingCheck memory;
  DiagnosticSink sink;
  const ProgramFileText read = readProgramFile(path.string(), {.memory = memory.check()}, sink);
  ASSERT_TRUE(read.text) << read.error;
  EXPECT_TRUE(read.converted);
  EXPECT_EQ(read.name, path.string() + " (converted)");
  ASSERT_TRUE(read.original);
  EXPECT_EQ(read.original->name(), path.string());
  EXPECT_EQ(read.lineOrigins.size(), static_cast<size_t>(std::count(read.text->begin(), read.text->end(), '\n')));
  ASSERT_EQ(memory.asked.size(), 2u);
  EXPECT_EQ(memory.asked[0].second, kCpfg.size() * kCheckBytesPerSourceByte);
  EXPECT_EQ(memory.asked[1].first,
            "checking the " + std::to_string(read.text->size()) + " bytes of '" + path.string() + " (converted)'");

  // Refused before it is converted: nothing reaches the converter.
  RecordingCheck tight;
  tight.limit = 100;
  DiagnosticSink quiet;
  const ProgramFileText refused = readProgramFile(path.string(), {.memory = tight.check()}, quiet);
  EXPECT_FALSE(refused.text);
  EXPECT_EQ(refused.failure, ProgramFileFailure::PastMemoryLimit);
  EXPECT_EQ(refused.error, "checking the " + std::to_string(kCpfg.size()) + " bytes of '" + path.string() +
                               "' is too much");
  EXPECT_EQ(tight.asked.size(), 1u);
  EXPECT_TRUE(quiet.diagnostics().empty());
}

// cpfg reads the view file its command line names, which a vlab object keeps in its
// `specifications`; without one, the view file of the L-system's name.
TEST(ProgramFile, ACpfgFilesViewIsTheOneItsSpecificationsNameElseItsOwnName) {
  const fs::path dir = scratch("specifications");
  const std::string lsystem = "Lsystem: 1\nAxiom: F+F\nendlsystem\n";
  const fs::path lamp = writeFile(dir / "lamp.l", lsystem);
  writeFile(dir / "view.v", "angle increment: 20\n");
  writeFile(dir / "lamp.v", "angle increment: 60\n");
  writeFile(dir / "specifications", "lamp.l\nmodel:\n\tgenerate:\n\t\tcpfg -M materials.mat lamp.l view.v anim.a\n");
  DiagnosticSink sink;
  const ProgramFileText named = readProgramFile(lamp.string(), {}, sink);
  ASSERT_TRUE(named.text) << named.error;
  EXPECT_NE(named.text->find("  #angle 20\n"), std::string::npos) << *named.text;
  EXPECT_TRUE(sink.diagnostics().empty());

  const fs::path other = writeFile(dir / "other.l", lsystem);
  writeFile(dir / "other.v", "angle factor: 12\n");
  const ProgramFileText own = readProgramFile(other.string(), {}, sink);
  ASSERT_TRUE(own.text) << own.error;
  EXPECT_NE(own.text->find("  #angle 360 / 12\n"), std::string::npos) << *own.text;

  const fs::path alone = writeFile(dir / "alone.l", lsystem);
  DiagnosticSink warned;
  const ProgramFileText without = readProgramFile(alone.string(), {}, warned);
  ASSERT_TRUE(without.text) << without.error;
  EXPECT_EQ(without.text->find("#angle"), std::string::npos) << *without.text;
  ASSERT_EQ(warned.diagnostics().size(), 1u);
  EXPECT_EQ(formatDiagnostics(warned).rfind(alone.string() + ":2:1: warning: no view file", 0), 0u)
      << formatDiagnostics(warned);
}

TEST(ProgramFile, WhyThereIsNoTextComesBackWithItsKind) {
  const fs::path dir = scratch("failures");
  DiagnosticSink sink;
  const ProgramFileText missing = readProgramFile((dir / "none.cell").string(), {}, sink);
  EXPECT_EQ(missing.failure, ProgramFileFailure::Unreadable);
  EXPECT_EQ(missing.error.rfind("cannot read '" + (dir / "none.cell").string() + "': ", 0), 0u) << missing.error;

  const fs::path big = writeFile(dir / "big.cell", std::string(2000, ' '));
  const ProgramFileText tooLarge = readProgramFile(big.string(), {.maxSourceBytes = 1000, .memory = {}}, sink);
  EXPECT_EQ(tooLarge.failure, ProgramFileFailure::Unreadable);

  const fs::path bad = writeFile(dir / "bad.l", "Lsystem: 1\nAxiom: F\nF --> F(\nendlsystem\n");
  DiagnosticSink errors;
  const ProgramFileText notConverted = readProgramFile(bad.string(), {}, errors);
  EXPECT_FALSE(notConverted.text);
  EXPECT_TRUE(notConverted.failure == ProgramFileFailure::NotConverted ||
              notConverted.failure == ProgramFileFailure::Untranslatable);
  EXPECT_EQ(notConverted.error, "it cannot be converted from cpfg");
  EXPECT_GT(errors.errorCount(), 0);
  // The converter's diagnostics point into the file, which the result keeps.
  ASSERT_TRUE(notConverted.original);
  EXPECT_EQ(formatDiagnostics(errors).rfind(bad.string() + ":3:8: error: ", 0), 0u) << formatDiagnostics(errors);
  EXPECT_NE(formatDiagnostics(errors).find("\nF --> F(\n       ^\n"), std::string::npos) << formatDiagnostics(errors);
}

}  // namespace
}  // namespace ontogen
