// Walks tests/programs/*.cell: one small program per behaviour, with what it must do
// written in the file as comments:
//   // expect-word T: WORD        the derivation word at time T (6 significant digits)
//   // expect-image T: WORD       the word as interpretation reads it at T (after homomorphism rules)
//   // expect-rewrites T: COUNTS  the strategies that rewrote the word by T and how often, as
//                                 run --stats prints them ("compact-serial 2"; core/rewrite_plan.h)
//   // expect-error L:C: TEXT     an error at line L, column C whose message contains TEXT
//   // expect-run-error: TEXT     developing on past the last expected word (1000 s) fails with TEXT
//   // expect-warning L:C: TEXT   a warning at line L, column C whose message contains TEXT
//   // expect-no-warnings         the program compiles without warnings
//   // step: DT                   the step used to develop (default: the program's #dt)
//   // seed: S                    the seed (default 1)
//   // define: NAME=VALUE         compile with this value for #define NAME (CompileOptions::defines)
// A file with expect-error lines must report exactly those errors and no others; one with
// expect-warning or expect-no-warnings lines exactly those warnings.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <string_view>
#include <sstream>

#include "core/rewrite_plan.h"
#include "core/word.h"
#include "core/world.h"
#include "interpreters/set_registry.h"
#include "interpreters/text/word_text.h"
#include "lang/compiler.h"

namespace ontogen {
namespace {

// What is expected at a time: the developing word, the image interpretation reads, or
// the strategies that rewrote the word so far.
struct ExpectedWord {
  enum Kind { Word, Image, Rewrites };
  double time = 0;
  std::string text;
  Kind kind = Word;
};

struct Expectations {
  std::vector<ExpectedWord> words;  ///< in file order (time runs forward)
  std::vector<std::tuple<int, int, std::string>> errors;
  std::vector<std::tuple<int, int, std::string>> warnings;
  bool checkWarnings = false;
  std::string runError;
  std::optional<double> step;
  uint64_t seed = 1;
  std::vector<DefineOverride> defines;
};

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The text after `// KEY` on a line, or nothing. (No <regex>: GCC 12 warns falsely
// inside it under the sanitizers.)
std::optional<std::string> after(const std::string& line, std::string_view key) {
  size_t comment = line.find("//");
  if (comment == std::string::npos) return std::nullopt;
  size_t start = line.find_first_not_of(' ', comment + 2);
  if (start == std::string::npos || line.compare(start, key.size(), key) != 0) return std::nullopt;
  return line.substr(start + key.size());
}

// Splits "T: rest" at the first ": " (or ':' at the end).
std::pair<std::string, std::string> splitAtColon(const std::string& text) {
  size_t colon = text.find(':');
  std::string head = text.substr(0, colon);
  std::string tail = colon == std::string::npos ? "" : text.substr(colon + 1);
  if (!tail.empty() && tail[0] == ' ') tail.erase(0, 1);
  return {head, tail};
}

Expectations expectationsOf(const std::string& text) {
  Expectations result;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (auto wordLine = after(line, "expect-word ")) {
      auto [time, word] = splitAtColon(*wordLine);
      result.words.push_back({std::stod(time), word, ExpectedWord::Word});
    } else if (auto imageLine = after(line, "expect-image ")) {
      auto [time, word] = splitAtColon(*imageLine);
      result.words.push_back({std::stod(time), word, ExpectedWord::Image});
    } else if (auto rewritesLine = after(line, "expect-rewrites ")) {
      auto [time, counts] = splitAtColon(*rewritesLine);
      result.words.push_back({std::stod(time), counts, ExpectedWord::Rewrites});
    } else if (auto errorLine = after(line, "expect-error ")) {
      auto [line_, tail] = splitAtColon(*errorLine);
      auto [column, message] = splitAtColon(tail);
      result.errors.push_back({std::stoi(line_), std::stoi(column), message});
    } else if (auto warningLine = after(line, "expect-warning ")) {
      auto [line_, tail] = splitAtColon(*warningLine);
      auto [column, message] = splitAtColon(tail);
      result.warnings.push_back({std::stoi(line_), std::stoi(column), message});
      result.checkWarnings = true;
    } else if (after(line, "expect-no-warnings")) {
      result.checkWarnings = true;
    } else if (auto runLine = after(line, "expect-run-error:")) {
      result.runError = runLine->substr(runLine->find_first_not_of(' '));
    } else if (auto stepLine = after(line, "step:")) {
      result.step = std::stod(*stepLine);
    } else if (auto seedLine = after(line, "seed:")) {
      result.seed = std::stoull(*seedLine);
    } else if (auto defineLine = after(line, "define: ")) {
      size_t equals = defineLine->find('=');
      result.defines.push_back({defineLine->substr(0, equals), std::stod(defineLine->substr(equals + 1))});
    }
  }
  return result;
}

class ProgramFile : public testing::TestWithParam<std::filesystem::path> {};

TEST_P(ProgramFile, BehavesAsWritten) {
  const auto& path = GetParam();
  std::string text = readFile(path);
  Expectations expected = expectationsOf(text);
  ASSERT_TRUE(!expected.words.empty() || !expected.errors.empty() || !expected.runError.empty())
      << path << " states no expectation";
  DiagnosticSink sink;
  CompileOptions options;
  options.commandSets = commandSets();
  options.defines = expected.defines;
  std::shared_ptr<const Program> program = compileSource(path.string(), text, sink, options);

  std::vector<std::tuple<int, int, std::string>> reported;
  for (const auto& d : sink.diagnostics())
    if (d.severity == Severity::Error) reported.push_back({d.span.line(), d.span.column(), d.message});
  for (const auto& [line, column, message] : expected.errors) {
    bool found = false;
    for (const auto& [l, c, m] : reported) found |= l == line && c == column && m.find(message) != std::string::npos;
    EXPECT_TRUE(found) << "expected error at " << line << ":" << column << " containing '" << message
                       << "'; reported:\n"
                       << formatDiagnostics(sink);
  }
  EXPECT_EQ(reported.size(), expected.errors.size()) << formatDiagnostics(sink);
  if (expected.checkWarnings) {
    std::vector<std::tuple<int, int, std::string>> warned;
    for (const auto& d : sink.diagnostics())
      if (d.severity == Severity::Warning) warned.push_back({d.span.line(), d.span.column(), d.message});
    for (const auto& [line, column, message] : expected.warnings) {
      bool found = false;
      for (const auto& [l, c, m] : warned) found |= l == line && c == column && m.find(message) != std::string::npos;
      EXPECT_TRUE(found) << "expected a warning at " << line << ":" << column << " containing '" << message
                         << "'; reported:\n"
                         << formatDiagnostics(sink);
    }
    EXPECT_EQ(warned.size(), expected.warnings.size()) << formatDiagnostics(sink);
  }
  if (!expected.errors.empty()) {
    EXPECT_EQ(program, nullptr);
    return;
  }
  ASSERT_NE(program, nullptr) << formatDiagnostics(sink);

  WorldDef def;
  def.seed = expected.seed;
  def.environment = queryEnvironmentOf(*program);
  World world(program, def);
  double step = expected.step.value_or(program->dt);
  try {
    for (const auto& [time, what, kind] : expected.words) {
      world.advanceTo(time, step);
      if (kind == ExpectedWord::Rewrites)
        EXPECT_EQ(formatRewriteCounts(world.stats().rewrites), what) << "the rewrites by t = " << time;
      else
        EXPECT_EQ(formatWord(kind == ExpectedWord::Image ? captureInterpretedWord(world) : captureWord(world)), what)
            << (kind == ExpectedWord::Image ? "the image " : "") << "at t = " << time;
    }
    if (!expected.runError.empty()) {
      world.advanceTo(world.time() + 1000, step);
      ADD_FAILURE() << "expected the run to fail with '" << expected.runError << "'";
    }
  } catch (const std::exception& error) {
    if (expected.runError.empty()) {
      ADD_FAILURE() << "the run failed: " << error.what();
    } else {
      EXPECT_NE(std::string(error.what()).find(expected.runError), std::string::npos) << error.what();
    }
  }
}

std::vector<std::filesystem::path> programFiles() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(ONTOGEN_SOURCE_DIR "/tests/programs"))
    if (entry.path().extension() == ".cell") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

INSTANTIATE_TEST_SUITE_P(Programs, ProgramFile, testing::ValuesIn(programFiles()),
                         [](const testing::TestParamInfo<std::filesystem::path>& file) {
                           std::string name = file.param.stem().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

}  // namespace
}  // namespace ontogen
