// WriterWatch: other participants' writers of watched topics, with the process behind them, kept
// up to date as writers come and go.
#include "hubrt/dds/writer_watch.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "dds_fixture.h"
#include "test_types_traits.h"

namespace hubrt::dds::test {
namespace {

using std::chrono::milliseconds;

// Waits (generous: Cyclone's threads on a loaded machine) until `predicate` holds for the list.
bool wait_until(const WriterWatch& watch,
                const std::function<bool(const std::vector<WatchedWriter>&)>& predicate) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < deadline) {
    if (predicate(watch.current())) return true;
    std::this_thread::sleep_for(milliseconds(5));
  }
  return false;
}

TEST_F(DdsTest, WriterWatchReportsOtherParticipantsWritersOfWatchedTopicsWithTheirProcess) {
  std::atomic<int> reports{0};
  auto watch = WriterWatch::start(
      participant(), [](std::string_view topic) { return topic.starts_with("rt/hubrt_test/watched"); },
      [&reports](const std::vector<WatchedWriter>&) { ++reports; });
  ASSERT_TRUE(watch) << watch.error().message;
  EXPECT_EQ(reports, 1) << "the first list is reported at once";
  EXPECT_TRUE((*watch)->current().empty());

  // Our own participant's writer never counts; another participant's on an unwatched topic neither.
  auto own_topic = Topic<Ping>::create(participant(), "/hubrt_test/watched");
  ASSERT_TRUE(own_topic);
  auto own_writer = Writer<Ping>::create(participant(), *own_topic);
  ASSERT_TRUE(own_writer);
  auto other = Participant::create(config(), "other", "hubrt.started_ns=5;");
  ASSERT_TRUE(other) << other.error().message;
  auto unwatched_topic = Topic<Ping>::create(*other, "/hubrt_test/elsewhere");
  ASSERT_TRUE(unwatched_topic);
  auto unwatched_writer = Writer<Ping>::create(*other, *unwatched_topic);
  ASSERT_TRUE(unwatched_writer);
  auto other_topic = Topic<Ping>::create(*other, "/hubrt_test/watched");
  ASSERT_TRUE(other_topic);
  std::optional<Writer<Ping>> other_writer;
  {
    auto w = Writer<Ping>::create(*other, *other_topic, Qos::sensor_data(7));
    ASSERT_TRUE(w);
    other_writer.emplace(std::move(*w));
  }

  ASSERT_TRUE(wait_until(**watch, [](const auto& list) { return !list.empty(); }));
  const std::vector<WatchedWriter> list = (*watch)->current();
  ASSERT_EQ(list.size(), 1U);
  EXPECT_EQ(list[0].topic_name, "rt/hubrt_test/watched");
  EXPECT_EQ(list[0].participant_key, other->guid());
  std::array<char, 256> host{};
  ASSERT_EQ(gethostname(host.data(), host.size() - 1), 0);
  EXPECT_EQ(list[0].host, host.data());              // Cyclone's __Hostname
  EXPECT_EQ(list[0].pid, std::to_string(getpid()));  // Cyclone's __Pid
  EXPECT_FALSE(list[0].process.empty());
  EXPECT_EQ(list[0].user_data, "hubrt.started_ns=5;");
  // Its type and what it offers, as a recorder keeps them (rosbag2's offered_qos_profiles).
  EXPECT_EQ(list[0].type_name, "hubrt_test::msg::dds_::Ping_");
  EXPECT_EQ(list[0].qos.reliability, OfferedQos::Reliability::kBestEffort);
  EXPECT_EQ(list[0].qos.durability, OfferedQos::Durability::kVolatile);
  EXPECT_EQ(list[0].qos.history, OfferedQos::History::kKeepLast);
  EXPECT_EQ(list[0].qos.depth, 7);
  EXPECT_EQ(list[0].qos.deadline, Duration::max());

  // The writer goes: so does the entry.
  other_writer.reset();
  EXPECT_TRUE(wait_until(**watch, [](const auto& l) { return l.empty(); }));
  EXPECT_GE(reports, 3);
}

// More writers than one 64-sample loan holds (32 hubs on one host have ~200): the watch reads them
// all, and keeps reading and purging after its loans grew. Before the fix the next refresh after a
// grown loan wrote past the end of its 64-entry buffer (writer_watch.cc, LoanBuffer; the
// AddressSanitizer build reports it, a release hubd corrupted its heap).
TEST_F(DdsTest, WriterWatchFollowsMoreWritersThanOneLoanHolds) {
  constexpr std::size_t kWriters = 150;  // two doublings of the 64-entry first loan
  auto watch = WriterWatch::start(
      participant(), [](std::string_view topic) { return topic.starts_with("rt/hubrt_test/many"); },
      [](const std::vector<WatchedWriter>&) {});
  ASSERT_TRUE(watch) << watch.error().message;
  auto other = Participant::create(config(), "other");
  ASSERT_TRUE(other) << other.error().message;
  auto topic = Topic<Ping>::create(*other, "/hubrt_test/many");
  ASSERT_TRUE(topic);
  std::vector<Writer<Ping>> writers;
  for (std::size_t i = 0; i < kWriters; ++i) {
    auto writer = Writer<Ping>::create(*other, *topic);
    ASSERT_TRUE(writer) << writer.error().message;
    writers.push_back(std::move(*writer));
  }
  ASSERT_TRUE(wait_until(**watch, [&](const auto& list) { return list.size() == kWriters; }))
      << (*watch)->current().size() << " of " << kWriters;

  // One more, then all gone: refreshes after the loans grew, reading and taking.
  auto last = Writer<Ping>::create(*other, *topic);
  ASSERT_TRUE(last);
  EXPECT_TRUE(wait_until(**watch, [&](const auto& list) { return list.size() == kWriters + 1; }))
      << (*watch)->current().size();
  writers.clear();
  EXPECT_TRUE(wait_until(**watch, [](const auto& list) { return list.size() == 1; }))
      << (*watch)->current().size();
}

}  // namespace
}  // namespace hubrt::dds::test
