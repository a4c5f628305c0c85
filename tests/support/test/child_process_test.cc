#include "hubrt/test_support/child_process.h"

#include <signal.h>

#include <cerrno>
#include <chrono>

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

}  // namespace
}  // namespace hubrt::test_support
