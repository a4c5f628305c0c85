#include "log_queue.h"

#include <pthread.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>

namespace hubrt::hubd {
namespace {

// Writes all of `text` to `fd`; false when the kernel refuses (EPIPE, EBADF, EIO, ENOSPC...).
// Blocks while the reader does not read: only the writer thread calls it.
bool write_all(int fd, const char* text, std::size_t size) noexcept {
  while (size > 0) {
    const ssize_t n = ::write(fd, text, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    text += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

constexpr std::string_view kCut = "...\n";

}  // namespace

LogQueue::LogQueue(int fd, std::atomic<std::uint64_t>& dropped)
    : fd_(fd), dropped_(dropped), text_(new char[kSlots * kLineBytes]) {
  // Every signal blocked in the new thread (it inherits the creator's mask), the creator's own
  // mask restored afterwards.
  sigset_t all;
  sigset_t previous;
  sigfillset(&all);
  pthread_sigmask(SIG_SETMASK, &all, &previous);
  writer_ = std::thread([this] { write_loop(); });
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

LogQueue::~LogQueue() {
  if (!finished_) finish(kFinishTimeout);
}

void LogQueue::push(std::initializer_list<std::string_view> parts) noexcept {
  const std::lock_guard lock(mutex_);
  if (stopping_ || count_ == kSlots) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  const std::size_t slot = (head_ + count_) % kSlots;
  char* out = text_.get() + slot * kLineBytes;
  std::size_t size = 0;
  bool cut = false;
  for (const std::string_view part : parts) {
    const std::size_t room = kLineBytes - size;
    const std::size_t n = part.size() < room ? part.size() : room;
    std::memcpy(out + size, part.data(), n);
    size += n;
    if (n < part.size()) cut = true;
  }
  if (cut) {
    // Cut at a character: back over UTF-8 continuation bytes, so the line stays valid UTF-8.
    size = kLineBytes - kCut.size();
    while (size > 0 && (static_cast<unsigned char>(out[size]) & 0xC0) == 0x80) --size;
    std::memcpy(out + size, kCut.data(), kCut.size());
    size += kCut.size();
  }
  sizes_[slot] = size;
  ++count_;
  wake_writer_.notify_one();
}

void LogQueue::write_loop() noexcept {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_writer_.wait(lock, [this] { return count_ > 0 || stopping_; });
    if (count_ == 0) return;  // stopping, and everything written
    const std::size_t slot = head_;
    writing_ = true;
    lock.unlock();
    // The slot stays taken (count_ includes it) while it is written, so no producer reuses it.
    const bool ok = write_all(fd_, text_.get() + slot * kLineBytes, sizes_[slot]);
    lock.lock();
    writing_ = false;
    if (!ok) dropped_.fetch_add(1, std::memory_order_relaxed);
    head_ = (head_ + 1) % kSlots;
    --count_;
    if (count_ == 0) drained_.notify_all();
  }
}

bool LogQueue::drain(Duration timeout) noexcept {
  std::unique_lock lock(mutex_);
  return drained_.wait_for(lock, timeout, [this] { return count_ == 0; });
}

bool LogQueue::finish(Duration timeout) noexcept {
  finished_ = true;
  // A writer that makes progress (a loaded machine, a slow terminal) gets up to four timeouts; one
  // that wrote nothing for a whole timeout is stuck on a reader that does not read.
  std::size_t before = queued();
  bool drained = drain(timeout);
  for (int round = 1; !drained && round < 4; ++round) {
    const std::size_t left = queued();
    if (left >= before) break;
    before = left;
    drained = drain(timeout);
  }
  bool idle = false;
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
    idle = !writing_;
    if (idle) {  // what could not be written in time is dropped, and counted
      dropped_.fetch_add(count_, std::memory_order_relaxed);
      count_ = 0;
    }
    wake_writer_.notify_one();
  }
  if (idle) {
    writer_.join();
    return drained;
  }
  // Blocked in write(2): it may stay there for good. The process ends around it; this object
  // must then never be destroyed under it (hubd keeps its queue for the process's life).
  writer_.detach();
  return false;
}

std::size_t LogQueue::queued() const noexcept {
  const std::lock_guard lock(mutex_);
  return count_;
}

}  // namespace hubrt::hubd
