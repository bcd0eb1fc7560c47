// The message for a command name that `relume` does not know: it names the word and suggests the
// nearest known command (by edit distance) when one is close enough to be a typo.
#pragma once

#include <string>
#include <vector>

namespace relume {

// Levenshtein distance: insertions, deletions and substitutions, each costing 1.
int edit_distance(const std::string& a, const std::string& b);

// "unknown command 'compres'; did you mean 'compress'? (`relume --help` lists the commands)".
std::string unknown_command_message(const std::string& word, const std::vector<std::string>& known);

}  // namespace relume
