// `ontogen statics` as a user meets it: the JSON of the paper's binary tree and spiral,
// the equations file, --at and --define, the exit codes of bad input; `ontogen help`
// lists the physics set's commands.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <functional>
#include <set>
#include <string>

#include "tests/apps/cli_support.h"

namespace {

namespace fs = std::filesystem;
using ontogen::test::CliResult;

fs::path scratch(const std::string& name) { return ontogen::test::scratchDir("statics_" + name); }
CliResult ontogen(const std::string& args) { return ontogen::test::runOntogen(args); }
std::string readFile(const fs::path& path) { return ontogen::test::readWholeFile(path); }
std::string model(const std::string& name) { return std::string(ONTOGEN_SOURCE_DIR) + "/models/" + name; }

TEST(StaticsCli, TheBinaryTreeAsJsonAndAsEquations) {
  const fs::path equations = scratch("tree") / "tree.txt";
  const CliResult result =
      ontogen("statics " + model("statics_binary_tree.cell") + " --json --equations " + equations.string());
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json json = nlohmann::json::parse(result.out);
  EXPECT_EQ(json["t"], 4);
  EXPECT_EQ(json["g"], 9.81);
  ASSERT_EQ(json["rods"].size(), 15u);
  EXPECT_EQ(json["rods"][0]["parent"], -1);
  for (const char* field : {"id", "parent", "base", "tip", "rest_tip", "length", "mass", "force", "moment"})
    EXPECT_TRUE(json["rods"][3].contains(field)) << field;
  const std::string text = readFile(equations);
  const std::string root = json["rods"][0]["id"].dump();
  EXPECT_NE(text.find("\nF_" + root + " = ("), std::string::npos) << text;
  EXPECT_NE(text.find(" + F_" + json["rods"][1]["id"].dump()), std::string::npos);
  size_t lines = 0;
  for (char c : text) lines += c == '\n';
  EXPECT_EQ(lines, 2u + 30u) << "two lines of header, an F and an M per rod";
}

TEST(StaticsCli, TheSpiralHas29RodsInAChainAndAtTwoSecondsTwo) {
  const CliResult all = ontogen("statics " + model("statics_spiral.cell") + " --json");
  ASSERT_EQ(all.exitCode, 0) << all.err;
  const nlohmann::json json = nlohmann::json::parse(all.out);
  ASSERT_EQ(json["rods"].size(), 29u);
  for (size_t i = 1; i < 29; ++i) EXPECT_EQ(json["rods"][i]["parent"], json["rods"][i - 1]["id"]);
  const CliResult early = ontogen("statics " + model("statics_spiral.cell") + " --json --at 2");
  ASSERT_EQ(early.exitCode, 0) << early.err;
  EXPECT_EQ(nlohmann::json::parse(early.out)["rods"].size(), 2u);
  const CliResult text = ontogen("statics " + model("statics_spiral.cell") + " --define RODS=3");
  ASSERT_EQ(text.exitCode, 0) << text.err;
  EXPECT_EQ(text.out.rfind("3 rods at t = 3 s\n", 0), 0u) << text.out;
}

// A rod's id is its cell's id as `word --json` prints it: the two outputs join on it.
TEST(StaticsCli, RodsJoinTheirCellsOfWordJsonById) {
  const CliResult statics = ontogen("statics " + model("statics_binary_tree.cell") + " --json --at 4");
  ASSERT_EQ(statics.exitCode, 0) << statics.err;
  const CliResult word = ontogen("word " + model("statics_binary_tree.cell") + " --json --at 4");
  ASSERT_EQ(word.exitCode, 0) << word.err;
  std::set<double> cells;
  std::function<void(const nlohmann::json&)> collect = [&](const nlohmann::json& value) {
    if (value.is_object() && value.contains("id")) cells.insert(value["id"].get<double>());
    if (value.is_object() || value.is_array())
      for (const nlohmann::json& item : value) collect(item);
  };
  collect(nlohmann::json::parse(word.out));
  const nlohmann::json rods = nlohmann::json::parse(statics.out)["rods"];
  ASSERT_EQ(rods.size(), 15u);
  for (const nlohmann::json& rod : rods) {
    EXPECT_TRUE(cells.count(rod["id"].get<double>())) << rod["id"];
    EXPECT_LT(rod["id"].get<double>(), 9007199254740992.0) << "past 2^53 a JSON reader rounds it";
  }
}

TEST(StaticsCli, TheCantileverBendsAndReportsItsDeflectedTip) {
  const CliResult result = ontogen("statics " + model("cantilever.cell") + " --json --define P=2000");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  const nlohmann::json last = nlohmann::json::parse(result.out)["rods"].back();
  EXPECT_NEAR(last["rest_tip"][0].get<double>(), 1, 1e-12);
  EXPECT_LT(last["tip"][1].get<double>(), -0.4);
}

TEST(StaticsCli, BadInputHasItsExitCode) {
  EXPECT_EQ(ontogen("statics " + model("cantilever.cell") + " --at -1").exitCode, 2);
  // Not a time: a bad argument, refused in one short line (no 300 digits), not a model error.
  for (const char* at : {"nan", "inf", "-inf", "1e999"}) {
    const CliResult result = ontogen("statics " + model("cantilever.cell") + " --at " + at);
    EXPECT_EQ(result.exitCode, 2) << at << "\n" << result.err;
    EXPECT_LT(result.err.size(), 200u) << result.err;
  }
  EXPECT_EQ(ontogen("statics " + model("cantilever.cell") + " --define Q=1").exitCode, 2);
  const fs::path dir = scratch("bad");
  std::ofstream(dir / "bad.cell") << "lsystem a {\n  axiom rod(1, y)\n}\n";
  const CliResult bad = ontogen("statics " + (dir / "bad.cell").string());
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.err.find("bad.cell:2:16: error: unknown name 'y'"), std::string::npos) << bad.err;
  const CliResult unwritable =
      ontogen("statics " + model("cantilever.cell") + " --equations " + (dir / "no" / "such" / "dir.txt").string());
  EXPECT_EQ(unwritable.exitCode, 4) << unwritable.err;
}

TEST(StaticsCli, HelpListsThePhysicsCommands) {
  const CliResult result = ontogen("help");
  ASSERT_EQ(result.exitCode, 0);
  EXPECT_NE(result.out.find("Physics commands (set 'physics'"), std::string::npos);
  EXPECT_NE(result.out.find("load(x, y, z, at)"), std::string::npos);
  EXPECT_NE(result.out.find("ontogen statics FILE"), std::string::npos);
}

}  // namespace
