// SupervisedDevice on the fake GPIO chips and the virtual CAN network: opening at start, a chip
// that is missing or vanishes and returns, the back-off's timing under a manual clock, health,
// the error text and the counters; outputs driving nothing while not open.
#include "hubrt/hal/common/supervised_device.h"

#include <gtest/gtest.h>

#include "hubrt/hal/fake/fake_gpio.h"
#include "hubrt/hal/fake/virtual_can_network.h"

namespace hubrt::hal {
namespace {

using std::chrono::milliseconds;

// A Backend over the fake GPIO world and a virtual CAN network whose interface can be missing;
// counts every open call.
class TestBackend final : public Backend {
 public:
  explicit TestBackend(const Clock& clock) : gpio(clock), network(clock) {}
  Expected<std::unique_ptr<DigitalInput>> open_input(const DigitalInputConfig& config) override {
    ++opens;
    return gpio.open_input(config);
  }
  Expected<std::unique_ptr<DigitalOutput>> open_output(const DigitalOutputConfig& config) override {
    ++opens;
    return gpio.open_output(config);
  }
  Expected<std::unique_ptr<CanBus>> open_can(const CanConfig& config) override {
    ++opens;
    if (!can_present)
      return make_error(ErrorCode::kNotFound, config.bus + ": no interface " + config.interface);
    auto node = network.open(config);
    if (!node) return std::move(node).error();
    return std::unique_ptr<CanBus>(std::move(*node));
  }
  Expected<std::unique_ptr<ModbusClient>> open_modbus(const ModbusConfig& /*config*/) override {
    return make_error(ErrorCode::kNotFound, "no Modbus here");
  }

  fake::FakeGpio gpio;
  fake::VirtualCanNetwork network;
  bool can_present = false;
  int opens = 0;
};

class SupervisedDeviceTest : public ::testing::Test {
 protected:
  SupervisedDeviceTest() : chip_(backend_.gpio.add_chip("expander", 8)) {}

  [[nodiscard]] Time now() const { return clock_.now().mono; }
  static DigitalInputConfig input_config() {
    DigitalInputConfig c;
    c.signal = "dock.slot.smart_tool";
    c.chip = "expander";
    c.line = 2;
    return c;
  }
  static DigitalOutputConfig output_config() {
    DigitalOutputConfig c;
    c.signal = "rsp.lock_valve";
    c.chip = "expander";
    c.line = 5;
    c.initial = false;
    c.safe = false;
    return c;
  }
  // The output line's electrical level (active high).
  bool line5() const { return chip_.level(5).value(); }

  ManualClock clock_;
  TestBackend backend_{clock_};
  fake::FakeGpioChip& chip_;
};

TEST_F(SupervisedDeviceTest, OpensAtStartAndReadsWithoutReopening) {
  ASSERT_TRUE(chip_.set_input_level(2, true).is_ok());
  SupervisedInput input(backend_, input_config());
  EXPECT_EQ(input.health(), DeviceHealth::kNeverOpened);
  EXPECT_EQ(input.error(), "not opened yet");
  input.open_now(now());
  EXPECT_EQ(input.health(), DeviceHealth::kOpen);
  EXPECT_TRUE(input.error().empty());
  for (int i = 0; i < 3; ++i) {
    const Result<bool> level = input.read(now());
    ASSERT_TRUE(level.is_ok());
    EXPECT_TRUE(level.value());
  }
  EXPECT_EQ(backend_.opens, 1);
  EXPECT_EQ(input.supervision().reopen_attempts(), 0U);
}

TEST_F(SupervisedDeviceTest, AMissingChipIsRetriedWithADoublingBackOffUpToItsCap) {
  chip_.vanish();
  SupervisedInput input(backend_, input_config());
  const Time start = now();
  input.open_now(start);
  EXPECT_EQ(input.health(), DeviceHealth::kNeverOpened);
  EXPECT_NE(input.error().find("dock.slot.smart_tool"), std::string_view::npos) << input.error();
  // Retries at 0.1, 0.3, 0.7, 1.5, 3.1, 5.1, 7.1 s: waits of 0.1 s doubling to the 2 s cap.
  const int expected_at_ms[] = {100, 300, 700, 1500, 3100, 5100, 7100};
  std::vector<int> attempts_at_ms;
  for (int ms = 1; ms <= 7100; ++ms) {
    clock_.set(start + milliseconds(ms));
    const int before = backend_.opens;
    EXPECT_EQ(input.read(now()).status().code(), ErrorCode::kUnavailable);
    if (backend_.opens != before) attempts_at_ms.push_back(ms);
  }
  EXPECT_EQ(attempts_at_ms, std::vector<int>(std::begin(expected_at_ms), std::end(expected_at_ms)));
  EXPECT_EQ(input.supervision().reopen_attempts(), 7U);
  EXPECT_EQ(input.health(), DeviceHealth::kNeverOpened);

  chip_.reappear();
  clock_.set(start + milliseconds(9099));
  EXPECT_FALSE(input.read(now()).is_ok()) << "no retry before it is due: opening is not free";
  clock_.set(start + milliseconds(9100));
  EXPECT_TRUE(input.read(now()).is_ok());
  EXPECT_EQ(input.health(), DeviceHealth::kOpen);
  EXPECT_TRUE(input.error().empty());
  EXPECT_EQ(input.supervision().reopens(), 1U);
}

TEST_F(SupervisedDeviceTest, AnInputWhoseChipVanishesIsDroppedAndOpenedAgainWhenItReturns) {
  SupervisedInput input(backend_, input_config());
  input.open_now(now());
  ASSERT_TRUE(input.read(now()).is_ok());

  chip_.vanish();
  EXPECT_EQ(input.read(now()).status().code(), ErrorCode::kUnavailable);
  EXPECT_EQ(input.health(), DeviceHealth::kRetrying);
  EXPECT_EQ(input.error(), "device went away");
  EXPECT_EQ(input.supervision().drops(), 1U);
  clock_.advance(milliseconds(100));
  EXPECT_FALSE(input.read(now()).is_ok());
  EXPECT_NE(input.error().find("not found"), std::string_view::npos) << input.error();
  EXPECT_EQ(input.health(), DeviceHealth::kRetrying);

  chip_.reappear();
  ASSERT_TRUE(chip_.set_input_level(2, true).is_ok());
  clock_.advance(milliseconds(199));
  EXPECT_FALSE(input.read(now()).is_ok()) << "the second retry waits 0.2 s";
  clock_.advance(milliseconds(1));
  const Result<bool> level = input.read(now());
  ASSERT_TRUE(level.is_ok());
  EXPECT_TRUE(level.value()) << "a new device: the old one belonged to the vanished chip";
  EXPECT_EQ(input.health(), DeviceHealth::kOpen);
  EXPECT_EQ(input.supervision().reopen_attempts(), 2U);
  EXPECT_EQ(input.supervision().reopens(), 1U);

  // A second loss starts the back-off over at 0.1 s.
  chip_.vanish();
  chip_.reappear();
  EXPECT_FALSE(input.read(now()).is_ok());
  clock_.advance(milliseconds(100));
  EXPECT_TRUE(input.read(now()).is_ok());
}

TEST_F(SupervisedDeviceTest, AReadThatFailsWithoutTheChipGoingAwayKeepsTheDevice) {
  SupervisedInput input(backend_, input_config());
  input.open_now(now());
  ASSERT_TRUE(chip_.fail_reads(2, true).is_ok());
  EXPECT_EQ(input.read(now()).status().code(), ErrorCode::kIo);
  EXPECT_EQ(input.health(), DeviceHealth::kOpen);
  ASSERT_TRUE(chip_.fail_reads(2, false).is_ok());
  EXPECT_TRUE(input.read(now()).is_ok());
  EXPECT_EQ(backend_.opens, 1);
}

TEST_F(SupervisedDeviceTest, AnOutputDrivesNothingWhileGoneAndStartsAtItsInitialLevelWhenBack) {
  SupervisedOutput output(backend_, output_config());
  output.open_now(now());
  ASSERT_TRUE(output.write(true, now()).is_ok());
  EXPECT_TRUE(line5());
  EXPECT_TRUE(output.driven());

  chip_.vanish();
  EXPECT_EQ(output.write(true, now()).code(), ErrorCode::kUnavailable);
  EXPECT_EQ(output.health(), DeviceHealth::kRetrying);
  EXPECT_FALSE(output.driven()) << "nothing drives a line that is not open";
  EXPECT_EQ(chip_.holder(5), std::nullopt);

  chip_.reappear();
  ASSERT_TRUE(chip_.set_input_level(5, true).is_ok());  // left high by whatever drove it last
  ASSERT_TRUE(chip_.release_input(5).is_ok());
  clock_.advance(milliseconds(100));
  // The write that re-opens the line drives it after the open put it at `initial` (low).
  const std::size_t changes_before = chip_.history(5).size();
  ASSERT_TRUE(output.write(true, now()).is_ok());
  const auto history = chip_.history(5);
  ASSERT_EQ(history.size(), changes_before + 2) << "opened at initial, then driven";
  EXPECT_FALSE(history[history.size() - 2].high);
  EXPECT_TRUE(history.back().high);
  EXPECT_EQ(chip_.holder(5), std::string(fake::kFakeGpioConsumer));
}

TEST_F(SupervisedDeviceTest, WriteSafeIfOpenNeverOpensAndDropsALineFoundGone) {
  chip_.vanish();
  SupervisedOutput output(backend_, output_config());
  output.open_now(now());
  EXPECT_EQ(output.write_safe_if_open().code(), ErrorCode::kUnavailable);
  EXPECT_EQ(backend_.opens, 1) << "no time at hand: no retry";

  chip_.reappear();
  clock_.advance(milliseconds(100));
  ASSERT_TRUE(output.write(true, now()).is_ok());
  EXPECT_TRUE(output.write_safe_if_open().is_ok());
  EXPECT_FALSE(line5());

  chip_.vanish();
  EXPECT_EQ(output.write_safe_if_open().code(), ErrorCode::kUnavailable);
  EXPECT_EQ(output.health(), DeviceHealth::kRetrying);
  chip_.reappear();
  EXPECT_TRUE(output.write(false, now()).is_ok()) << "a line dropped without a time is retried at once";
}

TEST_F(SupervisedDeviceTest, ACanBusMissingAtStartIsOpenedOnceItExistsAndKeptWhileDown) {
  CanConfig config;
  config.bus = "tool_bus";
  config.interface = "vcan0";
  SupervisedCanBus bus(backend_, config);
  bus.open_now(now());
  EXPECT_EQ(bus.health(), DeviceHealth::kNeverOpened);
  EXPECT_EQ(bus.error(), "tool_bus: no interface vcan0");
  EXPECT_EQ(bus.device(now()), nullptr);

  backend_.can_present = true;
  clock_.advance(milliseconds(100));
  CanBus* opened = bus.device(now());
  ASSERT_NE(opened, nullptr);
  EXPECT_EQ(bus.health(), DeviceHealth::kOpen);

  // Down is a state of the bus that SocketCAN recovers from by itself: the bus is kept.
  backend_.network.set_bus_state("vcan0", CanBusState::kDown);
  const Result<CanFrame> frame = opened->receive(Duration{0});
  EXPECT_EQ(frame.status().code(), ErrorCode::kUnavailable);
  bus.observe(frame.status().code(), now());
  EXPECT_EQ(bus.device(now()), opened);
  EXPECT_EQ(bus.supervision().drops(), 0U);
}

TEST_F(SupervisedDeviceTest, ALongErrorIsCutAtACharacterAndMarked) {
  DeviceSupervision supervision(kDefaultBackOff);
  std::string text(DeviceSupervision::kErrorCapacity - 4, 'x');
  text += "\xc3\xa9\xc3\xa9\xc3\xa9";  // "ééé" across the cut
  supervision.open_failed(text, Time{});
  const std::string_view error = supervision.error();
  ASSERT_LE(error.size(), DeviceSupervision::kErrorCapacity);
  EXPECT_EQ(error.substr(error.size() - 3), "...");
  EXPECT_EQ(error.substr(0, error.size() - 3), text.substr(0, error.size() - 3));
  EXPECT_NE(static_cast<unsigned char>(error[error.size() - 4]), 0xc3U) << "no lead byte without its tail";
}

}  // namespace
}  // namespace hubrt::hal
