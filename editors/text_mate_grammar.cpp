#include "editors/text_mate_grammar.h"

#include <algorithm>
#include <cctype>
#include <nlohmann/json.hpp>
#include <set>
#include <string_view>
#include <vector>

#include "interpreters/creature/creature_commands.h"
#include "interpreters/dynamics/dynamics_commands.h"
#include "interpreters/geometry/turtle_commands.h"
#include "interpreters/music/music_commands.h"
#include "interpreters/physics/physics_commands.h"
#include "model/builtins.h"
#include "lang/directives.h"
#include "lang/keywords.h"

namespace ontogen::editors {

namespace {

using Json = nlohmann::ordered_json;

// What may stand either side of a name: the lexer's identifier characters (letters,
// digits, '_', and every UTF-8 letter such as ρ).
constexpr std::string_view kBefore = "(?<![\\p{L}\\p{N}_])";
constexpr std::string_view kAfter = "(?![\\p{L}\\p{N}_])";

std::string escaped(std::string_view name) {
  std::string out;
  for (char c : name) {
    if (std::string_view("\\^$.|?*+()[]{}/-").find(c) != std::string_view::npos) out += '\\';
    out += c;
  }
  return out;
}

/// A command spelt like a name (cC, disc, ?F), not with symbols (+, [, &).
bool namelike(std::string_view name) {
  if (name.empty()) return false;
  const unsigned char first = static_cast<unsigned char>(name[0] == '?' && name.size() > 1 ? name[1] : name[0]);
  return std::isalpha(first) || first == '_' || first >= 0x80;
}

/// One alternation of the names, longest first so that no name hides a longer one.
std::string alternation(std::vector<std::string> names) {
  std::sort(names.begin(), names.end(), [](const std::string& a, const std::string& b) {
    return a.size() != b.size() ? a.size() > b.size() : a < b;
  });
  names.erase(std::unique(names.begin(), names.end()), names.end());
  std::string out = "(?:";
  for (size_t i = 0; i < names.size(); ++i) out += (i ? "|" : "") + escaped(names[i]);
  return out + ")";
}

Json match(const std::string& regex, std::string_view scope) { return Json{{"match", regex}, {"name", scope}}; }

/// The command set's name-like commands not already coloured by an earlier set.
template <typename Table>
Json commands(const Table& table, std::set<std::string>& taken, std::string_view scope) {
  std::vector<std::string> names;
  for (const auto& command : table)
    if (namelike(command.name) && taken.insert(std::string(command.name)).second) names.emplace_back(command.name);
  return match(std::string(kBefore) + alternation(names) + std::string(kAfter), scope);
}

Json keywordPatterns(std::set<std::string>& taken) {
  Json patterns = Json::array();
  const std::pair<KeywordKind, std::string_view> kinds[] = {{KeywordKind::Declaration, "storage.type.cell"},
                                                             {KeywordKind::Statement, "keyword.control.cell"},
                                                             {KeywordKind::Reference, "variable.language.cell"}};
  for (const auto& [kind, scope] : kinds) {
    std::vector<std::string> names, single;
    for (const Keyword& keyword : keywords()) {
      if (keyword.kind != kind || !taken.insert(std::string(keyword.name)).second) continue;
      (keyword.name.size() == 1 ? single : names).emplace_back(keyword.name);
    }
    if (!names.empty()) patterns.push_back(match(std::string(kBefore) + alternation(names) + std::string(kAfter), scope));
    // A one-letter keyword (g) only where the name it declares follows, so that a
    // parameter of that name stays a name.
    if (!single.empty())
      patterns.push_back(
          match(std::string(kBefore) + alternation(single) + "(?=\\s+[\\p{L}_])" + std::string(kAfter), scope));
  }
  return patterns;
}

Json directivePatterns() {
  Json patterns = Json::array();
  patterns.push_back(Json{{"match", "(#define)\\s+([\\p{L}_][\\p{L}\\p{N}_]*)"},
                          {"captures",
                           {{"1", {{"name", "keyword.control.directive.cell"}}},
                            {"2", {{"name", "entity.name.constant.cell"}}}}}});
  for (const Directive& directive : directives()) {
    if (directive.words.empty()) continue;
    // `#music developmental`: the word coloured as a constant.
    std::vector<std::string> words(directive.words.begin(), directive.words.end());
    patterns.push_back(Json{{"match", "(#" + escaped(directive.name) + ")\\s+(" + alternation(words) + ")" + std::string(kAfter)},
                            {"captures",
                             {{"1", {{"name", "keyword.control.directive.cell"}}},
                              {"2", {{"name", "constant.language.cell"}}}}}});
  }
  std::vector<std::string> names;
  for (const Directive& directive : directives()) names.emplace_back(directive.name);
  patterns.push_back(match("#" + alternation(names) + std::string(kAfter), "keyword.control.directive.cell"));
  patterns.push_back(match("#[\\p{L}\\p{N}_]*", "invalid.illegal.directive.cell"));
  return patterns;
}

}  // namespace

std::string textMateGrammar() {
  std::set<std::string> taken;
  Json repository;
  repository["comments"] = {
      {"patterns",
       Json::array({match("//.*$", "comment.line.double-slash.cell"),
                    Json{{"begin", "/\\*"}, {"end", "\\*/"}, {"name", "comment.block.cell"}}})}};
  repository["strings"] = {{"patterns", Json::array({match("\"[^\"\\n]*\"?", "string.quoted.double.cell")})}};
  repository["directives"] = {{"patterns", directivePatterns()}};
  repository["numbers"] = {
      {"patterns", Json::array({match("(?<![\\p{L}\\p{N}_.])(?:\\d+(?:\\.\\d*)?|\\.\\d+)(?:[eE][+-]?\\d+)?",
                                      "constant.numeric.cell")})}};
  repository["arrows"] = {
      {"patterns", Json::array({match("-->|->|→", "keyword.operator.arrow.cell"), match("∅", "constant.language.empty.cell")})}};
  repository["keywords"] = {{"patterns", keywordPatterns(taken)}};

  std::vector<std::string> functions{"if"};
  for (const BuiltinFunction& function : builtinFunctions()) functions.emplace_back(function.name);
  std::vector<std::string> constants;
  for (const BuiltinConstant& constant : builtinConstants()) constants.emplace_back(constant.name);
  std::vector<std::string> scales;
  for (const MusicScale& scale : musicScales()) scales.emplace_back(scale.name);
  repository["builtins"] = {
      {"patterns",
       Json::array({match(std::string(kBefore) + alternation(functions) + "(?=\\s*\\()", "support.function.builtin.cell"),
                    match(std::string(kBefore) + alternation(constants) + std::string(kAfter), "constant.language.cell"),
                    match(std::string(kBefore) + alternation(scales) + std::string(kAfter),
                          "constant.language.scale.cell")})}};
  for (const std::string& name : functions) taken.insert(name);

  repository["commands"] = {
      {"patterns", Json::array({commands(turtleCommands(), taken, "support.function.turtle.cell"),
                                commands(creatureCommands(), taken, "support.function.creature.cell"),
                                commands(physicsCommands(), taken, "support.function.physics.cell"),
                                commands(dynamicsCommands(), taken, "support.function.dynamics.cell"),
                                commands(musicCommands(), taken, "support.function.music.cell")})}};
  repository["operators"] = {
      {"patterns", Json::array({match("[-+*/%^<>=!&|~$@\\\\]+|≤|≥|≠", "keyword.operator.cell")})}};

  Json patterns = Json::array();
  for (const char* part :
       {"comments", "strings", "directives", "numbers", "arrows", "keywords", "builtins", "commands", "operators"})
    patterns.push_back(Json{{"include", std::string("#") + part}});
  Json grammar;
  grammar["name"] = "ontogen cell language";
  grammar["scopeName"] = "source.cell";
  grammar["fileTypes"] = Json::array({"cell"});
  grammar["comment"] = "Generated by `ontogen help --grammar` from the tables `ontogen help` prints; do not edit.";
  grammar["patterns"] = patterns;
  grammar["repository"] = repository;
  return grammar.dump(2) + "\n";
}

}  // namespace ontogen::editors
