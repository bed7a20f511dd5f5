// The editors' grammar (editors/text_mate_grammar.h): the committed copy is what
// `ontogen help --grammar` prints, and every name of the tables it is made from is in it.
// tests/editors/text_mate_grammar_test.mjs tokenizes models with it in a real TextMate
// engine (vscode-textmate with Oniguruma).

#include "editors/text_mate_grammar.h"

#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "interpreters/creature/creature_commands.h"
#include "interpreters/dynamics/dynamics_commands.h"
#include "interpreters/music/music_commands.h"
#include "interpreters/physics/physics_commands.h"
#include "interpreters/geometry/turtle_commands.h"
#include "model/builtins.h"
#include "lang/directives.h"
#include "lang/keywords.h"

namespace {

using ontogen::editors::textMateGrammar;

std::string committed() {
  std::ifstream in(std::string(ONTOGEN_SOURCE_DIR) + "/editors/vscode/syntaxes/cell.tmLanguage.json", std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(TextMateGrammar, TheCommittedCopyIsWhatTheTablesMake) {
  // If this fails after a table changed: ontogen help --grammar > editors/vscode/syntaxes/cell.tmLanguage.json
  EXPECT_EQ(committed(), textMateGrammar());
  EXPECT_EQ(textMateGrammar(), textMateGrammar());
}

TEST(TextMateGrammar, ItIsATextMateGrammarHoldingEveryNameOfTheTables) {
  const nlohmann::json grammar = nlohmann::json::parse(textMateGrammar());
  EXPECT_EQ(grammar["scopeName"], "source.cell");
  EXPECT_EQ(grammar["fileTypes"], nlohmann::json::array({"cell"}));
  for (const nlohmann::json& include : grammar["patterns"])
    EXPECT_TRUE(grammar["repository"].contains(include["include"].get<std::string>().substr(1))) << include;
  const std::string text = textMateGrammar();
  // Names as the JSON holds them: a regex's escapes doubled.
  auto holds = [&](std::string_view name) { return text.find(std::string(name)) != std::string::npos; };
  for (const ontogen::Keyword& keyword : ontogen::keywords()) EXPECT_TRUE(holds(keyword.name)) << keyword.name;
  for (const ontogen::Directive& directive : ontogen::directives()) EXPECT_TRUE(holds(directive.name)) << directive.name;
  for (const ontogen::BuiltinFunction& function : ontogen::builtinFunctions()) EXPECT_TRUE(holds(function.name)) << function.name;
  for (const ontogen::MusicCommand& command : ontogen::musicCommands()) {
    if (std::isalpha(static_cast<unsigned char>(command.name[0]))) {
      EXPECT_TRUE(holds(command.name)) << command.name;
    }
  }
  for (const ontogen::DynamicsCommand& command : ontogen::dynamicsCommands()) EXPECT_TRUE(holds(command.name)) << command.name;
  for (const ontogen::TurtleCommand& command : ontogen::turtleCommands()) {
    if (std::isalpha(static_cast<unsigned char>(command.name[0]))) {
      EXPECT_TRUE(holds(command.name)) << command.name;
    }
  }
  for (const ontogen::CreatureCommand& command : ontogen::creatureCommands()) {
    if (std::isalpha(static_cast<unsigned char>(command.name[0]))) {
      EXPECT_TRUE(holds(command.name)) << command.name;
    }
  }
  for (const ontogen::PhysicsCommand& command : ontogen::physicsCommands()) {
    if (std::isalpha(static_cast<unsigned char>(command.name[0]))) {
      EXPECT_TRUE(holds(command.name)) << command.name;
    }
  }
}

}  // namespace
