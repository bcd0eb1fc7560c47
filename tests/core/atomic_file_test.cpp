// Tests of atomic writes under faults: an interruption (a real SIGINT through the command's
// handler) while a file is written keeps the previous file and leaves no temporary; a second
// signal unlinks the registered temporary and exits 130; stale temporaries of dead processes are
// removed by the next write; folders are written whole or not at all; a full disk (a file-size
// limit) is an Error naming the target; output locations are checked before any work (a file
// where a folder should be, and a folder that takes no files, are named).
#include "core/atomic_file.hpp"

#include <signal.h>
#include <sys/resource.h>

#include <filesystem>
#include <fstream>
#include <relume/error.hpp>

#include "core/interruption.hpp"
#include "core/signals.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string contents(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// The names in `folder` that start with ".tmp-".
std::vector<std::string> temporaries(const fs::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(folder))
    if (entry.path().filename().string().starts_with(".tmp-"))
      names.push_back(entry.path().filename().string());
  return names;
}

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

TEST(AtomicFileFaults, SigintWhileWritingKeepsThePreviousFile) {
  testing::TempDir dir;
  const fs::path target = dir / "out.bin";
  write_file_atomically(target, "old");
  EXPECT_EXIT(
      {
        install_interruption_handlers();
        try {
          write_atomically(target, [&](const fs::path& temp) {
            write_text(temp, "new, half written");
            ::raise(SIGINT);  // arrives while the temporary exists, as a Ctrl-C would
          });
        } catch (const Interrupted&) {
          std::exit(interrupting_signal() == SIGINT ? 42 : 1);
        }
        std::exit(2);
      },
      ::testing::ExitedWithCode(42), "stopping at the next safe point");
  EXPECT_EQ(contents(target), "old");
  EXPECT_THAT(temporaries(dir.path()), ::testing::IsEmpty());
}

TEST(AtomicFileFaults, SecondSignalUnlinksTheTemporaryAndExits) {
  testing::TempDir dir;
  const fs::path target = dir / "out.bin";
  EXPECT_EXIT(
      {
        install_interruption_handlers();
        write_atomically(target, [&](const fs::path& temp) {
          write_text(temp, "half written");
          ::raise(SIGTERM);  // first: interruption requested; this work does not check it
          ::raise(SIGTERM);  // second: the handler unlinks the temporary and exits at once
        });
        std::exit(2);
      },
      ::testing::ExitedWithCode(128 + SIGTERM), "stopped at once");
  EXPECT_FALSE(fs::exists(target));
  EXPECT_THAT(temporaries(dir.path()), ::testing::IsEmpty());
}

TEST(AtomicFileFaults, StaleTemporariesOfDeadProcessesAreRemoved) {
  testing::TempDir dir;
  const fs::path target = dir / "scene.relume";
  // pid 2147483647 runs nowhere (above any pid_max); pid 1 always runs.
  write_text(dir / ".tmp-2147483647-scene.relume", "left by a killed run");
  fs::create_directory(dir / ".tmp-2147483646-scene.relume");
  write_text(dir / ".tmp-2147483646-scene.relume" / "001.exr", "a killed folder write");
  write_text(dir / ".tmp-1-scene.relume", "a running process's");
  write_text(dir / ".tmp-2147483647-other.relume", "another target's");
  write_file_atomically(target, "new");
  EXPECT_EQ(contents(target), "new");
  EXPECT_FALSE(fs::exists(dir / ".tmp-2147483647-scene.relume"));
  EXPECT_FALSE(fs::exists(dir / ".tmp-2147483646-scene.relume"));
  EXPECT_TRUE(fs::exists(dir / ".tmp-1-scene.relume"));
  EXPECT_TRUE(fs::exists(dir / ".tmp-2147483647-other.relume"));
}

TEST(AtomicFileFaults, FolderIsWrittenWholeOrNotAtAll) {
  testing::TempDir dir;
  const fs::path target = dir / "nested" / "field";
  EXPECT_THROW(write_folder_atomically(target,
                                       [&](const fs::path& temp) {
                                         write_file_atomically(temp / "001.exr", "image");
                                         throw Error("disk full");
                                       }),
               Error);
  EXPECT_FALSE(fs::exists(target));
  EXPECT_THAT(temporaries(dir.path()), ::testing::IsEmpty());

  write_folder_atomically(
      target, [&](const fs::path& temp) { write_file_atomically(temp / "001.exr", "first"); });
  EXPECT_EQ(contents(target / "001.exr"), "first");
  // Into an existing folder: entries of the same names are replaced, others kept.
  write_text(target / "notes.txt", "kept");
  fs::create_directories(target / "data");
  write_text(target / "data" / "old.bin", "stale");
  write_folder_atomically(target.string() + "/", [&](const fs::path& temp) {
    write_file_atomically(temp / "001.exr", "second");
    fs::create_directories(temp / "data");
    write_file_atomically(temp / "data" / "new.bin", "fresh");
  });
  EXPECT_EQ(contents(target / "001.exr"), "second");
  EXPECT_EQ(contents(target / "notes.txt"), "kept");
  // A folder of the same name is replaced whole: none of the old one's files stay.
  EXPECT_EQ(contents(target / "data" / "new.bin"), "fresh");
  EXPECT_FALSE(fs::exists(target / "data" / "old.bin"));
  EXPECT_THAT(temporaries(dir.path()), ::testing::IsEmpty());
}

TEST(AtomicFileFaults, FullDiskIsAnErrorNamingTheTarget) {
  testing::TempDir dir;
  const fs::path target = dir / "big.bin";
  // A file-size limit stands in for a full disk: writes past it fail (SIGXFSZ ignored).
  EXPECT_EXIT(
      {
        ::signal(SIGXFSZ, SIG_IGN);
        rlimit limit;
        limit.rlim_cur = limit.rlim_max = 64 << 10;
        ::setrlimit(RLIMIT_FSIZE, &limit);
        try {
          write_file_atomically(target, std::string(1 << 20, 'x'));
        } catch (const Error& e) {
          std::fprintf(stderr, "%s\n", e.what());
          std::exit(42);
        }
        std::exit(1);
      },
      ::testing::ExitedWithCode(42), "cannot write .*big.bin: File too large");
  EXPECT_FALSE(fs::exists(target));
  EXPECT_THAT(temporaries(dir.path()), ::testing::IsEmpty());
}

TEST(AtomicFileFaults, OutputLocationsAreCheckedBeforeWork) {
  testing::TempDir dir;
  EXPECT_THAT(testing::error_message([&] { check_output_file_location(dir / "no" / "x.exr"); }),
              HasSubstr("does not exist"));
  EXPECT_THAT(testing::error_message([&] { check_output_file_location(dir.path()); }),
              HasSubstr("it is a folder"));
  write_text(dir / "file", "");
  EXPECT_THAT(testing::error_message([&] { check_output_folder_location(dir / "file"); }),
              HasSubstr("a file of that name exists"));
  EXPECT_THAT(testing::error_message([&] { check_output_folder_location(dir / "file" / "sub"); }),
              HasSubstr("is not a folder"));
  EXPECT_NO_THROW(check_output_folder_location(dir / "new" / "deeper"));
  EXPECT_NO_THROW(check_output_file_location(dir / "x.exr"));
  EXPECT_THAT(temporaries(dir.path()), ::testing::IsEmpty()) << "the probe files are removed";
}

// `-o plainfile/x.relume` said that the folder did not exist; `-o /proc/x.relume` passed (access()
// lets root write anywhere) and failed after the field was loaded.
TEST(AtomicFileFaults, AFileForAFolderAndAFolderThatTakesNoFilesAreNamed) {
  testing::TempDir dir;
  write_text(dir / "plainfile", "");
  EXPECT_EQ(testing::error_message([&] { check_output_file_location(dir / "plainfile" / "x.relume"); }),
            "cannot write " + (dir / "plainfile" / "x.relume").string() + ": " +
                (dir / "plainfile").string() + " is a file, not a folder");
  EXPECT_THAT(testing::error_message([] { check_output_file_location("/proc/x.relume"); }),
              HasSubstr("cannot write /proc/x.relume: folder /proc is not writable ("));
  EXPECT_THAT(testing::error_message([] { check_output_folder_location("/proc/out"); }),
              HasSubstr("cannot write the folder /proc/out: folder /proc is not writable ("));
}

}  // namespace
}  // namespace relume
