// Fault tests of `relume compress` under SIGINT and SIGTERM, sent by the test to the running
// command: during clustering (once its first checkpoint exists) and during the final write (the
// moment the container's temporary file is created, seen with inotify). Each run must exit 128 +
// the signal, leave no temporary file (the streamed plan's scratch file included), and either a
// complete container or a valid checkpoint from which --resume writes the same bytes as an
// uninterrupted run. Both plans are tried: in memory, and streamed under a memory limit. A run
// asked for 100,000 clusters stops within 2 s of the signal while it seeds them.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/inotify.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <regex>
#include <string_view>
#include <thread>

#include "core/atomic_file.hpp"
#include "core/memory_budget.hpp"
#include "support/test_support.hpp"

extern char** environ;

namespace relume {
namespace {

namespace fs = std::filesystem;
using testing::run_relume;

const std::vector<std::string> compress_options = {"--clusters",   "12", "--terms",    "3",
                                                   "--iterations", "25", "--assign",   "cpu",
                                                   "--threads",    "2",  "--residual", "3"};

// A memory limit under which the 40x40x20 scene is compressed streamed, in strips of 2 rows.
const std::string streamed_limit = "800K";

// Starts `relume ARGS` (args[0] is the binary), its output in dir/log.txt.
// With `progress`, the child prints its progress lines even when RELUME_QUIET is set around the
// test run (scripts/test.sh sets it, so CI does).
pid_t start_relume(const testing::TempDir& dir, std::vector<std::string> args,
                   bool progress = false) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> variables;
  for (char** variable = environ; *variable; ++variable)
    if (!std::string_view(*variable).starts_with("RELUME_QUIET=") || !progress)
      variables.emplace_back(*variable);
  if (progress) variables.emplace_back("RELUME_QUIET=0");
  std::vector<char*> envp;
  for (auto& v : variables) envp.push_back(v.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  const std::string log = (dir / "log.txt").string();
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  EXPECT_EQ(posix_spawn(&pid, RELUME_BINARY, &actions, nullptr, argv.data(), envp.data()), 0);
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

// Starts `relume [--memory-limit L] compress scene -o out [--resume]` in `dir`, its output in
// dir/log.txt.
pid_t start_compress(const testing::TempDir& dir, bool resume, bool streamed) {
  std::vector<std::string> args = {RELUME_BINARY, "-q"};
  if (streamed) args.insert(args.end(), {"--memory-limit", streamed_limit});
  args.insert(args.end(),
              {"compress", (dir / "scene").string(), "-o", (dir / "out.relume").string()});
  args.insert(args.end(), compress_options.begin(), compress_options.end());
  if (resume) args.push_back("--resume");
  return start_relume(dir, args);
}

int wait_exit(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
}

std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().filename().string().starts_with(".tmp-"))
      names.push_back(entry.path().filename().string());
  return names;
}

template <bool Streamed>
class Interruption : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    reference_dir_ = new testing::TempDir;
    const auto synth = run_relume("-q synth -o '" + (*reference_dir_ / "scene").string() +
                                  "' --size 40x40 --lights 20 --samples 1");
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
    std::string line;
    for (const auto& o : compress_options) line += " " + o;
    const std::string global = Streamed ? "--memory-limit " + streamed_limit + " " : "";
    const auto run =
        run_relume(global + "compress '" + (*reference_dir_ / "scene").string() + "' -o '" +
                   (*reference_dir_ / "reference.relume").string() + "'" + line);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    ASSERT_NE(run.output.find(Streamed ? "plan: streamed" : "plan: in memory"), std::string::npos)
        << run.output;
    reference_ = new std::string(read_file(*reference_dir_ / "reference.relume"));
  }
  static void TearDownTestSuite() {
    delete reference_;
    delete reference_dir_;
  }

  // A fresh folder with a copy of the scene.
  void SetUp() override {
    fs::copy(*reference_dir_ / "scene", dir_ / "scene", fs::copy_options::recursive);
  }

  // After an interrupted run: no temporary; a complete container equal to the reference, or
  // none and a checkpoint that --resume completes into the reference.
  void expect_nothing_half_written() {
    EXPECT_THAT(temporaries(dir_.path()), ::testing::IsEmpty());
    if (!fs::exists(dir_ / "out.relume")) {
      ASSERT_TRUE(fs::exists(dir_ / "out.relume.checkpoint")) << read_file(dir_ / "log.txt");
      EXPECT_EQ(wait_exit(start_compress(dir_, true, Streamed)), 0) << read_file(dir_ / "log.txt");
      EXPECT_FALSE(fs::exists(dir_ / "out.relume.checkpoint"));
    }
    EXPECT_TRUE(read_file(dir_ / "out.relume") == *reference_)
        << "the resumed container differs from the uninterrupted run's";
  }

  void interrupt_during_clustering(int signal_number) {
    const pid_t pid = start_compress(dir_, false, Streamed);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(dir_ / "out.relume.checkpoint") &&
           std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_TRUE(fs::exists(dir_ / "out.relume.checkpoint"));
    kill(pid, signal_number);
    EXPECT_EQ(wait_exit(pid), 128 + signal_number) << read_file(dir_ / "log.txt");
    EXPECT_FALSE(fs::exists(dir_ / "out.relume")) << "the run ended before the signal";
    expect_nothing_half_written();
  }

  void interrupt_during_final_write(int signal_number) {
    const int watch = inotify_init1(IN_CLOEXEC);
    ASSERT_GE(watch, 0);
    inotify_add_watch(watch, dir_.path().c_str(), IN_CREATE);
    const pid_t pid = start_compress(dir_, false, Streamed);
    const std::string container_temp = ".tmp-" + std::to_string(pid) + "-out.relume";
    alignas(inotify_event) char buffer[4096];
    for (bool seen = false; !seen;) {
      const ssize_t n = read(watch, buffer, sizeof buffer);
      ASSERT_GT(n, 0);
      for (char* p = buffer; p < buffer + n;) {
        const auto* event = reinterpret_cast<const inotify_event*>(p);
        if (event->len > 0 && container_temp == event->name) seen = true;
        p += sizeof(inotify_event) + event->len;
      }
    }
    kill(pid, signal_number);
    close(watch);
    EXPECT_EQ(wait_exit(pid), 128 + signal_number) << read_file(dir_ / "log.txt");
    std::printf("signal %d during the final write: %s\n", signal_number,
                fs::exists(dir_ / "out.relume")
                    ? "the write had completed (the container is kept)"
                    : "the write was discarded (resumed from the checkpoint)");
    expect_nothing_half_written();
  }

  testing::TempDir dir_;
  static testing::TempDir* reference_dir_;
  static std::string* reference_;
};

template <bool Streamed>
testing::TempDir* Interruption<Streamed>::reference_dir_ = nullptr;
template <bool Streamed>
std::string* Interruption<Streamed>::reference_ = nullptr;

using CompressInterruption = Interruption<false>;
using StreamedCompressInterruption = Interruption<true>;

// `--clusters 100000` seeded its clusters one by one for minutes without looking at the first
// signal, and printed nothing with -v. A 120 x 100 scene has at most 36,000 functions: the run
// warns that they fill far fewer clusters, reports the seeding's progress, and a signal sent
// while it seeds ends it within 2 s.
class ManyClustersInterruption : public ::testing::TestWithParam<int> {
 protected:
  static void SetUpTestSuite() {
    scene_dir_ = new testing::TempDir;
    const auto synth = run_relume("-q synth -o '" + (*scene_dir_ / "scene").string() +
                                  "' --size 120x100 --lights 20 --samples 1");
    ASSERT_EQ(synth.exit_code, 0) << synth.output;
  }
  static void TearDownTestSuite() { delete scene_dir_; }
  static testing::TempDir* scene_dir_;
};

testing::TempDir* ManyClustersInterruption::scene_dir_ = nullptr;

TEST_P(ManyClustersInterruption, SeedingStopsWithinTwoSecondsOfTheSignal) {
  const int signal_number = GetParam();
  testing::TempDir dir;
  const pid_t pid = start_relume(
      dir, {RELUME_BINARY, "-v", "compress", (*scene_dir_ / "scene").string(), "-o",
            (dir / "out.relume").string(), "--clusters", "100000", "--terms", "2", "--assign",
            "cpu", "--threads", "2", "--noise-floor", "0"},
      /*progress=*/true);
  // The warning comes before the seeding, and its progress line (every 5 s off a terminal)
  // during it.
  const std::string warning = "100000 clusters are more than ";
  const std::string seeding = "compress: seeding clusters: ";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (read_file(dir / "log.txt").find(seeding) == std::string::npos &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const std::string log = read_file(dir / "log.txt");
  ASSERT_NE(log.find(seeding), std::string::npos) << log;
  EXPECT_LT(log.find(warning), log.find(seeding)) << log;
  // Its memory so far within 1.5 times the plan (the 100,000 clusters' state counted in it).
  std::smatch plan;
  ASSERT_TRUE(std::regex_search(
      log, plan, std::regex("needs about ([0-9.]+) ([KMG]B) on top of the ([0-9.]+) ([KMG]B)")))
      << log;
  const double planned = double(parse_byte_size(plan[1].str() + plan[2].str())) +
                         double(parse_byte_size(plan[3].str() + plan[4].str()));
  std::ifstream process_status("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(process_status, line) && !line.starts_with("VmHWM:")) {
  }
  const double peak = 1024.0 * std::stod(line.substr(6));
  EXPECT_LT(peak, 1.5 * planned) << log;
  const auto sent = std::chrono::steady_clock::now();
  kill(pid, signal_number);
  const int status = wait_exit(pid);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  EXPECT_EQ(status, 128 + signal_number) << read_file(dir / "log.txt");
  EXPECT_LT(seconds, 2.0) << read_file(dir / "log.txt");
  EXPECT_FALSE(fs::exists(dir / "out.relume"));
  EXPECT_THAT(temporaries(dir.path()), ::testing::IsEmpty());
}

INSTANTIATE_TEST_SUITE_P(Signals, ManyClustersInterruption, ::testing::Values(SIGINT, SIGTERM));

TEST_F(CompressInterruption, SigintDuringClustering) { interrupt_during_clustering(SIGINT); }
TEST_F(CompressInterruption, SigtermDuringClustering) { interrupt_during_clustering(SIGTERM); }
TEST_F(CompressInterruption, SigintDuringTheFinalWrite) { interrupt_during_final_write(SIGINT); }
TEST_F(CompressInterruption, SigtermDuringTheFinalWrite) { interrupt_during_final_write(SIGTERM); }
TEST_F(StreamedCompressInterruption, SigintDuringClustering) {
  interrupt_during_clustering(SIGINT);
}
TEST_F(StreamedCompressInterruption, SigtermDuringTheFinalWrite) {
  interrupt_during_final_write(SIGTERM);
}

}  // namespace
}  // namespace relume
