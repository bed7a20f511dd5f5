#pragma once
// The table of the cell language's words: its keywords (contextual: the parser reads
// them as identifiers where no keyword can stand, so `cell` or `pool` stay free as
// module labels) and the names a program reads but never declares (`age`, `time`, `me`).
// `ontogen help` prints it and the editors' grammar (editors/text_mate_grammar.h) colours
// it; tests/lang/keywords_test.cpp holds it to the words lang/parser*.cpp and
// lang/compile_context.cpp accept.

#include <span>
#include <string_view>

namespace ontogen {

/// What a word does, which is also how an editor colours it.
enum class KeywordKind {
  Declaration,  ///< opens a block or names a file: cell, lsystem, system, import
  Statement,    ///< begins a statement or section inside a block: axiom, rules, pool ...
  Reference,    ///< a value a program reads and never declares: age, time, me ...
};

/// One row of the table.
struct Keyword {
  std::string_view name;
  KeywordKind kind;
  std::string_view doc;  ///< one line
};

/// Every keyword and reference, declarations first, in the order `ontogen help` lists them.
std::span<const Keyword> keywords();

/// "declaration", "statement", "reference".
std::string_view keywordKindName(KeywordKind kind);

}  // namespace ontogen
