// The black box's memory: a ring of bytes allocated once, at start, into which each recorded
// sample is copied as it goes by (its bytes, its stream, its times), the oldest giving way to the
// newest. Recording allocates nothing and holds a lock only for the copy: it runs in the cycle.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <span>
#include <vector>

#include "hubrt/base/time.h"

namespace hubrt::blackbox {

struct RingEntry {
  std::uint16_t stream = 0;
  std::uint64_t log_time = 0;      // ns since the Unix epoch
  std::uint64_t publish_time = 0;  // ns since the Unix epoch
  std::span<const std::uint8_t> bytes;
};

// What a snapshot holds: the entries' bytes in one buffer.
struct RingSnapshot {
  struct Item {
    std::uint16_t stream = 0;
    std::uint64_t log_time = 0;
    std::uint64_t publish_time = 0;
    std::size_t offset = 0;
    std::size_t size = 0;
  };
  std::vector<std::uint8_t> bytes;
  std::vector<Item> items;  // oldest first
  [[nodiscard]] std::span<const std::uint8_t> bytes_of(const Item& item) const noexcept {
    return std::span<const std::uint8_t>(bytes).subspan(item.offset, item.size);
  }
};

class Ring {
 public:
  // Every entry takes kEntryOverhead bytes besides its payload (rounded up to 8).
  static constexpr std::size_t kEntryOverhead = 32;

  // Allocates and touches `capacity_bytes` (rounded down to 8, at least 4 KiB): the memory is the
  // process's from the start, not when the ring fills a minute later.
  explicit Ring(std::size_t capacity_bytes);
  Ring(const Ring&) = delete;
  Ring& operator=(const Ring&) = delete;

  // Copies an entry in, dropping the oldest entries to make room. An entry larger than a quarter of
  // the ring is not kept (counted in refused()). Allocation-free; thread-safe.
  void record(std::uint16_t stream, std::span<const std::uint8_t> bytes, std::uint64_t log_time,
              std::uint64_t publish_time) noexcept;

  // The entries logged no earlier than `span` before the newest, oldest first. Allocates (the
  // copy); the lock is held for the copy only. Thread-safe.
  [[nodiscard]] RingSnapshot snapshot(Duration span) const;

  // Calls visit(const RingEntry&) for every entry, oldest first, WITHOUT the lock: for the crash
  // handlers only (a crashed process's other threads may be anywhere; an entry being written may
  // show torn). Async-signal-safe when `visit` is.
  template <class Visit>
  void visit_unlocked(Visit&& visit) const noexcept {
    std::size_t at = read_;
    std::size_t left = used_;
    while (left > 0) {
      const std::size_t step = entry_at(at, visit);
      if (step == 0 || step > left) return;  // torn: stop
      left -= step;
      at = (at + step) % capacity_;
    }
  }

  [[nodiscard]] std::size_t capacity() const noexcept { return capacity_; }
  [[nodiscard]] std::uint64_t recorded() const noexcept { return recorded_.load(std::memory_order_relaxed); }
  [[nodiscard]] std::uint64_t evicted() const noexcept { return evicted_.load(std::memory_order_relaxed); }
  [[nodiscard]] std::uint64_t refused() const noexcept { return refused_.load(std::memory_order_relaxed); }

 private:
  struct Header;
  static constexpr std::uint16_t kSkip = 0xFFFF;  // filler to the ring's end
  // Reads the entry (or filler) at `at`, calls visit for an entry; returns the bytes it spans
  // (the filler to the end included), 0 when torn.
  template <class Visit>
  std::size_t entry_at(std::size_t at, Visit& visit) const noexcept;
  void evict_oldest() noexcept;

  std::vector<std::uint8_t> buffer_;
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::size_t read_ = 0;   // the oldest entry; guarded by mutex_
  std::size_t write_ = 0;  // where the next goes; guarded
  std::size_t used_ = 0;   // bytes between them (fillers included); guarded
  std::atomic<std::uint64_t> recorded_{0};
  std::atomic<std::uint64_t> evicted_{0};
  std::atomic<std::uint64_t> refused_{0};
};

struct Ring::Header {
  std::uint32_t size = 0;  // of the whole entry, header and padding included (a multiple of 8)
  std::uint16_t stream = 0;
  std::uint16_t reserved = 0;
  std::uint32_t payload = 0;
  std::uint32_t reserved2 = 0;
  std::uint64_t log_time = 0;
  std::uint64_t publish_time = 0;
};
template <class Visit>
std::size_t Ring::entry_at(std::size_t at, Visit& visit) const noexcept {
  static_assert(sizeof(Header) == kEntryOverhead);
  // Less than a header's room before the end: a filler without a header (it reaches the end).
  if (capacity_ - at < sizeof(Header)) return capacity_ - at;
  Header header;
  std::memcpy(&header, buffer_.data() + at, sizeof header);
  if (header.size < sizeof(Header) || header.size > capacity_ - at ||
      header.payload > header.size - sizeof(Header))
    return 0;
  if (header.stream != kSkip) {
    visit(RingEntry{header.stream, header.log_time, header.publish_time,
                    std::span<const std::uint8_t>(buffer_.data() + at + sizeof(Header), header.payload)});
  }
  return header.size;
}

}  // namespace hubrt::blackbox
