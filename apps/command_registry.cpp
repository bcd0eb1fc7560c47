// Storage for the self-registered subcommands.
#include "command_registry.hpp"

#include <algorithm>
#include <utility>

namespace relume {
namespace {
std::vector<std::pair<int, CommandSetup>>& registry() {
  static std::vector<std::pair<int, CommandSetup>> commands;
  return commands;
}
}  // namespace

CommandRegistration::CommandRegistration(int order, CommandSetup setup) {
  registry().emplace_back(order, std::move(setup));
}

std::vector<CommandSetup> registered_commands() {
  auto sorted = registry();
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<CommandSetup> setups;
  for (auto& [order, setup] : sorted) setups.push_back(setup);
  return setups;
}

}  // namespace relume
