// Heap allocations on the calling thread for the hot-path calls, ours against raw Cyclone's.
// Prints the figures it measures.
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/test_support/child_process.h"

#include "alloc_counter.h"
#include "dds_fixture.h"
#include "test_types_traits.h"

namespace hubrt::dds::test {
namespace {

constexpr int kWarmup = 200;
constexpr int kMeasured = 1000;

struct Counts {
  std::size_t write = 0;
  std::size_t take = 0;
};

class Allocations : public DdsTest {
 protected:
  void SetUp() override {
    DdsTest::SetUp();
    if (HasFatalFailure()) return;
    auto counter_topic = Topic<Counter>::create(participant(), "/hubrt_test/alloc_counter");
    auto ping_topic = Topic<Ping>::create(participant(), "/hubrt_test/alloc_ping");
    ASSERT_TRUE(counter_topic && ping_topic);
    counter_topic_.emplace(std::move(*counter_topic));
    ping_topic_.emplace(std::move(*ping_topic));
  }

  // Writes and takes one sample per iteration through `write` / `take`, counting allocations on
  // this thread for each call separately.
  template <class Write, class Take>
  static Counts measure(Write&& write, Take&& take) {
    for (int i = 0; i < kWarmup; ++i) {
      write(i);
      take();
    }
    Counts counts;
    for (int i = 0; i < kMeasured; ++i) {
      {
        const hubrt::testing::AllocationScope counter;
        write(i);
        counts.write += counter.count();
      }
      {
        const hubrt::testing::AllocationScope counter;
        take();
        counts.take += counter.count();
      }
    }
    return counts;
  }

  static void print(const char* what, const Counts& c) {
    std::printf("[alloc] %-44s write %6zu  take %6zu  (allocations in %d calls)\n", what, c.write, c.take,
                kMeasured);
  }

  std::optional<Topic<Counter>> counter_topic_;
  std::optional<Topic<Ping>> ping_topic_;
};

TEST_F(Allocations, FixedSizeTypeOursAddsNothingToCyclone) {
  auto writer = Writer<Counter>::create(participant(), *counter_topic_);
  auto reader = Reader<Counter>::create(participant(), *counter_topic_);
  ASSERT_TRUE(writer && reader);
  ASSERT_TRUE(writer->wait_for_readers(1, kDeliveryBound));
  Counter out{};
  Counter in{};
  bool all_taken = true;

  const Counts ours = measure(
      [&](int i) {
        out.count = i;
        EXPECT_TRUE(writer->write(out).is_ok());
      },
      [&] { all_taken &= reader->take_next(in).value_or(false); });
  const Counts raw = measure(
      [&](int i) {
        out.count = i;
        EXPECT_EQ(dds_write(writer->handle(), &out), DDS_RETCODE_OK);
      },
      [&] {
        void* buf[1] = {&in};
        dds_sample_info_t info;
        all_taken &= dds_take(reader->handle(), buf, &info, 1, 1) == 1;
      });
  print("Counter, ours (Writer::write, take_next)", ours);
  print("Counter, raw (dds_write, dds_take)", raw);
  EXPECT_TRUE(all_taken) << "every written sample must have been taken (local delivery is synchronous)";
  EXPECT_LE(ours.write, raw.write);
  EXPECT_LE(ours.take, raw.take);
}

TEST_F(Allocations, StringsAndSequencesReuseTheTakeBuffers) {
  auto writer = Writer<Ping>::create(participant(), *ping_topic_);
  auto reader = Reader<Ping>::create(participant(), *ping_topic_);
  ASSERT_TRUE(writer && reader);
  ASSERT_TRUE(writer->wait_for_readers(1, kDeliveryBound));
  // Fixed buffers owned here, as the cycle does it: writing needs no allocation of ours.
  std::string text(32, 'x');
  std::vector<std::int32_t> values(16, 3);
  Ping out{};
  out.text = text.data();
  out.values._buffer = values.data();
  out.values._length = out.values._maximum = static_cast<std::uint32_t>(values.size());
  Sample<Ping> in;
  bool all_taken = true;

  const Counts ours = measure(
      [&](int i) {
        out.seq = static_cast<std::uint32_t>(i);
        EXPECT_TRUE(writer->write(out).is_ok());
      },
      [&] { all_taken &= reader->take_next(in).value_or(false); });
  print("Ping 32 chars + 16 int32, ours", ours);
  EXPECT_TRUE(all_taken);
  EXPECT_EQ(in->seq, static_cast<std::uint32_t>(kMeasured - 1));
  EXPECT_EQ(ours.take, 0u) << "same-sized strings and sequences must be taken into the existing buffers";
}

TEST_F(Allocations, WriteWithNobodyListening) {
  auto writer = Writer<Counter>::create(participant(), *counter_topic_);
  ASSERT_TRUE(writer);
  // For reference, a raw writer without the instance registration Writer does. Cyclone keys its
  // instance table by key value, and evidently every keyless type shares the one empty key: while our
  // writer holds the registration this raw writer profits too and also shows 0. With the
  // registration disabled both showed 2.0 to 3.0 allocations per write here (instance created
  // and garbage-collected on every write); that is what the assertion below guards against.
  const EntityHandle raw_writer(
      dds_create_writer(participant().handle(), ping_topic_->handle(), Qos::ros2_default().get(), nullptr));
  ASSERT_GT(raw_writer.get(), 0);
  Counter out{};
  const Counts ours = measure(
      [&](int i) {
        out.count = i;
        EXPECT_TRUE(writer->write(out).is_ok());
      },
      [] {});
  char text[] = "fixed";
  Ping ping{};
  ping.text = text;
  const Counts raw = measure(
      [&](int i) {
        ping.seq = static_cast<std::uint32_t>(i);
        EXPECT_EQ(dds_write(raw_writer.get(), &ping), DDS_RETCODE_OK);
      },
      [] {});
  print("Counter, no reader, ours", ours);
  print("Ping, no reader, raw unregistered writer", raw);
  EXPECT_EQ(ours.write, 0u) << "the registered instance must spare Cyclone its per-write instance churn";
}

// The hub's real situation: its readers are in other processes. Prints Cyclone's allocations per
// write; they vary with how fast the remote reader acknowledges (unacknowledged samples stay in
// the writer's history), so only the delivery is asserted here. That we add none is pinned by
// the deterministic tests above.
TEST_F(Allocations, WriteToAReaderInAnotherProcess) {
  auto probe = test_support::ChildProcess::start(HUBRT_DDS_ENV_PROBE, {"--read", "/hubrt_test/alloc_counter"},
                                                 domain_->env());
  ASSERT_TRUE(probe) << probe.error().message;
  ASSERT_TRUE(probe->wait_for_output("probe: reading", kDeliveryBound)) << probe->stderr_text();
  auto writer = Writer<Counter>::create(participant(), *counter_topic_);
  ASSERT_TRUE(writer);
  ASSERT_TRUE(writer->wait_for_readers(1, kDeliveryBound));
  Counter out{};
  const Counts ours = measure(
      [&](int i) {
        out.count = i;
        EXPECT_TRUE(writer->write(out).is_ok());
      },
      [] {});
  print("Counter, reader in another process, ours", ours);
  EXPECT_EQ(writer->matched_readers().value_or(0), 1u) << "the remote reader stayed matched throughout";
  expect_probe_ends_cleanly(*probe);
}

}  // namespace
}  // namespace hubrt::dds::test
