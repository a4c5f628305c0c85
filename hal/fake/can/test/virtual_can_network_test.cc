// Deterministic tests of the virtual CAN network: ManualClock, receive with timeout 0, no threads.
#include "hubrt/hal/fake/virtual_can_network.h"

#include <vector>

#include <gtest/gtest.h>

namespace hubrt::hal::fake {
namespace {

using std::chrono::milliseconds;

CanFrame frame(std::uint32_t id, std::uint8_t first_byte = 0, bool extended = false) {
  CanFrame f;
  f.id = id;
  f.extended = extended;
  f.len = 1;
  f.data[0] = first_byte;
  return f;
}

CanConfig config(std::string interface, std::vector<CanFilter> filters = {}) {
  CanConfig c;
  c.bus = "test_bus";
  c.interface = std::move(interface);
  c.filters = std::move(filters);
  return c;
}

std::unique_ptr<VirtualCanNode> open(VirtualCanNetwork& net, const CanConfig& c,
                                     VirtualCanNodeOptions o = {}) {
  auto node = net.open(c, o);
  EXPECT_TRUE(node.is_ok()) << (node.is_ok() ? "" : node.error().message);
  return node.is_ok() ? std::move(*node) : nullptr;
}

ErrorCode receive_code(CanBus& bus) {
  return bus.receive(Duration::zero()).status().code();
}

class VirtualCanNetworkTest : public ::testing::Test {
 protected:
  ManualClock clock;
  VirtualCanNetwork net{clock};
};

TEST_F(VirtualCanNetworkTest, FrameReachesEveryOtherNodeOnItsBusOnly) {
  auto a = open(net, config("vcan0"));
  auto b = open(net, config("vcan0"));
  auto c = open(net, config("vcan0"));
  auto other_bus = open(net, config("vcan1"));

  ASSERT_TRUE(a->send(frame(0x123, 7), milliseconds(10)).is_ok());

  for (CanBus* receiver : {static_cast<CanBus*>(b.get()), static_cast<CanBus*>(c.get())}) {
    const Result<CanFrame> got = receiver->receive(Duration::zero());
    ASSERT_TRUE(got.is_ok());
    EXPECT_EQ(got.value().id, 0x123U);
    EXPECT_EQ(got.value().data[0], 7);
  }
  EXPECT_EQ(receive_code(*a), ErrorCode::kTimeout) << "a sender must not hear itself";
  EXPECT_EQ(receive_code(*other_bus), ErrorCode::kTimeout) << "buses are separate";
}

TEST_F(VirtualCanNetworkTest, FramesKeepOrderAndContent) {
  auto a = open(net, config("vcan0"));
  auto b = open(net, config("vcan0"));
  CanFrame ext = frame(0x1ABCDE12, 0, true);
  ext.len = 8;
  for (std::uint8_t i = 0; i < 8; ++i) ext.data[i] = static_cast<std::uint8_t>(0xA0 + i);
  CanFrame remote = frame(0x7FF);
  remote.remote = true;
  remote.len = 0;
  ASSERT_TRUE(a->send(ext, Duration::zero()).is_ok());
  ASSERT_TRUE(a->send(remote, Duration::zero()).is_ok());

  const Result<CanFrame> first = b->receive(Duration::zero());
  ASSERT_TRUE(first.is_ok());
  EXPECT_TRUE(first.value().extended);
  EXPECT_EQ(first.value().id, 0x1ABCDE12U);
  EXPECT_EQ(first.value().len, 8);
  EXPECT_EQ(first.value().data, ext.data);
  const Result<CanFrame> second = b->receive(Duration::zero());
  ASSERT_TRUE(second.is_ok());
  EXPECT_TRUE(second.value().remote);
  EXPECT_EQ(second.value().id, 0x7FFU);
}

TEST_F(VirtualCanNetworkTest, FiltersApplyPerNodeAndCanBeReplaced) {
  auto a = open(net, config("vcan0"));
  auto b = open(net, config("vcan0", {CanFilter{0x100, 0x700, false}}));
  ASSERT_TRUE(a->send(frame(0x105), Duration::zero()).is_ok());
  ASSERT_TRUE(a->send(frame(0x205), Duration::zero()).is_ok());
  ASSERT_TRUE(a->send(frame(0x105, 0, true), Duration::zero()).is_ok()) << "extended: format must match";

  const Result<CanFrame> got = b->receive(Duration::zero());
  ASSERT_TRUE(got.is_ok());
  EXPECT_EQ(got.value().id, 0x105U);
  EXPECT_FALSE(got.value().extended);
  EXPECT_EQ(receive_code(*b), ErrorCode::kTimeout);

  const std::vector<CanFilter> only_300{CanFilter{0x300, 0x7FF, false}};
  ASSERT_TRUE(b->set_filters(only_300).is_ok());
  ASSERT_TRUE(a->send(frame(0x105), Duration::zero()).is_ok());
  ASSERT_TRUE(a->send(frame(0x300), Duration::zero()).is_ok());
  EXPECT_EQ(b->receive(Duration::zero()).value().id, 0x300U);
  EXPECT_EQ(receive_code(*b), ErrorCode::kTimeout);

  ASSERT_TRUE(b->set_filters({}).is_ok()) << "no filters = everything";
  ASSERT_TRUE(a->send(frame(0x555), Duration::zero()).is_ok());
  EXPECT_EQ(b->receive(Duration::zero()).value().id, 0x555U);
}

TEST_F(VirtualCanNetworkTest, FullReceiveQueueDropsNewFramesAndCountsThem) {
  auto a = open(net, config("vcan0"));
  auto b = open(net, config("vcan0"), VirtualCanNodeOptions{2, true});
  for (std::uint8_t i = 0; i < 5; ++i) ASSERT_TRUE(a->send(frame(0x10, i), Duration::zero()).is_ok());

  EXPECT_EQ(b->queued_frames(), 2U);
  EXPECT_EQ(b->dropped_frames(), 3U);
  EXPECT_EQ(b->status().rx_dropped, 3U);
  EXPECT_EQ(b->receive(Duration::zero()).value().data[0], 0) << "the oldest frames are kept";
  EXPECT_EQ(b->receive(Duration::zero()).value().data[0], 1);
  EXPECT_EQ(receive_code(*b), ErrorCode::kTimeout);
}

TEST_F(VirtualCanNetworkTest, BusOffIsVisibleAndStopsTrafficUntilRecovery) {
  auto a = open(net, config("vcan0"));
  auto b = open(net, config("vcan0"));
  net.set_bus_state("vcan0", CanBusState::kBusOff);

  const CanBusStatus s = a->status();
  EXPECT_EQ(s.state, CanBusState::kBusOff);
  EXPECT_EQ(s.tx_errors, 256);
  EXPECT_EQ(s.error_frames, 1U);
  EXPECT_EQ(a->send(frame(0x1), Duration::zero()).code(), ErrorCode::kUnavailable);
  EXPECT_EQ(receive_code(*b), ErrorCode::kUnavailable);

  net.set_bus_state("vcan0", CanBusState::kErrorActive);
  EXPECT_EQ(a->status().state, CanBusState::kErrorActive);
  EXPECT_EQ(a->status().tx_errors, 0);
  ASSERT_TRUE(a->send(frame(0x2), Duration::zero()).is_ok());
  EXPECT_EQ(b->receive(Duration::zero()).value().id, 0x2U) << "nothing from the bus-off period is left over";
}

TEST_F(VirtualCanNetworkTest, DownInterfaceIsUnavailableButNoErrorFrame) {
  auto a = open(net, config("vcan0"));
  net.set_bus_state("vcan0", CanBusState::kDown);
  EXPECT_EQ(a->status().state, CanBusState::kDown);
  EXPECT_EQ(a->status().error_frames, 0U);
  EXPECT_EQ(a->send(frame(0x1), Duration::zero()).code(), ErrorCode::kUnavailable);
  EXPECT_EQ(receive_code(*a), ErrorCode::kUnavailable);
}

TEST_F(VirtualCanNetworkTest, ErrorPassiveStillCommunicates) {
  auto a = open(net, config("vcan0"));
  auto b = open(net, config("vcan0"));
  net.set_bus_state("vcan0", CanBusState::kErrorPassive);
  EXPECT_EQ(a->status().state, CanBusState::kErrorPassive);
  EXPECT_EQ(a->status().tx_errors, 128);
  ASSERT_TRUE(a->send(frame(0x9), Duration::zero()).is_ok());
  EXPECT_TRUE(b->receive(Duration::zero()).is_ok());
}

TEST_F(VirtualCanNetworkTest, NodeStateAffectsOnlyThatNode) {
  auto a = open(net, config("vcan0"));
  auto b = open(net, config("vcan0"));
  auto c = open(net, config("vcan0"));
  b->set_node_state(CanBusState::kBusOff);
  EXPECT_EQ(a->status().state, CanBusState::kErrorActive);
  EXPECT_EQ(b->status().state, CanBusState::kBusOff);
  ASSERT_TRUE(a->send(frame(0x1), Duration::zero()).is_ok());
  EXPECT_TRUE(c->receive(Duration::zero()).is_ok());
  EXPECT_EQ(b->send(frame(0x2), Duration::zero()).code(), ErrorCode::kUnavailable);

  b->set_node_state(CanBusState::kErrorActive);
  EXPECT_EQ(receive_code(*b), ErrorCode::kTimeout) << "a bus-off controller missed the frame";
  // The worse of bus and node state wins.
  b->set_node_state(CanBusState::kErrorWarning);
  net.set_bus_state("vcan0", CanBusState::kErrorPassive);
  EXPECT_EQ(b->status().state, CanBusState::kErrorPassive);
}

TEST_F(VirtualCanNetworkTest, MalformedFramesAreRejectedAndNotSent) {
  auto a = open(net, config("vcan0"));
  auto b = open(net, config("vcan0"));
  CanFrame oversize = frame(0x1);
  oversize.len = 9;
  EXPECT_EQ(a->send(oversize, Duration::zero()).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(a->send(frame(0x800), Duration::zero()).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(a->send(frame(0x2000'0000, 0, true), Duration::zero()).code(), ErrorCode::kInvalidArgument);
  EXPECT_EQ(receive_code(*b), ErrorCode::kTimeout);
}

TEST_F(VirtualCanNetworkTest, OpenAndSetFiltersRejectInvalidConfiguration) {
  auto no_interface = net.open(config(""));
  ASSERT_FALSE(no_interface.is_ok());
  EXPECT_EQ(no_interface.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(no_interface.error().message.find("test_bus"), std::string::npos) << no_interface.error().message;

  auto wide_filter = net.open(config("vcan0", {CanFilter{0x800, 0x7FF, false}}));
  ASSERT_FALSE(wide_filter.is_ok());
  EXPECT_NE(wide_filter.error().message.find("vcan0"), std::string::npos) << wide_filter.error().message;

  auto zero_queue = net.open(config("vcan0"), VirtualCanNodeOptions{0, true});
  EXPECT_FALSE(zero_queue.is_ok());

  auto a = open(net, config("vcan0"));
  const std::vector<CanFilter> bad{CanFilter{0, 0x2000'0000, true}};
  EXPECT_EQ(a->set_filters(bad).code(), ErrorCode::kInvalidArgument);
}

// A device that emits one numbered frame every 100 ms and records what it heard and when.
class MetronomeDevice final : public VirtualCanDevice {
 public:
  MetronomeDevice(VirtualCanNetwork& net, Time first) : next_(first) {
    node_ = open(net, config("vcan0"), VirtualCanNodeOptions{16, false});
  }
  void advance(Time now) noexcept override {
    advanced_to.push_back(now);
    while (next_ <= now) {
      node_->send(frame(0x700, count_++), Duration::zero()).ignore();
      next_ += milliseconds(100);
    }
    for (Result<CanFrame> f = node_->receive(Duration::zero()); f.is_ok();
         f = node_->receive(Duration::zero())) {
      heard_at.push_back(now);
    }
  }
  [[nodiscard]] Time next_wakeup() const noexcept override { return next_; }

  std::vector<Time> advanced_to;
  std::vector<Time> heard_at;

 private:
  std::unique_ptr<VirtualCanNode> node_;
  Time next_;
  std::uint8_t count_ = 0;
};

TEST_F(VirtualCanNetworkTest, DevicesAdvanceLazilyFromTheClockWhenTheBusIsUsed) {
  const Time t0 = clock.now().mono;
  MetronomeDevice metronome(net, t0);
  net.attach(metronome);
  auto hub = open(net, config("vcan0"));

  EXPECT_EQ(hub->receive(Duration::zero()).value().data[0], 0);
  EXPECT_EQ(receive_code(*hub), ErrorCode::kTimeout);

  clock.advance(milliseconds(250));
  EXPECT_EQ(hub->receive(Duration::zero()).value().data[0], 1);
  EXPECT_EQ(hub->receive(Duration::zero()).value().data[0], 2);
  EXPECT_EQ(receive_code(*hub), ErrorCode::kTimeout) << "the 300 ms frame is not due yet";
  EXPECT_EQ(metronome.advanced_to.back(), t0 + milliseconds(250));

  // A frame the hub sends is handled by the device at the time it was sent.
  clock.advance(milliseconds(20));
  ASSERT_TRUE(hub->send(frame(0x80), Duration::zero()).is_ok());
  ASSERT_EQ(metronome.heard_at.size(), 1U);
  EXPECT_EQ(metronome.heard_at[0], t0 + milliseconds(270));

  // advance_devices() moves devices without touching a node.
  clock.advance(milliseconds(40));
  net.advance_devices();
  EXPECT_EQ(hub->queued_frames(), 1U);

  net.detach(metronome);
  clock.advance(milliseconds(500));
  hub->receive(Duration::zero()).status().ignore();
  EXPECT_EQ(receive_code(*hub), ErrorCode::kTimeout) << "a detached device is never advanced";
}

}  // namespace
}  // namespace hubrt::hal::fake
