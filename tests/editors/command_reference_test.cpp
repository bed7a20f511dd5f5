// The sets' command reference (editors/command_reference.h): the committed docs/COMMANDS.md
// is what `ontogen help --reference` prints, it has a row for every command of every
// table in the table's order, and docs/LANGUAGE.md links each set to it.

#include "editors/command_reference.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "interpreters/creature/creature_commands.h"
#include "interpreters/dynamics/dynamics_commands.h"
#include "interpreters/geometry/turtle_commands.h"
#include "interpreters/music/music_commands.h"
#include "interpreters/physics/physics_commands.h"

namespace {

using ontogen::editors::commandReference;

std::string readDoc(const std::string& name) {
  std::ifstream in(std::string(ONTOGEN_SOURCE_DIR) + "/docs/" + name, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The signatures in the rows of the section headed `heading`, in order, unescaped.
std::vector<std::string> rowsOf(const std::string& reference, const std::string& heading) {
  std::istringstream lines(reference);
  std::vector<std::string> rows;
  std::string line;
  for (bool in = false; std::getline(lines, line);) {
    if (line.rfind("## ", 0) == 0) in = line == "## " + heading;
    if (!in || line.rfind("| `", 0) != 0) continue;
    std::string signature;
    for (size_t i = 3; i < line.size() && line[i] != '`'; ++i) {
      if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') continue;
      signature += line[i];
    }
    rows.push_back(signature);
  }
  return rows;
}

template <typename Table>
std::vector<std::string> signaturesOf(const Table& table) {
  std::vector<std::string> out;
  for (const auto& row : table) out.emplace_back(row.signature);
  return out;
}

TEST(CommandReference, TheCommittedCopyIsWhatTheTablesMake) {
  // If this fails after a table changed: ontogen help --reference > docs/COMMANDS.md
  EXPECT_EQ(readDoc("COMMANDS.md"), commandReference());
  EXPECT_EQ(commandReference(), commandReference());
}

TEST(CommandReference, EveryCommandOfEveryTableHasARowInItsSet) {
  const std::string reference = commandReference();
  EXPECT_EQ(rowsOf(reference, "The geometry set"), signaturesOf(ontogen::turtleCommands()));
  EXPECT_EQ(rowsOf(reference, "The creature set"), signaturesOf(ontogen::creatureCommands()));
  EXPECT_EQ(rowsOf(reference, "The dynamics set"), signaturesOf(ontogen::dynamicsCommands()));
  EXPECT_EQ(rowsOf(reference, "The physics set"), signaturesOf(ontogen::physicsCommands()));
  EXPECT_EQ(rowsOf(reference, "The music set"), signaturesOf(ontogen::musicCommands()));
}

// A row has its three cells whatever its text holds: the turtle's `|` is escaped.
TEST(CommandReference, EveryRowHasThreeCells) {
  std::istringstream lines(commandReference());
  std::string line;
  int rows = 0;
  while (std::getline(lines, line)) {
    if (line.rfind("| `", 0) != 0) continue;
    ++rows;
    int bars = 0;
    for (size_t i = 0; i < line.size(); ++i) bars += line[i] == '|' && (i == 0 || line[i - 1] != '\\');
    EXPECT_EQ(bars, 4) << line;
  }
  EXPECT_GT(rows, 90);
  EXPECT_NE(commandReference().find("| `\\|` | 0 | "), std::string::npos) << "the turtle's |, escaped";
}

// docs/LANGUAGE.md gives each set's commands by a link to its section of the reference.
TEST(CommandReference, TheLanguageLinksEverySetToItsCommands) {
  const std::string language = readDoc("LANGUAGE.md");
  for (const char* anchor : {"the-geometry-set", "the-creature-set", "the-dynamics-set", "the-physics-set",
                             "the-music-set"})
    EXPECT_NE(language.find(std::string("(COMMANDS.md#") + anchor + ")"), std::string::npos) << anchor;
}

}  // namespace
