// What ontogen writes, it owns: an output that is a symbolic link is written through the
// link (the link stays a link), an output that is not a regular file (a FIFO, a folder)
// is refused with exit 4 and left as it was, and a command whose standard output cannot
// be written (/dev/full) fails with exit 4 and says so.

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <string>

#include "tests/apps/cli_support.h"

namespace {

namespace fs = std::filesystem;
using ontogen::test::CliResult;
using ontogen::test::modelPath;
using ontogen::test::readWholeFile;
using ontogen::test::runOntogen;
using ontogen::test::scratchDir;

fs::path makeFifo(const fs::path& path) {
  EXPECT_EQ(::mkfifo(path.c_str(), 0644), 0) << path;
  return path;
}

// --equations, run's formats and timeline --out all go through the one writer: a link
// to a file gives the file the bytes and stays a link.
TEST(OutputOwnership, ASymbolicLinkIsWrittenThroughToItsTarget) {
  const fs::path dir = scratchDir("own_link");
  const std::string tree = modelPath("statics_binary_tree.cell");
  const CliResult plain = runOntogen("statics " + tree + " --equations " + (dir / "plain.txt").string());
  ASSERT_EQ(plain.exitCode, 0) << plain.err;
  ontogen::test::writeFile(dir / "target.txt", "old");
  ::chmod((dir / "target.txt").c_str(), 0600);
  fs::create_symlink("target.txt", dir / "link.txt");
  const CliResult linked = runOntogen("statics " + tree + " --equations " + (dir / "link.txt").string());
  ASSERT_EQ(linked.exitCode, 0) << linked.err;
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_EQ(fs::read_symlink(dir / "link.txt"), "target.txt");
  EXPECT_EQ(readWholeFile(dir / "target.txt"), readWholeFile(dir / "plain.txt"));
  EXPECT_EQ(fs::status(dir / "target.txt").permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);

  // run's outputs: the file run names is a link into another folder.
  const fs::path out = dir / "out", elsewhere = dir / "elsewhere";
  fs::create_directories(out);
  fs::create_directories(elsewhere);
  ontogen::test::writeFile(elsewhere / "koch.svg", "old");
  fs::create_symlink(elsewhere / "koch.svg", out / "koch.svg");
  const CliResult run = runOntogen("run " + modelPath("koch.cell") + " --format svg --out " + out.string());
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_TRUE(fs::is_symlink(out / "koch.svg"));
  EXPECT_EQ(readWholeFile(elsewhere / "koch.svg").rfind("<?xml", 0), 0u) << readWholeFile(elsewhere / "koch.svg");
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), 1) << "no temporary left";
}

TEST(OutputOwnership, AFifoAFolderAndALinkToAFifoAreRefusedAndKept) {
  const fs::path dir = scratchDir("own_refused");
  const std::string tree = modelPath("statics_binary_tree.cell");
  const fs::path fifo = makeFifo(dir / "fifo.txt");
  fs::create_directories(dir / "folder.txt");
  fs::create_symlink("fifo.txt", dir / "link.txt");
  struct Case {
    fs::path path;
    std::string says;
  };
  for (const Case& c : {Case{fifo, "it is a FIFO"}, Case{dir / "folder.txt", "it is a folder"},
                        Case{dir / "link.txt", "it is a FIFO (through its link, '" + fifo.string() + "')"}}) {
    const CliResult result = runOntogen("statics " + tree + " --equations " + c.path.string(), 30);
    EXPECT_EQ(result.exitCode, 4) << c.path << "\n" << result.err;
    EXPECT_NE(result.err.find("cannot write '" + c.path.string() + "': " + c.says + "; ontogen writes only regular files"),
              std::string::npos)
        << result.err;
  }
  EXPECT_EQ(fs::status(fifo).type(), fs::file_type::fifo);
  EXPECT_EQ(fs::status(dir / "folder.txt").type(), fs::file_type::directory);
  EXPECT_TRUE(fs::is_symlink(dir / "link.txt"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3) << "no temporary left";

  // The other commands' outputs go the same way.
  const fs::path out = dir / "out";
  fs::create_directories(out);
  makeFifo(out / "koch.svg");
  const CliResult run = runOntogen("run " + modelPath("koch.cell") + " --format svg --out " + out.string(), 30);
  EXPECT_EQ(run.exitCode, 4) << run.err;
  EXPECT_NE(run.err.find("it is a FIFO"), std::string::npos) << run.err;
  EXPECT_EQ(fs::status(out / "koch.svg").type(), fs::file_type::fifo);
  const fs::path diagram = makeFifo(dir / "diagram.svg");
  const CliResult timeline = runOntogen("timeline " + modelPath("anabaena.cell") + " --out " + diagram.string(), 30);
  EXPECT_EQ(timeline.exitCode, 4) << timeline.err;
  EXPECT_NE(timeline.err.find("it is a FIFO"), std::string::npos) << timeline.err;
  EXPECT_EQ(fs::status(diagram).type(), fs::file_type::fifo);
}

// Every command that writes to standard output fails when it cannot (a full disk).
TEST(OutputOwnership, AFullStandardOutputIsExitFour) {
  const std::string koch = modelPath("koch.cell"), tree = modelPath("statics_binary_tree.cell");
  const std::string cpfg = std::string(ONTOGEN_SOURCE_DIR) + "/tests/convert/fig1_24d.l";
  for (const std::string& command :
       {"word " + koch + " --at 6", "word " + koch + " --at 6 --json", "statics " + tree + " --json", "statics " + tree,
        "convert " + cpfg, "check " + koch, "run " + koch + " --format none --stats", std::string("help --grammar"), std::string("help")}) {
    const CliResult result = runOntogen(command + " >/dev/full", 60);
    EXPECT_EQ(result.exitCode, 4) << command << "\n" << result.err;
    EXPECT_NE(result.err.find("ontogen: error: cannot write the standard output"), std::string::npos)
        << command << "\n" << result.err;
  }
}

}  // namespace
