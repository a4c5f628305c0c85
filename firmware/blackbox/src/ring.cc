#include "hubrt/blackbox/ring.h"

#include <algorithm>

namespace hubrt::blackbox {
namespace {

constexpr std::size_t round_up8(std::size_t n) noexcept {
  return (n + 7) & ~std::size_t{7};
}

}  // namespace

Ring::Ring(std::size_t capacity_bytes)
    : buffer_(std::max<std::size_t>(capacity_bytes & ~std::size_t{7}, 4096), 0), capacity_(buffer_.size()) {}

void Ring::evict_oldest() noexcept {
  std::size_t step = 0;
  bool entry = false;
  if (capacity_ - read_ < sizeof(Header)) {
    step = capacity_ - read_;
  } else {
    Header header;
    std::memcpy(&header, buffer_.data() + read_, sizeof header);
    step = header.size;
    entry = header.stream != kSkip;
  }
  used_ -= step;
  read_ = (read_ + step) % capacity_;
  if (entry) evicted_.fetch_add(1, std::memory_order_relaxed);
  if (used_ == 0) read_ = write_ = 0;
}

void Ring::record(std::uint16_t stream, std::span<const std::uint8_t> bytes, std::uint64_t log_time,
                  std::uint64_t publish_time) noexcept {
  const std::size_t size = round_up8(sizeof(Header) + bytes.size());
  if (size > capacity_ / 4 || stream == kSkip) {
    refused_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  const std::lock_guard lock(mutex_);
  for (;;) {
    if (used_ == 0) read_ = write_ = 0;
    // The data runs from read_ to write_ (wrapping); the free room is after write_.
    const bool wrapped = write_ < read_ || (write_ == read_ && used_ > 0);
    const std::size_t room = wrapped ? read_ - write_ : capacity_ - write_;
    if (room >= size) break;
    if (!wrapped && read_ > 0) {
      // Not enough before the end, but the start is free: fill to the end and go round.
      if (capacity_ - write_ >= sizeof(Header)) {
        Header filler;
        filler.size = static_cast<std::uint32_t>(capacity_ - write_);
        filler.stream = kSkip;
        std::memcpy(buffer_.data() + write_, &filler, sizeof filler);
      }
      used_ += capacity_ - write_;
      write_ = 0;
      continue;
    }
    evict_oldest();
  }
  Header header;
  header.size = static_cast<std::uint32_t>(size);
  header.stream = stream;
  header.payload = static_cast<std::uint32_t>(bytes.size());
  header.log_time = log_time;
  header.publish_time = publish_time;
  std::memcpy(buffer_.data() + write_, &header, sizeof header);
  if (!bytes.empty()) std::memcpy(buffer_.data() + write_ + sizeof header, bytes.data(), bytes.size());
  write_ = (write_ + size) % capacity_;
  used_ += size;
  recorded_.fetch_add(1, std::memory_order_relaxed);
}

RingSnapshot Ring::snapshot(Duration span) const {
  RingSnapshot out;
  const std::lock_guard lock(mutex_);
  std::uint64_t newest = 0;
  visit_unlocked([&](const RingEntry& e) { newest = std::max(newest, e.log_time); });
  const auto span_ns = static_cast<std::uint64_t>(std::max<std::int64_t>(span.count(), 0));
  const std::uint64_t oldest = newest > span_ns ? newest - span_ns : 0;
  std::size_t bytes = 0;
  std::size_t count = 0;
  visit_unlocked([&](const RingEntry& e) {
    if (e.log_time < oldest) return;
    bytes += e.bytes.size();
    ++count;
  });
  out.bytes.reserve(bytes);
  out.items.reserve(count);
  visit_unlocked([&](const RingEntry& e) {
    if (e.log_time < oldest) return;
    out.items.push_back({e.stream, e.log_time, e.publish_time, out.bytes.size(), e.bytes.size()});
    out.bytes.insert(out.bytes.end(), e.bytes.begin(), e.bytes.end());
  });
  return out;
}

}  // namespace hubrt::blackbox
