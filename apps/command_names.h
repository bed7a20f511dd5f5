#pragma once
// The names of the ontogen executable's commands, and the nearest of them to a word
// that is none, so that `ontogen chek` answers "did you mean 'check'?" (and a flag's,
// `--stpe`, "did you mean '--step'?").

#include <span>
#include <string>
#include <string_view>

namespace ontogen::app {

/// Every command, in the order help lists them.
std::span<const std::string_view> commandNames();

/// Edits (insertions, deletions, substitutions of one byte) that turn `a` into `b`.
size_t editDistance(std::string_view a, std::string_view b);

/// The candidate nearest to `word` if it is a near miss (at most a third of the word
/// wrong), else empty.
std::string nearMiss(std::string_view word, std::span<const std::string_view> candidates);

/// The message for a first argument that is no command and no flag ("unknown command
/// 'chek'; did you mean 'check'? ..."), or empty when argv names a command.
std::string unknownCommandMessage(int argc, const char* const* argv);

}  // namespace ontogen::app
