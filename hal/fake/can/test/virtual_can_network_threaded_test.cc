// The virtual network in real time: blocking receives woken by other threads, by due devices and
// by state changes. Bounds are generous because this 2-core machine is shared and scheduling
// noise reaches tens of milliseconds; each bound says what it guards against.
#include <atomic>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/hal/fake/virtual_can_network.h"

namespace hubrt::hal::fake {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using Steady = std::chrono::steady_clock;

CanConfig config() {
  CanConfig c;
  c.bus = "threaded";
  c.interface = "vcan0";
  return c;
}

CanFrame frame(std::uint32_t id) {
  CanFrame f;
  f.id = id;
  f.len = 0;
  return f;
}

TEST(VirtualCanNetworkThreaded, BlockedReceiverWakesWhenAnotherThreadSends) {
  SystemClock clock;
  VirtualCanNetwork net(clock);
  auto tx = std::move(*net.open(config()));
  auto rx = std::move(*net.open(config()));

  Result<CanFrame> got = Status(ErrorCode::kInternal);
  Steady::duration waited{};
  std::thread receiver([&] {
    const auto start = Steady::now();
    got = rx->receive(seconds(10));
    waited = Steady::now() - start;
  });
  ASSERT_TRUE(tx->send(frame(0x42), Duration::zero()).is_ok());
  receiver.join();
  ASSERT_TRUE(got.is_ok());
  EXPECT_EQ(got.value().id, 0x42U);
  // Far below the 10 s timeout: the frame, not the timeout, ended the wait.
  EXPECT_LT(waited, seconds(5));
}

// A device due in 30 ms of real time: a receive blocked for up to 5 s must wake for it.
class OneShotDevice final : public VirtualCanDevice {
 public:
  OneShotDevice(VirtualCanNetwork& net, Time due) : due_(due) {
    CanConfig c = config();
    node_ = std::move(*net.open(c, VirtualCanNodeOptions{4, false}));
  }
  void advance(Time now) noexcept override {
    if (!fired_.load() && now >= due_) {
      fired_ = true;
      node_->send(frame(0x701), Duration::zero()).ignore();
    }
  }
  [[nodiscard]] Time next_wakeup() const noexcept override { return fired_.load() ? Time::max() : due_; }

 private:
  std::unique_ptr<VirtualCanNode> node_;
  Time due_;
  std::atomic<bool> fired_{false};
};

TEST(VirtualCanNetworkThreaded, BlockedReceiverWakesWhenADeviceFallsDue) {
  SystemClock clock;
  VirtualCanNetwork net(clock);
  const Time due = clock.now().mono + milliseconds(30);
  OneShotDevice device(net, due);
  net.attach(device);
  auto hub = std::move(*net.open(config()));

  const auto start = Steady::now();
  const Result<CanFrame> got = hub->receive(seconds(5));
  const auto waited = Steady::now() - start;
  net.detach(device);

  ASSERT_TRUE(got.is_ok());
  EXPECT_EQ(got.value().id, 0x701U);
  EXPECT_GE(clock.now().mono, due) << "the device must not fire early";
  // Well below 5 s: the device's due time, not the timeout, woke the receiver.
  EXPECT_LT(waited, seconds(2));
}

TEST(VirtualCanNetworkThreaded, BusGoingDownWakesBlockedReceiver) {
  SystemClock clock;
  VirtualCanNetwork net(clock);
  auto rx = std::move(*net.open(config()));
  ErrorCode code = ErrorCode::kOk;
  std::thread receiver([&] { code = rx->receive(seconds(10)).status().code(); });
  net.set_bus_state("vcan0", CanBusState::kDown);
  receiver.join();
  EXPECT_EQ(code, ErrorCode::kUnavailable);
}

TEST(VirtualCanNetworkThreaded, ConcurrentSendersLoseNothing) {
  SystemClock clock;
  VirtualCanNetwork net(clock);
  constexpr int kPerSender = 500;
  auto a = std::move(*net.open(config()));
  auto b = std::move(*net.open(config()));
  auto rx =
      std::move(*net.open(config(), VirtualCanNodeOptions{static_cast<std::size_t>(2 * kPerSender), true}));

  auto send_all = [](VirtualCanNode& node, std::uint32_t id) {
    for (int i = 0; i < kPerSender; ++i) ASSERT_TRUE(node.send(frame(id), Duration::zero()).is_ok());
  };
  std::thread ta(send_all, std::ref(*a), 0x1);
  std::thread tb(send_all, std::ref(*b), 0x2);
  int from_a = 0;
  int from_b = 0;
  while (from_a + from_b < 2 * kPerSender) {
    const Result<CanFrame> got = rx->receive(seconds(5));
    ASSERT_TRUE(got.is_ok()) << "frames were lost";
    (got.value().id == 0x1 ? from_a : from_b)++;
  }
  ta.join();
  tb.join();
  EXPECT_EQ(from_a, kPerSender);
  EXPECT_EQ(from_b, kPerSender);
  EXPECT_EQ(rx->dropped_frames(), 0U);
}

}  // namespace
}  // namespace hubrt::hal::fake
