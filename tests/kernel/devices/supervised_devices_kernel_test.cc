// Supervised devices (hubrt/hal/common/supervised_device.h) on the Linux backend in the kernel
// tier: a gpio-sim chip removed under held lines and made again (a GPIO expander unplugged and
// plugged in again), for an input, an output and the smart tool's run lines; a vcan interface
// missing at start, then deleted and made again, for the CAN bus. Time for the back-off comes
// from a ManualClock: nothing here waits for a retry in real time. Skips outside the tier.
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/hal/common/supervised_device.h"
#include "hubrt/hal/linux/backend.h"
#include "hubrt/hal/socketcan/open_socketcan.h"
#include "hubrt/kernel_test/environment.h"
#include "hubrt/kernel_test/gpio_sim.h"
#include "hubrt/runtime/error_list.h"

#include "run_lines.h"

namespace hubrt::kernel_test {
namespace {

using std::chrono::milliseconds;

constexpr unsigned kLines = 8;
constexpr unsigned kInputLine = 1;
constexpr unsigned kForwardLine = 4;
constexpr unsigned kReverseLine = 5;
// gpio-sim shows a driven value at once; generous for a busy emulated guest.
constexpr auto kPatience = milliseconds(5000);

class SupervisedDevicesKernelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    HUBRT_SKIP_OUTSIDE_KERNEL_TIER();
    label_ = fmt::format("hubrt-sup-{}", ::getpid());
    make_chip();
  }

  void make_chip() {
    auto made = ScopedGpioSimChip::create(label_, kLines);
    ASSERT_TRUE(made) << made.error().message;
    chip_.emplace(std::move(*made));
  }
  // Removes the chip while the devices still hold their lines.
  void remove_chip() { chip_.reset(); }

  // By label: the chip comes back as another gpiochipN.
  [[nodiscard]] hal::DigitalInputConfig input_config() const {
    hal::DigitalInputConfig c;
    c.signal = "test.input";
    c.chip = label_;
    c.line = kInputLine;
    return c;
  }
  [[nodiscard]] hal::DigitalOutputConfig output_config(std::string signal, unsigned line) const {
    hal::DigitalOutputConfig c;
    c.signal = std::move(signal);
    c.chip = label_;
    c.line = line;
    return c;
  }
  [[nodiscard]] Time now() const { return clock_.now().mono; }
  void expect_value(unsigned line, int value) {
    auto seen = wait_for_value(chip_->chip(), line, value, kPatience);
    EXPECT_TRUE(seen) << seen.error().message;
  }

  std::string label_;
  std::optional<ScopedGpioSimChip> chip_;
  hal::LinuxBackend backend_{hal::LinuxDeviceLibraries{}};  // GPIO only
  ManualClock clock_;
};

TEST_F(SupervisedDevicesKernelTest, AnInputAndAnOutputRecoverWhenTheirChipIsRemovedAndMadeAgain) {
  hal::SupervisedInput input(backend_, input_config());
  hal::SupervisedOutput output(backend_, output_config("test.output", kForwardLine));
  input.open_now(now());
  output.open_now(now());
  ASSERT_EQ(input.health(), hal::DeviceHealth::kOpen) << input.error();
  ASSERT_EQ(output.health(), hal::DeviceHealth::kOpen) << output.error();
  ASSERT_TRUE(set_pull(chip_->chip(), kInputLine, Pull::kUp));
  ASSERT_TRUE(input.read(now()).value_or(false));
  ASSERT_TRUE(output.write(true, now()).is_ok());
  expect_value(kForwardLine, 1);

  remove_chip();
  EXPECT_EQ(input.read(now()).status().code(), ErrorCode::kUnavailable);
  EXPECT_EQ(output.write(true, now()).code(), ErrorCode::kUnavailable);
  EXPECT_EQ(input.health(), hal::DeviceHealth::kRetrying);
  EXPECT_EQ(output.health(), hal::DeviceHealth::kRetrying);
  EXPECT_EQ(input.error(), "device went away");
  clock_.advance(milliseconds(100));
  EXPECT_FALSE(input.read(now()).is_ok());
  EXPECT_FALSE(output.write(true, now()).is_ok());
  EXPECT_NE(input.error(), "device went away") << "the retry's own reason: the chip is missing";

  make_chip();
  clock_.advance(milliseconds(200));  // the second retry's wait
  const Result<bool> level = input.read(now());
  ASSERT_TRUE(level.is_ok()) << input.error();
  EXPECT_EQ(input.health(), hal::DeviceHealth::kOpen);
  ASSERT_TRUE(set_pull(chip_->chip(), kInputLine, Pull::kUp));
  EXPECT_TRUE(input.read(now()).value_or(false));
  ASSERT_TRUE(output.write(true, now()).is_ok()) << output.error();
  EXPECT_EQ(output.health(), hal::DeviceHealth::kOpen);
  expect_value(kForwardLine, 1);
  EXPECT_EQ(input.supervision().reopens(), 1U);
  EXPECT_EQ(output.supervision().reopens(), 1U);
}

TEST_F(SupervisedDevicesKernelTest, TheSmartToolsRunLinesRecoverWhenTheirChipIsRemovedAndMadeAgain) {
  hal::SupervisedOutput forward(backend_, output_config("tool.run_forward", kForwardLine));
  hal::SupervisedOutput reverse(backend_, output_config("tool.run_reverse", kReverseLine));
  forward.open_now(now());
  reverse.open_now(now());
  tool_ecu::RunLines lines(std::move(forward), std::move(reverse));
  lines.drive(tool_ecu::RunOutput::kReverse, now());
  ASSERT_EQ(lines.shown(), tool_ecu::RunOutput::kReverse);
  expect_value(kForwardLine, 1);
  expect_value(kReverseLine, 1);

  remove_chip();
  lines.drive(tool_ecu::RunOutput::kReverse, now());
  EXPECT_EQ(lines.shown(), tool_ecu::RunOutput::kIdle) << "nothing drives a line that is not open";
  runtime::ErrorList errors;
  lines.report(errors);
  ASSERT_EQ(errors.size(), 2U);
  EXPECT_NE(std::string_view(errors.at(0)).find("run line tool.run_forward not available"),
            std::string_view::npos)
      << errors.at(0);

  make_chip();
  clock_.advance(milliseconds(100));
  lines.drive(tool_ecu::RunOutput::kReverse, now());
  EXPECT_EQ(lines.shown(), tool_ecu::RunOutput::kReverse);
  expect_value(kForwardLine, 1);
  expect_value(kReverseLine, 1);
  errors.clear();
  lines.report(errors);
  EXPECT_EQ(errors.size(), 0U) << errors.at(0);
  lines.drive(tool_ecu::RunOutput::kIdle, now());
  expect_value(kForwardLine, 0);
}

// `ip` runs as root in the guest (the tier makes vcan0 with it too).
bool ip(const std::string& arguments) {
  // NOLINTNEXTLINE(cert-env33-c,concurrency-mt-unsafe): one thread; the command is the test's own
  return std::system(("ip " + arguments + " >/dev/null 2>&1").c_str()) == 0;
}

TEST(SupervisedCanBusKernelTest, ABusMissingAtStartOpensOnceItExistsAndOutlivesItsInterfaceBeingMadeAgain) {
  HUBRT_SKIP_OUTSIDE_KERNEL_TIER();
  const std::string name = fmt::format("hvc{}", ::getpid() % 100000);
  hal::LinuxBackend backend(hal::LinuxDeviceLibraries{
      .open_can = &hal::socketcan::open_socketcan, .open_modbus = nullptr, .open_badge_reader = nullptr});
  ManualClock clock;
  hal::CanConfig config;
  config.bus = "tool_bus";
  config.interface = name;
  hal::SupervisedCanBus bus(backend, config);
  bus.open_now(clock.now().mono);
  EXPECT_EQ(bus.health(), hal::DeviceHealth::kNeverOpened);
  EXPECT_NE(bus.error().find(name), std::string_view::npos) << bus.error();

  ASSERT_TRUE(ip(fmt::format("link add dev {} type vcan", name)));
  ASSERT_TRUE(ip(fmt::format("link set dev {} up", name)));
  clock.advance(milliseconds(100));
  hal::CanBus* opened = bus.device(clock.now().mono);
  ASSERT_NE(opened, nullptr) << bus.error();

  // The interface goes and comes back: SocketCAN re-binds the same bus; nothing is dropped.
  ASSERT_TRUE(ip(fmt::format("link del dev {}", name)));
  ASSERT_TRUE(ip(fmt::format("link add dev {} type vcan", name)));
  ASSERT_TRUE(ip(fmt::format("link set dev {} up", name)));
  auto sender = backend.open_can(config);
  ASSERT_TRUE(sender) << sender.error().message;
  hal::CanFrame frame;
  frame.id = 0x123;
  frame.len = 1;
  frame.data[0] = 0x5a;
  bool received = false;
  for (int attempt = 0; attempt < 50 && !received; ++attempt) {
    ASSERT_TRUE((*sender)->send(frame, milliseconds(100)).is_ok());
    const Result<hal::CanFrame> got = [&] {
      const Result<hal::CanFrame> r = bus.device(clock.now().mono)->receive(milliseconds(100));
      if (!r.is_ok()) bus.observe(r.status().code(), clock.now().mono);
      return r;
    }();
    received = got.is_ok() && got.value().id == 0x123;
  }
  EXPECT_TRUE(received);
  EXPECT_EQ(bus.device(clock.now().mono), opened);
  EXPECT_EQ(bus.supervision().drops(), 0U);
  ip(fmt::format("link del dev {}", name));
}

}  // namespace
}  // namespace hubrt::kernel_test
