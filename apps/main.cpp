// Entry point of the `relume` command: builds the CLI from the registered subcommands, runs the
// chosen one, and turns every relume::Error into a one-line message and exit status 1.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "command_registry.hpp"
#include "core/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "relume: compress one-light-at-a-time reflectance fields with clustered sparse residual\n"
      "factorization and relight them in real time with OpenCL (PoCL on CPUs, any GPU driver)."};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show help for every command");
  for (const auto& setup : relume::registered_commands()) setup(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const relume::Error& e) {
    std::fprintf(stderr, "relume: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relume: internal error: %s\n", e.what());
    return 2;
  }
  return 0;
}
