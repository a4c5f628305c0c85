// Waking whoever waits for data: the data-available callback and the waitset.
#include <array>
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/read_condition.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/waitset.h"
#include "hubrt/dds/writer.h"

#include "dds_fixture.h"
#include "test_types_traits.h"

namespace hubrt::dds::test {
namespace {

using std::chrono::milliseconds;

class Wakeups : public DdsTest {
 protected:
  void SetUp() override {
    DdsTest::SetUp();
    if (HasFatalFailure()) return;
    auto topic = Topic<Counter>::create(participant(), "/hubrt_test/counter");
    ASSERT_TRUE(topic) << topic.error().message;
    topic_.emplace(std::move(*topic));
    auto writer = Writer<Counter>::create(participant(), *topic_);
    ASSERT_TRUE(writer) << writer.error().message;
    writer_.emplace(std::move(*writer));
  }

  Status write(std::int64_t count) {
    Counter c{};
    c.count = count;
    return writer_->write(c);
  }

  std::optional<Topic<Counter>> topic_;
  std::optional<Writer<Counter>> writer_;
};

TEST_F(Wakeups, DataAvailableCallbackFiresOnACycloneThread) {
  std::mutex mutex;
  std::condition_variable cv;
  int calls = 0;
  std::thread::id callback_thread;
  auto reader = Reader<Counter>::create(participant(), *topic_, Qos::ros2_default(), [&] {
    const std::lock_guard lock(mutex);
    ++calls;
    callback_thread = std::this_thread::get_id();
    cv.notify_all();
  });
  ASSERT_TRUE(reader) << reader.error().message;
  ASSERT_TRUE(writer_->wait_for_readers(1, kDeliveryBound));
  {
    const std::lock_guard lock(mutex);
    EXPECT_EQ(calls, 0) << "no data yet, no call";
  }
  // Written from another thread so that "not on the writing thread" is observable whether
  // Cyclone delivers locally on the writer's thread or on one of its own.
  std::thread writer_thread([&] { EXPECT_TRUE(write(1).is_ok()); });
  {
    std::unique_lock lock(mutex);
    ASSERT_TRUE(cv.wait_for(lock, kDeliveryBound, [&] { return calls > 0; }));
    EXPECT_NE(callback_thread, std::this_thread::get_id());
  }
  writer_thread.join();
  Counter in{};
  ASSERT_TRUE(reader->take_next(in).value());
  EXPECT_EQ(in.count, 1);
}

TEST_F(Wakeups, ReaderDestructionWaitsForARunningCallback) {
  std::atomic<bool> started{false};
  std::atomic<bool> finished{false};
  std::optional<Reader<Counter>> reader;
  {
    auto created = Reader<Counter>::create(participant(), *topic_, Qos::ros2_default(), [&] {
      started = true;
      // Widens the window in which the reader is destroyed during the callback; a real callback
      // must not block.
      std::this_thread::sleep_for(milliseconds(200));
      finished = true;
    });
    ASSERT_TRUE(created);
    reader.emplace(std::move(*created));
  }
  ASSERT_TRUE(writer_->wait_for_readers(1, kDeliveryBound));
  std::thread writer_thread([&] { EXPECT_TRUE(write(1).is_ok()); });
  const auto deadline = std::chrono::steady_clock::now() + kDeliveryBound;
  while (!started && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
  ASSERT_TRUE(started);
  reader.reset();
  // Had the callback storage been freed under the running callback, ASan/TSan would report it;
  // and the destructor must not have returned before the callback did.
  EXPECT_TRUE(finished);
  writer_thread.join();
}

TEST_F(Wakeups, WaitSetWakesOnDataFromAnotherThread) {
  auto reader = Reader<Counter>::create(participant(), *topic_);
  ASSERT_TRUE(reader);
  auto condition = ReadCondition::create(*reader);
  ASSERT_TRUE(condition);
  auto waitset = WaitSet::create(participant());
  ASSERT_TRUE(waitset) << waitset.error().message;
  ASSERT_TRUE(waitset->attach(*condition, 42));
  ASSERT_TRUE(writer_->wait_for_readers(1, kDeliveryBound));

  std::thread writer_thread([&] { EXPECT_TRUE(write(7).is_ok()); });
  std::array<WaitSet::Token, 4> fired{};
  auto n = waitset->wait(fired, kDeliveryBound);
  writer_thread.join();
  ASSERT_TRUE(n.is_ok());
  ASSERT_EQ(n.value(), 1u);
  EXPECT_EQ(fired[0], 42);

  // A read condition stays triggered until the data is taken.
  n = waitset->wait(fired, kDeliveryBound);
  ASSERT_EQ(n.value_or(0), 1u);
  Counter in{};
  ASSERT_TRUE(reader->take_next(in).value());
  EXPECT_EQ(in.count, 7);
  n = waitset->wait(fired, milliseconds(10));
  ASSERT_TRUE(n.is_ok());
  EXPECT_EQ(n.value(), 0u) << "nothing left: the wait must time out";

  ASSERT_TRUE(waitset->detach(*condition));
  ASSERT_TRUE(write(8).is_ok());
  n = waitset->wait(fired, milliseconds(10));
  EXPECT_EQ(n.value_or(99), 0u) << "a detached condition no longer wakes the waitset";
}

TEST_F(Wakeups, WaitSetWakesOnTheGuardConditionAndConsumesTheWake) {
  auto waitset = WaitSet::create(participant());
  ASSERT_TRUE(waitset);
  std::array<WaitSet::Token, 2> fired{};
  std::thread waker([&] { EXPECT_TRUE(waitset->wake().is_ok()); });
  auto n = waitset->wait(fired, kDeliveryBound);
  waker.join();
  ASSERT_TRUE(n.is_ok());
  ASSERT_EQ(n.value(), 1u);
  EXPECT_EQ(fired[0], WaitSet::kWakeToken);

  n = waitset->wait(fired, milliseconds(10));
  ASSERT_TRUE(n.is_ok());
  EXPECT_EQ(n.value(), 0u) << "the wake was consumed by the wait that reported it";

  ASSERT_TRUE(waitset->wake().is_ok());
  ASSERT_TRUE(waitset->wake().is_ok());
  EXPECT_EQ(waitset->wait(fired, milliseconds(10)).value_or(0), 1u);
  EXPECT_EQ(waitset->wait(fired, milliseconds(10)).value_or(99), 0u) << "wakes are not counted";
}

TEST_F(Wakeups, WakeTokenIsReserved) {
  auto reader = Reader<Counter>::create(participant(), *topic_);
  ASSERT_TRUE(reader);
  auto condition = ReadCondition::create(*reader);
  ASSERT_TRUE(condition);
  auto waitset = WaitSet::create(participant());
  ASSERT_TRUE(waitset);
  auto attached = waitset->attach(*condition, WaitSet::kWakeToken);
  ASSERT_FALSE(attached);
  EXPECT_EQ(attached.error().code, ErrorCode::kInvalidArgument);
}

}  // namespace
}  // namespace hubrt::dds::test
