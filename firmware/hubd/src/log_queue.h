// hubd's log lines go to stderr through this bounded queue and a writer thread of its own, so
// that nothing that logs — the cycle above all — ever waits for stderr. A reader of stderr that
// stops reading (a stalled journald, a pipe nobody drains, a terminal on hold) blocks only the
// writer thread: while it is blocked, lines that find the queue full are dropped and counted
// (log_lines_dropped in /diagnostics), never waited for, and the hub's heartbeat, commands and
// stop signals go on.
//
// Why not spdlog's async_logger (Debian's libspdlog 1.10): with async_overflow_policy::
// overrun_oldest it never blocks a producer and counts overruns (thread_pool::overrun_counter),
// but its thread_pool's destructor — spdlog::shutdown(), or the end of the process — posts a
// terminate message with the blocking policy and joins the worker (details/thread_pool-inl.h):
// with the worker stuck in write(2) on a full pipe the process never ends, and SIGTERM would be
// answered by a hub that drove its outputs safe but does not exit. This queue bounds its end:
// finish() waits for the writer a bounded time, then leaves it blocked and lets the process exit.
#pragma once

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <mutex>
#include <string_view>
#include <thread>

#include "hubrt/base/time.h"

namespace hubrt::hubd {

class LogQueue {
 public:
  // Lines waiting at most (start-up's burst is ~20 lines), and the longest line kept (longer ones
  // are cut, ending in "...\n"): 32 KiB, allocated once and paged in as the ring turns.
  static constexpr std::size_t kSlots = 64;
  static constexpr std::size_t kLineBytes = 512;

  // Starts the writer thread, which writes each line to `fd` with write(2) (a line the kernel
  // refuses — EPIPE, EIO, ENOSPC — is dropped and counted). The thread is created with every
  // signal blocked: hubd reads its stop signals from a signalfd, which needs them blocked in
  // every thread. `dropped` counts every line lost (queue full, or write failed); it must outlive
  // the queue. Errors: none (a thread that cannot start aborts, as std::thread does).
  LogQueue(int fd, std::atomic<std::uint64_t>& dropped);
  // Calls finish(kFinishTimeout) if it was not called.
  ~LogQueue();
  LogQueue(const LogQueue&) = delete;
  LogQueue& operator=(const LogQueue&) = delete;

  // Queues one line made of `parts` (concatenated, cut to kLineBytes), or drops it and counts it
  // when every slot is taken. Never waits for the writer: the lock it takes is held by others
  // only to copy a line in or to move an index. Allocation-free. Thread-safe.
  void push(std::initializer_list<std::string_view> parts) noexcept;

  // Waits up to `timeout` until every queued line is written (or failed). Thread-safe.
  // Returns true when the queue is empty.
  bool drain(Duration timeout) noexcept;

  // Drains up to `timeout` — and up to three timeouts more while the writer makes progress — then
  // stops the writer: joins it when it is idle; when it is still blocked in write(2) (nobody reads
  // stderr), leaves it there — the process ends around it — and returns false. Lines pushed
  // afterwards are dropped and counted. Call once, from one thread.
  bool finish(Duration timeout) noexcept;

  // Lines waiting now. Thread-safe.
  [[nodiscard]] std::size_t queued() const noexcept;

  // How long the destructor waits for the last lines (hubd's stop message) to be written.
  static constexpr Duration kFinishTimeout = std::chrono::milliseconds(500);

 private:
  void write_loop() noexcept;

  int fd_;
  std::atomic<std::uint64_t>& dropped_;
  mutable std::mutex mutex_;
  std::condition_variable wake_writer_;
  std::condition_variable drained_;
  std::unique_ptr<char[]> text_;  // kSlots lines of kLineBytes, uninitialised until written
  std::array<std::size_t, kSlots> sizes_{};
  std::size_t head_ = 0;   // next line to write
  std::size_t count_ = 0;  // lines queued, the one being written included
  bool stopping_ = false;
  bool writing_ = false;  // the writer is inside write(2)
  bool finished_ = false;
  std::thread writer_;
};

}  // namespace hubrt::hubd
