#include "can_contract.h"

#include <chrono>
#include <thread>

namespace hubrt::hal::contract {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using Steady = std::chrono::steady_clock;

// How long a receive may wait for a frame that was already sent. A frame crosses a virtual bus or
// vcan in microseconds; 2 s only absorbs scheduling noise on a loaded machine (and the VM).
constexpr Duration kArrival = seconds(2);

CanFrame frame(std::uint32_t id, std::uint8_t len, std::uint8_t seed = 0, bool extended = false) {
  CanFrame f;
  f.id = id;
  f.extended = extended;
  f.len = len;
  for (std::uint8_t i = 0; i < len; ++i) f.data[i] = static_cast<std::uint8_t>(seed + i);
  return f;
}

void expect_same(const CanFrame& got, const CanFrame& sent) {
  EXPECT_EQ(got.id, sent.id);
  EXPECT_EQ(got.extended, sent.extended);
  EXPECT_EQ(got.remote, sent.remote);
  EXPECT_EQ(got.len, sent.len);
  for (std::uint8_t i = 0; i < sent.len && !sent.remote; ++i)
    EXPECT_EQ(got.data[i], sent.data[i]) << "byte " << int{i};
}

ErrorCode poll_code(CanBus& bus) {
  return bus.receive(Duration::zero()).status().code();
}

}  // namespace

void CanContract::SetUp() {
  harness_ = GetParam().make();
  ASSERT_NE(harness_, nullptr);
}

void CanContract::TearDown() {
  if (harness_) harness_->inject_bus_state(CanBusState::kErrorActive);
}

std::unique_ptr<CanBus> CanContract::open(const std::vector<CanFilter>& filters) {
  auto node = harness_->open_node(filters);
  EXPECT_TRUE(node.is_ok()) << (node.is_ok() ? "" : node.error().message);
  return node.is_ok() ? std::move(*node) : nullptr;
}

TEST_P(CanContract, FrameSentByOneNodeReachesTheOtherUnchanged) {
  auto a = open();
  auto b = open();
  ASSERT_TRUE(a && b);
  const CanFrame sent = frame(0x123, 8, 0xA0);
  ASSERT_TRUE(a->send(sent, milliseconds(100)).is_ok());
  const Result<CanFrame> got = b->receive(kArrival);
  ASSERT_TRUE(got.is_ok()) << to_string(got.status().code());
  expect_same(got.value(), sent);
  EXPECT_EQ(poll_code(*a), ErrorCode::kTimeout) << "a node does not receive its own frames";
}

TEST_P(CanContract, ExtendedRemoteAndEmptyFramesKeepTheirShape) {
  auto a = open();
  auto b = open();
  ASSERT_TRUE(a && b);
  CanFrame remote = frame(0x7FF, 0);
  remote.remote = true;
  for (const CanFrame& sent : {frame(0x1ABC'DE12, 5, 1, true), remote, frame(0x000, 0)}) {
    ASSERT_TRUE(a->send(sent, milliseconds(100)).is_ok());
    const Result<CanFrame> got = b->receive(kArrival);
    ASSERT_TRUE(got.is_ok());
    expect_same(got.value(), sent);
  }
}

TEST_P(CanContract, EveryOtherNodeReceivesInSendingOrder) {
  auto a = open();
  auto b = open();
  auto c = open();
  ASSERT_TRUE(a && b && c);
  for (std::uint8_t i = 0; i < 20; ++i)
    ASSERT_TRUE(a->send(frame(0x200 + i, 1, i), milliseconds(100)).is_ok());
  for (CanBus* receiver : {b.get(), c.get()}) {
    for (std::uint8_t i = 0; i < 20; ++i) {
      const Result<CanFrame> got = receiver->receive(kArrival);
      ASSERT_TRUE(got.is_ok()) << "frame " << int{i};
      EXPECT_EQ(got.value().id, 0x200U + i);
    }
  }
}

TEST_P(CanContract, FiltersPassOnlyMatchingIdsOfTheirFormat) {
  auto a = open();
  auto b = open({CanFilter{0x100, 0x700, false}});
  ASSERT_TRUE(a && b);
  ASSERT_TRUE(a->send(frame(0x205, 1), milliseconds(100)).is_ok());
  ASSERT_TRUE(a->send(frame(0x105, 1, 0, true), milliseconds(100)).is_ok());
  ASSERT_TRUE(a->send(frame(0x105, 1), milliseconds(100)).is_ok());
  const Result<CanFrame> got = b->receive(kArrival);
  ASSERT_TRUE(got.is_ok());
  EXPECT_EQ(got.value().id, 0x105U);
  EXPECT_FALSE(got.value().extended) << "the extended 0x105 must not pass a standard filter";
  EXPECT_EQ(poll_code(*b), ErrorCode::kTimeout);
}

TEST_P(CanContract, SetFiltersReplacesThemAndEmptyMeansEverything) {
  auto a = open();
  auto b = open({CanFilter{0x100, 0x7FF, false}});
  ASSERT_TRUE(a && b);
  const std::vector<CanFilter> only_300{CanFilter{0x300, 0x7FF, false}};
  ASSERT_TRUE(b->set_filters(only_300).is_ok());
  ASSERT_TRUE(a->send(frame(0x100, 0), milliseconds(100)).is_ok());
  ASSERT_TRUE(a->send(frame(0x300, 0), milliseconds(100)).is_ok());
  const Result<CanFrame> first = b->receive(kArrival);
  ASSERT_TRUE(first.is_ok());
  EXPECT_EQ(first.value().id, 0x300U);

  ASSERT_TRUE(b->set_filters({}).is_ok());
  ASSERT_TRUE(a->send(frame(0x555, 0), milliseconds(100)).is_ok());
  const Result<CanFrame> second = b->receive(kArrival);
  ASSERT_TRUE(second.is_ok());
  EXPECT_EQ(second.value().id, 0x555U);

  const std::vector<CanFilter> too_wide{CanFilter{0x800, 0x7FF, false}};
  EXPECT_EQ(b->set_filters(too_wide).code(), ErrorCode::kInvalidArgument);
}

TEST_P(CanContract, ReceiveTimesOutWithinBounds) {
  auto a = open();
  ASSERT_TRUE(a);
  const auto start = Steady::now();
  EXPECT_EQ(a->receive(milliseconds(50)).status().code(), ErrorCode::kTimeout);
  const auto took = Steady::now() - start;
  EXPECT_GE(took, milliseconds(50)) << "returned before the timeout";
  // Upper bound: the timeout plus scheduling noise (1 s is generous on a loaded 2-core machine).
  EXPECT_LT(took, milliseconds(50) + seconds(1));

  const auto poll_start = Steady::now();
  EXPECT_EQ(poll_code(*a), ErrorCode::kTimeout);
  EXPECT_LT(Steady::now() - poll_start, milliseconds(500)) << "timeout 0 polls";
}

TEST_P(CanContract, FramesThatDoNotFitAreRejectedAndNotSent) {
  auto a = open();
  auto b = open();
  ASSERT_TRUE(a && b);
  CanFrame oversize = frame(0x10, 8);
  oversize.len = 9;
  EXPECT_EQ(a->send(oversize, milliseconds(100)).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(a->send(frame(0x800, 1), milliseconds(100)).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(a->send(frame(0x2000'0000, 1, 0, true), milliseconds(100)).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(b->receive(milliseconds(50)).status().code(), ErrorCode::kTimeout);
}

TEST_P(CanContract, BusOffIsReportedAndStopsTrafficUntilRecovery) {
  auto a = open();
  auto b = open();
  ASSERT_TRUE(a && b);
  if (!harness_->inject_bus_state(CanBusState::kBusOff)) GTEST_SKIP() << "backend cannot inject bus-off";
  EXPECT_EQ(a->status().state, CanBusState::kBusOff);
  EXPECT_GT(a->status().error_frames, 0U) << "bus-off is announced by an error frame";
  EXPECT_EQ(a->send(frame(0x1, 0), milliseconds(50)).code(), ErrorCode::kUnavailable);
  EXPECT_EQ(b->receive(milliseconds(50)).status().code(), ErrorCode::kUnavailable);

  ASSERT_TRUE(harness_->inject_bus_state(CanBusState::kErrorActive));
  EXPECT_EQ(a->status().state, CanBusState::kErrorActive);
  ASSERT_TRUE(a->send(frame(0x2, 0), milliseconds(100)).is_ok());
  EXPECT_TRUE(b->receive(kArrival).is_ok());
}

TEST_P(CanContract, InterfaceDownIsUnavailableAndRecovers) {
  auto a = open();
  auto b = open();
  ASSERT_TRUE(a && b);
  if (!harness_->inject_bus_state(CanBusState::kDown))
    GTEST_SKIP() << "backend cannot take the interface down";
  EXPECT_EQ(a->status().state, CanBusState::kDown);
  EXPECT_EQ(a->send(frame(0x1, 0), milliseconds(50)).code(), ErrorCode::kUnavailable);
  EXPECT_EQ(b->receive(milliseconds(50)).status().code(), ErrorCode::kUnavailable);

  ASSERT_TRUE(harness_->inject_bus_state(CanBusState::kErrorActive));
  EXPECT_EQ(a->status().state, CanBusState::kErrorActive);
  ASSERT_TRUE(a->send(frame(0x2, 0), milliseconds(100)).is_ok());
  const Result<CanFrame> got = b->receive(kArrival);
  ASSERT_TRUE(got.is_ok());
  EXPECT_EQ(got.value().id, 0x2U);
}

TEST_P(CanContract, BlockedReceiverWakesWhenAFrameArrives) {
  auto a = open();
  auto b = open();
  ASSERT_TRUE(a && b);
  Result<CanFrame> got = Status(ErrorCode::kInternal);
  Steady::duration waited{};
  std::thread receiver([&] {
    const auto start = Steady::now();
    got = b->receive(seconds(10));
    waited = Steady::now() - start;
  });
  const Status sent = a->send(frame(0x42, 2), milliseconds(100));
  receiver.join();
  ASSERT_TRUE(sent.is_ok());
  ASSERT_TRUE(got.is_ok());
  EXPECT_EQ(got.value().id, 0x42U);
  // Far below the 10 s timeout: the frame ended the wait, not the timeout.
  EXPECT_LT(waited, seconds(5));
}

}  // namespace hubrt::hal::contract
