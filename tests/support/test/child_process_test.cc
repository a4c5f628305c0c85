#include "hubrt/test_support/child_process.h"

#include <signal.h>
#include <stdlib.h>

#include <cerrno>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <thread>

#include <gtest/gtest.h>

namespace hubrt::test_support {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

// Bounds below are generous on purpose: they only cover process start-up and shell work on a
// busy 2-core machine; the tests wait on events, not on time.
constexpr Duration kStartup = seconds(10);

TEST(ChildProcess, CapturesStdoutAndStderrSeparately) {
  auto child = ChildProcess::start("/bin/sh", {"-c", "echo to-out; echo to-err >&2"});
  ASSERT_TRUE(child) << child.error().message;
  auto status = child->wait(kStartup);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe();
  EXPECT_EQ(child->stdout_text(), "to-out\n");
  EXPECT_EQ(child->stderr_text(), "to-err\n");
}

TEST(ChildProcess, ReportsExitCode) {
  auto child = ChildProcess::start("sh", {"-c", "exit 3"});
  ASSERT_TRUE(child) << child.error().message;
  auto status = child->wait(kStartup);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(3)) << status->describe();
  EXPECT_FALSE(status->term_signal.has_value());
}

// OutputMode::kClosedPipe: writing ends the child with SIGPIPE unless it ignores it, then the
// write fails with EPIPE ("write error" from the shell's echo, which itself goes nowhere).
TEST(ChildProcess, AClosedPipeOutputFailsEveryWrite) {
  auto killed = ChildProcess::start("/bin/sh", {"-c", "echo lost"}, {}, OutputMode::kClosedPipe);
  ASSERT_TRUE(killed) << killed.error().message;
  auto status = killed->wait(kStartup);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->killed_by(SIGPIPE)) << status->describe();

  auto ignoring = ChildProcess::start("/bin/sh", {"-c", "trap '' PIPE; echo lost || exit 7; exit 0"}, {},
                                      OutputMode::kClosedPipe);
  ASSERT_TRUE(ignoring) << ignoring.error().message;
  status = ignoring->wait(kStartup);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(7)) << status->describe();
  EXPECT_EQ(ignoring->stdout_text(), "");
}

TEST(ChildProcess, PassesExtraEnvironmentAndOverridesExistingVariables) {
  auto child = ChildProcess::start("/bin/sh", {"-c", "echo \"$HUBRT_CHILD_TEST|$HOME\""},
                                   {{"HUBRT_CHILD_TEST", "hello"}, {"HOME", "/nowhere"}});
  ASSERT_TRUE(child) << child.error().message;
  ASSERT_TRUE(child->wait(kStartup));
  EXPECT_EQ(child->stdout_text(), "hello|/nowhere\n");
}

TEST(ChildProcess, WaitsForOutputThenStopsWithSigterm) {
  // exec: the shell becomes sleep, so SIGTERM reaches the process we wait for.
  auto child = ChildProcess::start("/bin/sh", {"-c", "echo ready; exec sleep 600"});
  ASSERT_TRUE(child) << child.error().message;
  EXPECT_TRUE(child->wait_for_output("ready", kStartup)) << child->stderr_text();
  auto still_running = child->wait(milliseconds(0));
  ASSERT_FALSE(still_running);
  EXPECT_EQ(still_running.error().code, ErrorCode::kTimeout);
  ASSERT_TRUE(child->signal(SIGTERM));
  auto status = child->wait(kStartup);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->killed_by(SIGTERM)) << status->describe();
  // Reaped: neither signal nor wait may touch the pid again.
  EXPECT_EQ(child->signal(SIGTERM).error().code, ErrorCode::kFailedPrecondition);
}

TEST(ChildProcess, WaitForOutputGivesUpWhenTheChildExitsWithoutIt) {
  auto child = ChildProcess::start("/bin/sh", {"-c", "echo something-else"});
  ASSERT_TRUE(child) << child.error().message;
  const auto start = std::chrono::steady_clock::now();
  // A long timeout that must not be used up: the child's exit ends the wait.
  EXPECT_FALSE(child->wait_for_output("ready", seconds(60)));
  EXPECT_LT(std::chrono::steady_clock::now() - start, seconds(30));
}

TEST(ChildProcess, WaitForOutputTimesOutWhileTheChildIsSilent) {
  auto child = ChildProcess::start("/bin/sh", {"-c", "exec sleep 600"});
  ASSERT_TRUE(child) << child.error().message;
  EXPECT_FALSE(child->wait_for_output("ready", milliseconds(50)));
}

// What a failure message says about a child a wait gave up on: a blocked one sleeps (state S), a
// busy one runs (R) and has used CPU; an ended one is told apart from both.
TEST(ChildProcess, ActivityTellsASleepingChildFromABusyOneAndAnEndedOne) {
  // `child`'s activity once `settled` holds for it, or the last one after kStartup.
  const auto activity_once = [](const ChildProcess& child, const auto& settled) {
    std::string activity;
    for (const auto deadline = std::chrono::steady_clock::now() + kStartup;
         std::chrono::steady_clock::now() < deadline && !settled(activity);) {
      std::this_thread::sleep_for(milliseconds(20));
      activity = child.activity();
    }
    return activity;
  };
  const auto has = [](const std::string& text, const char* part) {
    return text.find(part) != std::string::npos;
  };

  auto sleeping = ChildProcess::start("/bin/sh", {"-c", "echo up; exec sleep 600"});
  ASSERT_TRUE(sleeping) << sleeping.error().message;
  ASSERT_TRUE(sleeping->wait_for_output("up", kStartup));
  // Once the shell has exec'd sleep (a moment after it wrote "up").
  std::string activity = activity_once(*sleeping, [&](const std::string& a) { return has(a, "state S"); });
  EXPECT_NE(activity.find("still running: state S, "), std::string::npos) << activity;
  EXPECT_NE(activity.find(" s of CPU in 1 thread(s): sleep S"), std::string::npos) << activity;

  auto busy = ChildProcess::start("/bin/sh", {"-c", "echo up; while :; do :; done"});
  ASSERT_TRUE(busy) << busy.error().message;
  ASSERT_TRUE(busy->wait_for_output("up", kStartup));
  // Runnable (R) even while it waits for a core on a busy machine; its CPU grows past 0.00 s.
  activity = activity_once(
      *busy, [&](const std::string& a) { return has(a, "state R") && !has(a, ", 0.00 s of CPU"); });
  EXPECT_NE(activity.find("still running: state R, "), std::string::npos) << activity;
  EXPECT_EQ(activity.find(", 0.00 s of CPU"), std::string::npos) << activity;

  auto ended = ChildProcess::start("/bin/sh", {"-c", "exit 0"});
  ASSERT_TRUE(ended) << ended.error().message;
  EXPECT_FALSE(ended->wait_for_output("ready", kStartup));
  EXPECT_EQ(ended->activity(), "exited");
  ASSERT_TRUE(ended->wait(kStartup));
  EXPECT_EQ(ended->activity(), "reaped");
}

TEST(ChildProcess, DestructorKillsAndReapsARunningChild) {
  pid_t pid = -1;
  {
    auto child = ChildProcess::start("/bin/sh", {"-c", "echo up; exec sleep 600"});
    ASSERT_TRUE(child) << child.error().message;
    ASSERT_TRUE(child->wait_for_output("up", kStartup));
    pid = child->pid();
    ASSERT_EQ(::kill(pid, 0), 0);
  }
  // Reaped, not a zombie: the pid no longer exists for us.
  errno = 0;
  EXPECT_EQ(::kill(pid, 0), -1);
  EXPECT_EQ(errno, ESRCH);
}

TEST(ChildProcess, StartFailureNamesTheProgram) {
  auto child = ChildProcess::start("/nonexistent/hubrt-no-such-program", {});
  ASSERT_FALSE(child);
  EXPECT_EQ(child.error().code, ErrorCode::kIo);
  EXPECT_NE(child.error().message.find("/nonexistent/hubrt-no-such-program"), std::string::npos)
      << child.error().message;
}

TEST(ChildProcess, StartFailsForAFileThatIsNotExecutable) {
  // Under qemu-user a failed exec in the spawned child is not reported by posix_spawn: start()
  // must see it before spawning.
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("hubrt-not-executable-" + std::to_string(::getpid()));
  std::ofstream(file) << "#!/bin/sh\necho ran\n";
  std::filesystem::permissions(file,
                               std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  auto child = ChildProcess::start(file.string(), {});
  std::filesystem::remove(file);
  ASSERT_FALSE(child) << "started " << file << " without execute permission";
  EXPECT_EQ(child.error().code, ErrorCode::kIo);
  EXPECT_NE(child.error().message.find(file.string()), std::string::npos) << child.error().message;
}

TEST(ChildProcess, StartsAProgramForThisMachine) {
  // This test binary is a program for the machine the tests run on: in a cross build it is a
  // target program, which only starts through HUBRT_TARGET_EMULATOR.
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  auto child = ChildProcess::start(self, {"--gtest_list_tests", "--gtest_filter=ChildProcess.*"});
  ASSERT_TRUE(child) << child.error().message;
  auto status = child->wait(kStartup);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << child->stderr_text();
  EXPECT_NE(child->stdout_text().find("StartsAProgramForThisMachine"), std::string::npos)
      << child->stdout_text();
}

// Sets HUBRT_TARGET_EMULATOR for one test and puts the previous value back.
class ScopedEmulator {
 public:
  explicit ScopedEmulator(const char* value) {
    // NOLINTNEXTLINE(concurrency-mt-unsafe): tests run single-threaded here
    if (const char* old = std::getenv(kName); old != nullptr) previous_ = old;
    ::setenv(kName, value, 1);
  }
  ~ScopedEmulator() {
    if (previous_) {
      ::setenv(kName, previous_->c_str(), 1);
    } else {
      ::unsetenv(kName);
    }
  }
  ScopedEmulator(const ScopedEmulator&) = delete;
  ScopedEmulator& operator=(const ScopedEmulator&) = delete;

 private:
  static constexpr const char* kName = "HUBRT_TARGET_EMULATOR";
  std::optional<std::string> previous_;
};

TEST(ChildProcess, PutsTheEmulatorInFrontOfProgramsForThisMachine) {
  // /bin/echo stands in for qemu: what it prints is the command line the emulator was given.
  const ScopedEmulator emulator("/bin/echo  emulated -L /sysroot");
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  auto child = ChildProcess::start(self, {"--gtest_list_tests"});
  ASSERT_TRUE(child) << child.error().message;
  ASSERT_TRUE(child->wait(kStartup));
  EXPECT_EQ(child->stdout_text(), "emulated -L /sysroot " + self + " --gtest_list_tests\n");
}

TEST(ChildProcess, RunsOtherProgramsDirectlyWhenAnEmulatorIsSet) {
  // A script is no ELF program for this machine: the kernel runs it (through its #! line).
  const ScopedEmulator emulator("/bin/echo emulated");
  const std::filesystem::path script =
      std::filesystem::temp_directory_path() / ("hubrt-host-script-" + std::to_string(::getpid()));
  std::ofstream(script) << "#!/bin/sh\necho \"direct $1\"\n";
  std::filesystem::permissions(script, std::filesystem::perms::owner_all);
  auto child = ChildProcess::start(script.string(), {"arg"});
  ASSERT_TRUE(child) << child.error().message;
  ASSERT_TRUE(child->wait(kStartup));
  std::filesystem::remove(script);
  EXPECT_EQ(child->stdout_text(), "direct arg\n");
}

}  // namespace
}  // namespace hubrt::test_support
