#pragma once
// `ontogen help --reference`: docs/COMMANDS.md, the reference of every interpretation
// set's commands in Markdown, generated from the sets' command tables as `ontogen help`
// and the editors' grammar are (a row per command: its signature, the argument counts
// the compiler accepts, its one-line doc). docs/LANGUAGE.md says what the sets mean and
// links here for their commands; tests/editors/command_reference_test.cpp keeps the
// committed copy equal to what the tables make.

#include <string>

namespace ontogen::editors {

/// The reference as Markdown, a final newline: the same bytes from the same tables.
std::string commandReference();

}  // namespace ontogen::editors
