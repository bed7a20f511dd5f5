#include "interpreters/output_file.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
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

}  // namespace
}  // namespace ontogen
