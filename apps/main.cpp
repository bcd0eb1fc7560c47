// Entry point of the `relume` command: builds the CLI from the registered subcommands, handles
// the front door (--version, `relume help CMD`, unknown commands, the global -q/-v), runs the
// chosen command and turns every failure into a one-line `relume:` message and an exit status:
//   0  success
//   1  an error in the input or the work (a relume::Error, a failed allocation, ...)
//   2  a usage error (unknown command or option, bad option value)
//   130 / 143  interrupted by SIGINT / SIGTERM (core/signals.hpp): nothing half-written is left
#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <new>
#include <relume/error.hpp>
#include <relume/version.hpp>
#include <string>
#include <vector>

#include "command_registry.hpp"
#include "command_suggestion.hpp"
#include "core/console.hpp"
#include "core/elapsed_time.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "core/signals.hpp"
#include "options/finite_numbers.hpp"
#include "options/output_paths.hpp"
#ifdef RELUME_HAVE_MPI
#include "commands/compress/mpi_ranks.hpp"
#endif

namespace {

constexpr int exit_usage = 2;

std::vector<std::string> command_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands({})) names.push_back(command->get_name());
  return names;
}

// The global option that takes a value (its value is not the command's name).
constexpr const char* memory_limit_option = "--memory-limit";

// The first argument that is not an option or a global option's value: the command's name, or ""
// when there is none.
std::string first_word(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == memory_limit_option) {
      ++i;
      continue;
    }
    if (argv[i][0] != '-') return argv[i];
  }
  return "";
}

// `relume help [CMD]`: the help of the whole command or of one subcommand.
int print_help(CLI::App& app, int argc, char** argv) {
  std::string name;
  for (int i = 1; i < argc; ++i)
    if (argv[i][0] != '-' && std::string(argv[i]) != "help") {
      name = argv[i];
      break;
    }
  if (name.empty()) {
    std::printf("%s", app.help().c_str());
    return 0;
  }
  try {
    std::printf("%s", app.get_subcommand(name)->help("relume").c_str());
    return 0;
  } catch (const CLI::OptionNotFound&) {
    std::fprintf(stderr, "relume: %s\n",
                 relume::unknown_command_message(name, command_names(app)).c_str());
    return exit_usage;
  }
}

// Every --threads option has the same bound (core/parallel.hpp), checked while parsing.
void bound_thread_options(CLI::App& app) {
  for (CLI::App* command : app.get_subcommands({}))
    if (CLI::Option* threads = command->get_option_no_throw("--threads"))
      threads->check(CLI::Range(0u, relume::max_worker_threads));
}

// The message of an exception that is not a relume::Error: the standard library's own errors,
// with the file or the need named where the exception knows it.
std::string failure_message(const std::exception& e) {
  if (const auto* fs_error = dynamic_cast<const std::filesystem::filesystem_error*>(&e)) {
    std::string message = fs_error->code().message();
    for (const auto* path : {&fs_error->path1(), &fs_error->path2()})
      if (!path->empty()) message += ": " + path->string();
    return "error: " + message;
  }
  if (dynamic_cast<const std::bad_alloc*>(&e)) {
    const relume::MemoryBudget budget = relume::memory_budget();
    return "error: out of memory (" + relume::byte_size_text(budget.bytes) + " available now, " +
           budget.source +
           "): the input is too large for this machine, or --memory-limit is set "
           "too high";
  }
  return std::string("internal error: ") + e.what();
}

// What messages begin with: "relume", or under mpirun "relume (rank 2 of 3)".
std::string speaker = "relume";

// 128 + the signal that interrupted the run (130 for SIGINT, 143 for SIGTERM).
int interrupted_exit() {
  const int signal_number = relume::interrupting_signal();
  std::fprintf(stderr, "%s: interrupted (%s); no output was half-written\n", speaker.c_str(),
               signal_number == SIGTERM ? "SIGTERM" : "SIGINT");
  return 128 + (signal_number ? signal_number : SIGINT);
}

}  // namespace

// Parses the command line and runs the command; returns the exit status.
int run(int argc, char** argv) {
  CLI::App app{
      "relume: compress one-light-at-a-time reflectance fields with clustered sparse residual\n"
      "factorization and relight them in real time with OpenCL (PoCL on CPUs, any GPU driver).\n"
      "Example: relume synth -o scene && relume compress scene -o scene.relume &&\n"
      "         relume relight scene.relume --env sky.exr -o relit.png\n"
      "Run `relume help COMMAND` for a command's options. Exit status: 0 success, 1 error in the\n"
      "input or the work, 2 usage error.",
      "relume"};
  app.require_subcommand(1);
  app.fallthrough();  // the global flags also work after the command's name
  app.set_help_all_flag("--help-all", "Show help for every command");
  app.set_version_flag("--version", relume::version_line(), "Print the version and git commit");
  // Flag callbacks run before the command's callback, so the command sees the verbosity.
  auto* quiet = app.add_flag_callback(
      "-q,--quiet", [] { relume::set_verbosity(relume::Verbosity::quiet); },
      "Print only errors and the results asked for: no progress, notes or summaries "
      "(RELUME_QUIET=1 silences only the progress bars)");
  app.add_flag_callback(
         "-v,--verbose",
         [] {
           relume::set_verbosity(relume::Verbosity::verbose);
           relume::detail("%s", relume::version_line().c_str());
         },
         "Also print settings as resolved and timings")
      ->excludes(quiet);
  app.add_flag_callback(
      "-y,--overwrite", [] { relume::allow_overwrite(); },
      "Replace existing output files and write into non-empty output folders "
      "(without it, a command refuses them before it starts work)");
  app.add_option_function<std::string>(
      memory_limit_option,
      [](const std::string& size) {
        try {
          relume::set_memory_limit(relume::parse_byte_size(size));
        } catch (const relume::Error& e) {
          throw CLI::ValidationError("--memory-limit", e.what());
        }
      },
      "Refuse work estimated to need more memory than this (for example 8G or 512M; default: "
      "the memory available, within the cgroup and ulimit limits)");
  for (const auto& setup : relume::registered_commands()) setup(app);
  bound_thread_options(app);
  relume::refuse_non_finite_numbers(app);

  const std::string word = first_word(argc, argv);
  if (word == "help") return print_help(app, argc, argv);
  if (argc == 1) {
    std::printf("%s", app.help().c_str());
    return exit_usage;
  }
  const std::vector<std::string> names = command_names(app);
  if (!word.empty() && std::find(names.begin(), names.end(), word) == names.end()) {
    std::fprintf(stderr, "relume: %s\n", relume::unknown_command_message(word, names).c_str());
    return exit_usage;
  }

  const auto start = relume::Clock::now();
  try {
    relume::install_interruption_handlers();
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --help-all, --version
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "relume: %s\n", e.what());
    std::fprintf(stderr, "Run `relume help%s%s` for the options.\n", word.empty() ? "" : " ",
                 word.c_str());
    return exit_usage;
  } catch (const relume::Interrupted&) {
    return interrupted_exit();
  } catch (const relume::Error& e) {
    if (relume::interrupting_signal()) return interrupted_exit();
    std::fprintf(stderr, "%s: error: %s\n", speaker.c_str(), e.what());
    return 1;
  } catch (const std::exception& e) {
    if (relume::interrupting_signal()) return interrupted_exit();
    std::fprintf(stderr, "%s: %s\n", speaker.c_str(), failure_message(e).c_str());
    return 1;
  }
  if (relume::interrupting_signal()) return interrupted_exit();
  relume::detail("relume: %s done in %.2f s", word.c_str(), relume::seconds_since(start));
  return 0;
}

int main(int argc, char** argv) {
#ifdef RELUME_HAVE_MPI
  // Under mpirun the ranks run the same command; rank 0 speaks, the others only of failures, and
  // a failure on any rank ends them all with its message (the others would wait for it).
  relume::MpiRun mpi(&argc, &argv);
  if (mpi.several()) {
    speaker =
        "relume (rank " + std::to_string(mpi.rank()) + " of " + std::to_string(mpi.size()) + ")";
    if (mpi.rank() != 0) relume::set_verbosity(relume::Verbosity::quiet);
  }
  const int status = run(argc, argv);
  if (status != 0 && mpi.several()) {
    std::fflush(stderr);
    mpi.abort_all(status);
  }
  return status;
#else
  return run(argc, argv);
#endif
}
