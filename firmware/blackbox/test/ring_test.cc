// The ring keeps the newest entries that fit, in order, across every wrap-around; refuses what
// would take more than a quarter of it; allocates nothing while recording.
#include "hubrt/blackbox/ring.h"

#include <deque>
#include <random>

#include <gtest/gtest.h>

#include "alloc_counter.h"

namespace hubrt::blackbox {
namespace {

struct Kept {
  std::uint16_t stream;
  std::uint64_t log_time;
  std::vector<std::uint8_t> bytes;
  bool operator==(const Kept&) const = default;
};

std::vector<Kept> contents(const Ring& ring, Duration span = std::chrono::hours(1)) {
  const RingSnapshot snapshot = ring.snapshot(span);
  std::vector<Kept> out;
  for (const auto& item : snapshot.items) {
    const auto bytes = snapshot.bytes_of(item);
    out.push_back({item.stream, item.log_time, {bytes.begin(), bytes.end()}});
  }
  return out;
}

TEST(Ring, KeepsTheNewestEntriesThatFitInOrderAcrossEveryWrap) {
  Ring ring(8192);
  std::mt19937 random(7);
  std::deque<Kept> reference;  // what must be there: the newest whose sizes sum to what fits
  std::size_t reference_bytes = 0;
  for (std::uint64_t n = 1; n <= 5000; ++n) {
    std::vector<std::uint8_t> bytes(random() % 700);
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(n + i);
    const auto stream = static_cast<std::uint16_t>(n % 5);
    ring.record(stream, bytes, n * 1000, n * 1000 - 7);
    reference.push_back({stream, n * 1000, bytes});
    reference_bytes += (Ring::kEntryOverhead + bytes.size() + 7) / 8 * 8;
    // Whatever the wrap left, the ring holds at least what fits in half of it, and never more
    // than it can.
    while (reference_bytes > ring.capacity()) {
      reference_bytes -= (Ring::kEntryOverhead + reference.front().bytes.size() + 7) / 8 * 8;
      reference.pop_front();
    }
    if (n % 97 == 0) {
      const auto held = contents(ring);
      ASSERT_FALSE(held.empty());
      ASSERT_LE(held.size(), reference.size());
      // The ring's entries are the newest ones, in order: a suffix of the reference.
      const std::vector<Kept> suffix(reference.end() - static_cast<std::ptrdiff_t>(held.size()),
                                     reference.end());
      ASSERT_EQ(held, suffix) << "after " << n;
      std::size_t held_bytes = 0;
      for (const auto& k : held) held_bytes += (Ring::kEntryOverhead + k.bytes.size() + 7) / 8 * 8;
      EXPECT_GE(held_bytes + 700 + Ring::kEntryOverhead, ring.capacity() / 2) << "after " << n;
    }
  }
  EXPECT_EQ(ring.recorded(), 5000U);
  EXPECT_GT(ring.evicted(), 4000U);
}

TEST(Ring, SnapshotTakesOnlyTheLastSpanAndOversizeEntriesAreRefused) {
  Ring ring(64 * 1024);
  const std::vector<std::uint8_t> small(10, 1);
  for (std::uint64_t t = 1; t <= 100; ++t) ring.record(1, small, t * 1'000'000'000ULL, 0);  // one a second
  EXPECT_EQ(contents(ring, std::chrono::seconds(9)).size(), 10U);                           // 91 s .. 100 s
  EXPECT_EQ(contents(ring, std::chrono::seconds(9)).front().log_time, 91'000'000'000ULL);
  const std::vector<std::uint8_t> huge(ring.capacity() / 4, 2);
  ring.record(2, huge, 101'000'000'000ULL, 0);
  EXPECT_EQ(ring.refused(), 1U);
  EXPECT_EQ(contents(ring).size(), 100U);
}

TEST(Ring, RecordingAllocatesNothing) {
  Ring ring(16 * 1024);
  std::vector<std::uint8_t> bytes(300, 5);
  for (int n = 0; n < 100; ++n)
    ring.record(0, bytes, static_cast<std::uint64_t>(n), 0);  // warm: nothing to warm
  const std::uint64_t before = hubrt::testing::thread_allocations();
  for (int n = 0; n < 10'000; ++n)
    ring.record(static_cast<std::uint16_t>(n % 3), bytes, static_cast<std::uint64_t>(n), 1);
  EXPECT_EQ(hubrt::testing::thread_allocations() - before, 0U)
      << hubrt::testing::allocation_counting_method();
}

TEST(Ring, VisitWithoutTheLockSeesWhatASnapshotSees) {
  Ring ring(4096);
  for (std::uint64_t n = 0; n < 200; ++n) ring.record(3, std::vector<std::uint8_t>(n % 50, 9), n, n);
  std::vector<std::uint64_t> visited;
  ring.visit_unlocked([&](const RingEntry& e) { visited.push_back(e.log_time); });
  std::vector<std::uint64_t> snapped;
  for (const auto& k : contents(ring)) snapped.push_back(k.log_time);
  EXPECT_EQ(visited, snapped);
}

}  // namespace
}  // namespace hubrt::blackbox
