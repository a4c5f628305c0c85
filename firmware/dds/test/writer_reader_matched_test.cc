// A writer learns of each new reader that matches it (its publication-matched listener): the
// count it hands out once, and the callback that wakes a cycle (issue 16, point 2).
#include <atomic>
#include <optional>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"

#include "dds_fixture.h"
#include "test_types_traits.h"

namespace hubrt::dds::test {
namespace {

using ReaderMatched = DdsTest;

TEST_F(ReaderMatched, EachNewReaderIsCountedOnceAndWakesTheCallback) {
  auto topic = Topic<Counter>::create(participant(), "/hubrt_test/matched");
  ASSERT_TRUE(topic) << topic.error().message;
  std::atomic<int> wakes{0};
  auto writer = Writer<Counter>::create(participant(), *topic, Qos::ros2_default(), [&] { ++wakes; });
  ASSERT_TRUE(writer) << writer.error().message;
  EXPECT_EQ(writer->take_new_readers(), 0u) << "nobody there yet";

  auto created = Reader<Counter>::create(participant(), *topic);
  ASSERT_TRUE(created) << created.error().message;
  std::optional<Reader<Counter>> first(std::move(*created));
  ASSERT_TRUE(writer->wait_for_readers(1, kDeliveryBound));
  auto second = Reader<Counter>::create(participant(), *topic);
  ASSERT_TRUE(second) << second.error().message;
  ASSERT_TRUE(writer->wait_for_readers(2, kDeliveryBound));
  // wait_for_readers polls the same status the listener reports: by now both calls have run.
  EXPECT_EQ(writer->take_new_readers(), 2u);
  EXPECT_EQ(writer->take_new_readers(), 0u) << "taken once";
  EXPECT_EQ(wakes.load(), 2);

  first.reset();  // a reader that goes away is not a new one
  const auto deadline = std::chrono::steady_clock::now() + kDeliveryBound;
  while (writer->matched_readers().value_or(0) != 1 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  EXPECT_EQ(writer->take_new_readers(), 0u);
  EXPECT_EQ(wakes.load(), 2);
}

TEST_F(ReaderMatched, AMovedWriterKeepsCounting) {
  auto topic = Topic<Counter>::create(participant(), "/hubrt_test/matched_moved");
  ASSERT_TRUE(topic) << topic.error().message;
  auto created = Writer<Counter>::create(participant(), *topic);
  ASSERT_TRUE(created) << created.error().message;
  std::optional<Writer<Counter>> writer(std::move(*created));
  auto reader = Reader<Counter>::create(participant(), *topic);
  ASSERT_TRUE(reader) << reader.error().message;
  ASSERT_TRUE(writer->wait_for_readers(1, kDeliveryBound));
  EXPECT_EQ(writer->take_new_readers(), 1u);
}

// has_matched_readers() follows Cyclone's current count, readers going away included: what the sim
// bridge asks each cycle before reading the signals nobody may want (issue 16, point 4).
TEST_F(ReaderMatched, HasMatchedReadersFollowsReadersComingAndGoing) {
  auto topic = Topic<Counter>::create(participant(), "/hubrt_test/matched_now");
  ASSERT_TRUE(topic) << topic.error().message;
  auto writer = Writer<Counter>::create(participant(), *topic);
  ASSERT_TRUE(writer) << writer.error().message;
  EXPECT_FALSE(writer->has_matched_readers());
  auto created = Reader<Counter>::create(participant(), *topic);
  ASSERT_TRUE(created) << created.error().message;
  std::optional<Reader<Counter>> reader(std::move(*created));
  ASSERT_TRUE(writer->wait_for_readers(1, kDeliveryBound));
  EXPECT_TRUE(writer->has_matched_readers());
  reader.reset();
  const auto deadline = std::chrono::steady_clock::now() + kDeliveryBound;
  while (writer->has_matched_readers() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  EXPECT_FALSE(writer->has_matched_readers());
  EXPECT_EQ(writer->matched_readers().value_or(1), 0u);
}

}  // namespace
}  // namespace hubrt::dds::test
