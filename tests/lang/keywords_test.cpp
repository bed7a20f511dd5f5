// The keyword table against the words the parser and the compiler really accept: every
// word the parser (lang/parser*.cpp) reads as a keyword is in the table, every statement and
// declaration of the table is read there, and every reference is a name the compiler
// reads (lang/compile_context.cpp) or a scope the parser knows (me, parent, root).

#include "lang/keywords.h"

#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "lang/compile_context.h"

namespace {

using namespace ontogen;

std::string readSource(const std::string& path) {
  std::ifstream in(std::string(ONTOGEN_SOURCE_DIR) + "/" + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool inTable(std::string_view name, KeywordKind kind) {
  for (const Keyword& keyword : keywords())
    if (keyword.name == name && keyword.kind == kind) return true;
  return false;
}

TEST(Keywords, EveryWordTheParserReadsIsInTheTable) {
  // The parser's files (lang/parser_internal.h names them).
  std::string parser;
  for (const char* path : {"lang/parser.cpp", "lang/parser_internal.h", "lang/parser_cells.cpp",
                           "lang/parser_systems.cpp", "lang/parser_expressions.cpp"}) {
    const std::string text = readSource(path);
    ASSERT_FALSE(text.empty()) << path;
    parser += text;
  }
  std::set<std::string> read;
  const std::regex word(R"((?:checkWord\(|peek\(\d\)\.text == )\"([a-z]+)\")");
  for (auto it = std::sregex_iterator(parser.begin(), parser.end(), word); it != std::sregex_iterator(); ++it)
    read.insert((*it)[1]);
  EXPECT_GE(read.size(), 25u);
  for (const std::string& name : read)
    EXPECT_TRUE(inTable(name, KeywordKind::Declaration) || inTable(name, KeywordKind::Statement)) << name;
  for (const Keyword& keyword : keywords()) {
    EXPECT_FALSE(keyword.doc.empty()) << keyword.name;
    if (keyword.kind != KeywordKind::Reference) {
      EXPECT_TRUE(read.count(std::string(keyword.name))) << keyword.name;
    }
  }
}

TEST(Keywords, EveryReferenceIsANameTheCompilerReads) {
  int references = 0;
  for (const Keyword& keyword : keywords()) {
    if (keyword.kind != KeywordKind::Reference) continue;
    ++references;
    const bool scope = keyword.name == "me" || keyword.name == "parent" || keyword.name == "root";
    EXPECT_TRUE(scope || detail::isReadOnlyName(keyword.name)) << keyword.name;
  }
  EXPECT_EQ(references, 12);
  for (std::string_view name : {"age", "tau", "τ", "beta", "β", "lifetime", "time", "status", "id"})
    EXPECT_TRUE(inTable(name, KeywordKind::Reference)) << name;
}

}  // namespace
