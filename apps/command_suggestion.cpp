// Implementation of the unknown-command message and its suggestion.
#include "command_suggestion.hpp"

#include <algorithm>
#include <numeric>

namespace relume {

int edit_distance(const std::string& a, const std::string& b) {
  std::vector<int> previous(b.size() + 1), current(b.size() + 1);
  std::iota(previous.begin(), previous.end(), 0);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = int(i);
    for (std::size_t j = 1; j <= b.size(); ++j)
      current[j] = std::min(
          {previous[j] + 1, current[j - 1] + 1, previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
    std::swap(previous, current);
  }
  return previous[b.size()];
}

std::string unknown_command_message(const std::string& word,
                                    const std::vector<std::string>& known) {
  std::string message = "unknown command '" + word + "'";
  std::string nearest;
  int best = 0;
  for (const std::string& name : known) {
    const int distance = edit_distance(word, name);
    if (nearest.empty() || distance < best) nearest = name, best = distance;
  }
  // A typo changes a few letters; further than half the word is a different word.
  if (!nearest.empty() && best <= std::max<int>(2, int(word.size()) / 2))
    message += "; did you mean '" + nearest + "'?";
  return message + " (`relume --help` lists the commands)";
}

}  // namespace relume
