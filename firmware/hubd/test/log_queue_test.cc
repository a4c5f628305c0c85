// hubd's log queue (src/log_queue.h): lines reach the file descriptor in order from a thread of
// their own; a reader that stops reading blocks only that thread — push() never waits, lines that
// find the queue full are dropped and counted — and finish() ends within its bound whatever the
// reader does. Real pipes; the only waits are bounded, each bound saying what it guards against.
#include "log_queue.h"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <csignal>
#include <string>
#include <thread>

#include <gtest/gtest.h>

namespace hubrt::hubd {
namespace {

using std::chrono::milliseconds;
using Steady = std::chrono::steady_clock;

struct Pipe {
  Pipe() { EXPECT_EQ(::pipe2(fds.data(), O_CLOEXEC), 0); }
  ~Pipe() {
    for (const int fd : fds) {
      if (fd >= 0) ::close(fd);
    }
  }
  // Everything readable now (the write end closed first, so read() ends at EOF).
  std::string read_all() {
    ::close(fds[1]);
    fds[1] = -1;
    std::string text;
    std::array<char, 4096> buffer{};
    for (ssize_t n = 0; (n = ::read(fds[0], buffer.data(), buffer.size())) > 0;)
      text.append(buffer.data(), n);
    return text;
  }
  std::array<int, 2> fds{-1, -1};
};

TEST(LogQueue, WritesTheLinesInOrder) {
  Pipe pipe;
  std::atomic<std::uint64_t> dropped{0};
  {
    LogQueue queue(pipe.fds[1], dropped);
    queue.push({"one", " and ", "two\n"});
    queue.push({"three\n"});
    EXPECT_TRUE(queue.finish(std::chrono::seconds(5)));  // 5 s: a loaded machine; it takes microseconds
  }
  EXPECT_EQ(pipe.read_all(), "one and two\nthree\n");
  EXPECT_EQ(dropped.load(), 0u);
}

TEST(LogQueue, ALongLineIsCutAtACharacterAndMarked) {
  Pipe pipe;
  std::atomic<std::uint64_t> dropped{0};
  {
    LogQueue queue(pipe.fds[1], dropped);
    const std::string text(LogQueue::kLineBytes - 5, 'a');
    queue.push({text, "\xC3\xA9\xC3\xA9\xC3\xA9\n"});  // "ééé": the cut must not split one
    EXPECT_TRUE(queue.finish(std::chrono::seconds(5)));
  }
  const std::string line = pipe.read_all();
  EXPECT_EQ(line.size(), LogQueue::kLineBytes - 1) << "the cut moved back over the 2-byte character";
  EXPECT_EQ(line.substr(line.size() - 4), "...\n");
  EXPECT_EQ(line.find('\xC3'), std::string::npos);
}

TEST(LogQueue, AReaderThatStopsReadingNeverHoldsThePusherOrTheEnd) {
  Pipe pipe;  // nobody reads fds[0]
  // Kept for the process's life (reachable, so no leak report), as hubd keeps its own: its writer
  // is left blocked when finish() gives up on it.
  static LogQueue* queue = nullptr;
  static std::atomic<std::uint64_t> dropped_for_good{0};
  queue = new LogQueue(pipe.fds[1], dropped_for_good);  // NOLINT(cppcoreguidelines-owning-memory)
  const std::string line(200, 'x');
  // First the pipe fills (64 KiB: 327 lines of 201 bytes), at a pace the writer keeps up with,
  // then the queue's slots: the writer is blocked for good.
  for (int i = 0; i < 5'000 && queue->queued() < LogQueue::kSlots; ++i) {
    queue->push({line, "\n"});
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  ASSERT_EQ(queue->queued(), LogQueue::kSlots) << "the pipe never filled";
  const auto start = Steady::now();
  // A burst into the full queue: 10 000 lines, every one dropped and counted.
  for (int i = 0; i < 10'000; ++i) queue->push({line, "\n"});
  const auto pushing = Steady::now() - start;
  // Copies only: far under a second even under sanitizers; a pusher that waited for the reader
  // would never get here at all.
  EXPECT_LT(pushing, std::chrono::seconds(2));
  EXPECT_GE(dropped_for_good.load(), 10'000u)
      << "lines beyond the pipe and the queue are dropped and counted";
  EXPECT_EQ(queue->queued(), LogQueue::kSlots) << "the queue is full, the writer blocked";

  const auto finishing = Steady::now();
  EXPECT_FALSE(queue->finish(milliseconds(100))) << "the writer is still blocked in write(2)";
  EXPECT_LT(Steady::now() - finishing, std::chrono::seconds(2)) << "finish() is bounded";
  const std::uint64_t before = dropped_for_good.load();
  queue->push({"after the end\n"});
  EXPECT_EQ(dropped_for_good.load(), before + 1) << "a line after finish() is dropped and counted";
  // The writer stays blocked on the pipe until the test ends the pipe's reading side: then its
  // writes fail (EPIPE, SIGPIPE ignored here as in hubd) and it returns. The writing side stays
  // open for good: the detached writer may still be using its number.
  std::signal(SIGPIPE, SIG_IGN);
  ::close(pipe.fds[0]);
  pipe.fds[0] = -1;
  pipe.fds[1] = -1;
}

}  // namespace
}  // namespace hubrt::hubd
