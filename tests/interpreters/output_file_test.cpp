#include "interpreters/output_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

namespace ontogen {
namespace {

namespace fs = std::filesystem;

/// A fresh empty directory for one test, removed afterwards.
class OutputFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    directory_ = fs::temp_directory_path() /
                 ("ontogen_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }

  std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
  /// Number of entries in the directory.
  int entries() {
    int count = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(directory_)) ++count;
    return count;
  }

  fs::path directory_;
};

TEST_F(OutputFileTest, WritesTheContent) {
  fs::path path = directory_ / "a.txt";
  writeFileAtomically(path, [](std::ostream& out) { out << "hello\n"; });
  EXPECT_EQ(read(path), "hello\n");
  EXPECT_EQ(entries(), 1);  // no temporary left
}

TEST_F(OutputFileTest, ReplacesAnExistingFile) {
  fs::path path = directory_ / "a.txt";
  writeFileAtomically(path, [](std::ostream& out) { out << "a much longer first version\n"; });
  writeFileAtomically(path, [](std::ostream& out) { out << "second\n"; });
  EXPECT_EQ(read(path), "second\n");
  EXPECT_EQ(entries(), 1);
}

TEST_F(OutputFileTest, NewFileGetsOrdinaryPermissions) {
  fs::path reference = directory_ / "reference.txt";
  std::ofstream(reference) << "x";
  fs::path path = directory_ / "a.txt";
  writeFileAtomically(path, [](std::ostream& out) { out << "x"; });
  EXPECT_EQ(fs::status(path).permissions(), fs::status(reference).permissions());
}

TEST_F(OutputFileTest, MissingDirectoryThrowsAndLeavesNoFile) {
  fs::path path = directory_ / "missing" / "a.svg";
  try {
    writeFileAtomically(path, [](std::ostream& out) { out << "x"; });
    FAIL() << "no exception";
  } catch (const OutputError& error) {
    EXPECT_EQ(std::string(error.what()),
              "cannot write '" + path.string() + "': No such file or directory");
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_EQ(entries(), 0);
}

TEST_F(OutputFileTest, StreamFailureThrowsAndKeepsTheOldFile) {
  fs::path path = directory_ / "a.txt";
  writeFileAtomically(path, [](std::ostream& out) { out << "old\n"; });
  EXPECT_THROW(writeFileAtomically(path,
                                   [](std::ostream& out) {
                                     out << "half";
                                     out.setstate(std::ios::badbit);
                                   }),
               OutputError);
  EXPECT_EQ(read(path), "old\n");
  EXPECT_EQ(entries(), 1);
}

TEST_F(OutputFileTest, ExceptionFromTheWriterPropagatesAndKeepsTheOldFile) {
  fs::path path = directory_ / "a.txt";
  writeFileAtomically(path, [](std::ostream& out) { out << "old\n"; });
  EXPECT_THROW(writeFileAtomically(path,
                                   [](std::ostream& out) {
                                     out << "half";
                                     throw std::runtime_error("model failed");
                                   }),
               std::runtime_error);
  EXPECT_EQ(read(path), "old\n");
  EXPECT_EQ(entries(), 1);
}

TEST_F(OutputFileTest, TargetThatIsADirectoryThrowsAndLeavesNoTemporary) {
  fs::path path = directory_ / "sub";
  fs::create_directory(path);
  fs::create_directory(path / "keep");  // a non-empty directory cannot be replaced
  try {
    writeFileAtomically(path, [](std::ostream& out) { out << "x"; });
    FAIL() << "no exception";
  } catch (const OutputError& error) {
    EXPECT_NE(std::string(error.what()).find("cannot write '" + path.string() + "': "),
              std::string::npos);
  }
  EXPECT_TRUE(fs::is_directory(path));
  EXPECT_EQ(entries(), 1);
}

TEST_F(OutputFileTest, AnEmptyFolderIsRefusedToo) {
  fs::path path = directory_ / "empty";
  fs::create_directory(path);
  try {
    writeFileAtomically(path, [](std::ostream& out) { out << "x"; });
    FAIL() << "no exception";
  } catch (const OutputError& error) {
    EXPECT_EQ(std::string(error.what()),
              "cannot write '" + path.string() + "': it is a folder; ontogen writes only regular files");
  }
  EXPECT_TRUE(fs::is_directory(path));
  EXPECT_EQ(entries(), 1);
}

// The link stays a link; the file it points to gets the bytes and keeps its permissions.
TEST_F(OutputFileTest, ASymbolicLinkIsWrittenThrough) {
  fs::create_directory(directory_ / "real");
  std::ofstream(directory_ / "real" / "a.txt") << "old";
  ::chmod((directory_ / "real" / "a.txt").c_str(), 0600);
  fs::create_symlink("real/a.txt", directory_ / "link.txt");
  fs::create_symlink("link.txt", directory_ / "link2.txt");  // a link to a link
  writeFileAtomically(directory_ / "link2.txt", [](std::ostream& out) { out << "new\n"; });
  EXPECT_TRUE(fs::is_symlink(directory_ / "link.txt"));
  EXPECT_TRUE(fs::is_symlink(directory_ / "link2.txt"));
  EXPECT_EQ(fs::read_symlink(directory_ / "link.txt"), "real/a.txt");
  EXPECT_EQ(read(directory_ / "real" / "a.txt"), "new\n");
  EXPECT_EQ(fs::status(directory_ / "real" / "a.txt").permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write);
  EXPECT_EQ(entries(), 3);
  EXPECT_EQ(std::distance(fs::directory_iterator(directory_ / "real"), fs::directory_iterator()), 1);
}

TEST_F(OutputFileTest, ADanglingLinkMakesTheFileItNames) {
  fs::create_symlink("made.txt", directory_ / "link.txt");
  writeFileAtomically(directory_ / "link.txt", [](std::ostream& out) { out << "x"; });
  EXPECT_TRUE(fs::is_symlink(directory_ / "link.txt"));
  EXPECT_EQ(read(directory_ / "made.txt"), "x");
}

TEST_F(OutputFileTest, AFifoAndALinkToItAreRefusedAndKept) {
  const fs::path fifo = directory_ / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
  fs::create_symlink("fifo", directory_ / "link");
  for (const auto& [path, says] :
       {std::pair{fifo, std::string("it is a FIFO")},
        std::pair{directory_ / "link", "it is a FIFO (through its link, '" + fifo.string() + "')"}}) {
    try {
      writeFileAtomically(path, [](std::ostream& out) { out << "x"; });
      FAIL() << "no exception";
    } catch (const OutputError& error) {
      EXPECT_EQ(std::string(error.what()), "cannot write '" + path.string() + "': " + says + "; ontogen writes only regular files");
    }
  }
  EXPECT_EQ(fs::symlink_status(fifo).type(), fs::file_type::fifo);
  EXPECT_TRUE(fs::is_symlink(directory_ / "link"));
  EXPECT_EQ(entries(), 2);
}

TEST_F(OutputFileTest, LinksInALoopAreRefused) {
  fs::create_symlink("b", directory_ / "a");
  fs::create_symlink("a", directory_ / "b");
  EXPECT_THROW(writeFileAtomically(directory_ / "a", [](std::ostream& out) { out << "x"; }), OutputError);
  EXPECT_TRUE(fs::is_symlink(directory_ / "a"));
  EXPECT_EQ(entries(), 2);
}

}  // namespace
}  // namespace ontogen
