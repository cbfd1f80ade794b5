// A writer killed mid-write leaves nothing under the final name: the child process writes a
// large stage file and is killed with SIGKILL at several moments; the final path either does
// not exist or (if the kill came after the rename) holds a complete, valid file.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <thread>

#include "core/atomic_file.hpp"
#include "core/stage_files.hpp"
#include "test_util.hpp"

using namespace finverse;

TEST(AtomicWrite, KilledWriterLeavesNoFinalFile) {
  test::ScratchDir dir;
  const auto motion = test::sample_motion(400, 4000);  // ~77 MB of doubles: takes a while to write
  int killed_before_rename = 0;
  for (int delay_ms : {5, 20, 60}) {
    const auto path = dir / ("m" + std::to_string(delay_ms) + ".h5");
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      auto copy = motion;
      stage::write(path, copy, test::test_provenance());
      _exit(0);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    if (std::filesystem::exists(path)) {
      EXPECT_NO_THROW(stage::read<stage::Motion>(path)) << "a file under the final name must be complete";
    } else {
      ++killed_before_rename;
    }
  }
  EXPECT_GT(killed_before_rename, 0) << "the writer was never interrupted; the test proved nothing";
}

TEST(AtomicWrite, TextWriteReplacesWholeFile) {
  test::ScratchDir dir;
  write_text_atomic(dir / "a/b.json", "first");
  write_text_atomic(dir / "a/b.json", "second");
  EXPECT_EQ(test::slurp(dir / "a/b.json"), "second");
  EXPECT_FALSE(std::filesystem::exists(dir / "a/b.json.tmp"));
}

TEST(AtomicWrite, ExceptionDuringWriteRemovesTemporary) {
  test::ScratchDir dir;
  try {
    auto f = h5::File::create(dir / "x.h5");
    f.write("a", test::wave({10}));
    throw std::runtime_error("producer failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "x.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir / "x.h5.tmp"));
}
