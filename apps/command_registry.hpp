// Self-registration of `relume` subcommands: each *_command.cpp defines a static
// CommandRegistration that adds its CLI11 subcommand, so main.cpp never lists commands by hand.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace relume {

using CommandSetup = std::function<void(CLI::App& app)>;

struct CommandRegistration {
  CommandRegistration(int order, CommandSetup setup);
};

// Setups in ascending order (the order they appear in `relume --help`).
std::vector<CommandSetup> registered_commands();

}  // namespace relume
