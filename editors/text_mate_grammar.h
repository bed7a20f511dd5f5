#pragma once
// `ontogen help --grammar`: a TextMate grammar of the cell language (JSON, as VS Code,
// Sublime Text, Atom's successors and GitHub's Linguist read them), generated from the
// tables `ontogen help` prints: the keywords (lang/keywords.h), the directives
// (lang/directives.h), the built-in functions and constants (model/builtins.h), the
// commands of the turtle, creature, dynamics, physics and music sets and the music set's scale
// names. editors/vscode/syntaxes/cell.tmLanguage.json is a copy of its output
// (tests/editors/text_mate_grammar_test.cpp keeps the two equal).
//
// A grammar colours by regular expressions, line by line, without the parser's context,
// so it colours a word by what it usually is: `at` as a keyword (also a music command),
// `F` as a turtle command, the one-letter keyword `g` only where a name follows it.
// Commands spelt with symbols (+ - [ ] & ^ ...) are coloured as operators.

#include <string>

namespace ontogen::editors {

/// The grammar as pretty-printed JSON (two spaces, keys in a fixed order, a final
/// newline): the same bytes from the same tables.
std::string textMateGrammar();

}  // namespace ontogen::editors
