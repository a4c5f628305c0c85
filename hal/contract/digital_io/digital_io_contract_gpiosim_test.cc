// The digital I/O contract on the Linux backend (libgpiod v1) against gpio-sim, in the kernel
// tier (tests/kernel/run). Each test gets a fresh chip, reached by its label; the tier's gpio-sim
// pull/value files play the wiring. Skips outside the tier.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <string>

#include "hubrt/hal/linux/backend.h"
#include "hubrt/kernel_test/environment.h"
#include "hubrt/kernel_test/gpio_sim.h"

#include "digital_io_contract.h"

namespace hubrt::hal::contract {
namespace {

constexpr unsigned kLines = 8;

class GpioSimHarness final : public DigitalIoHarness {
 public:
  explicit GpioSimHarness(kernel_test::ScopedGpioSimChip chip) : chip_(std::move(chip)) {}

  Backend& backend() override { return backend_; }
  [[nodiscard]] std::string chip() const override { return chip_.chip().label; }
  [[nodiscard]] unsigned num_lines() const override { return chip_.chip().num_lines; }
  [[nodiscard]] std::vector<unsigned> input_lines() const override { return {0, 1}; }
  [[nodiscard]] std::vector<unsigned> output_lines() const override { return {4, 5}; }
  Expected<void> drive(unsigned line, bool high) override {
    return kernel_test::set_pull(chip_.chip(), line,
                                 high ? kernel_test::Pull::kUp : kernel_test::Pull::kDown);
  }
  Expected<bool> observe(unsigned line) override {
    auto value = kernel_test::read_value(chip_.chip(), line);
    if (!value) return std::move(value).error();
    return *value == 1;
  }
  [[nodiscard]] Time now() const override { return clock_.now().mono; }
  void advance(Duration d) override { clock_.advance(d); }
  // Edge events reach the line's file through the kernel's interrupt thread.
  [[nodiscard]] bool edges_immediate() const override { return false; }
  // Takes the simulated device down (as unbinding a driver would); ScopedGpioSimChip then deletes it.
  bool remove_chip() override {
    const std::string live = "/sys/kernel/config/gpio-sim/" + chip_.chip().label + "/live";
    const int fd = ::open(live.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) return false;
    const bool written = ::write(fd, "0", 1) == 1;
    ::close(fd);
    return written;
  }

 private:
  kernel_test::ScopedGpioSimChip chip_;
  LinuxBackend backend_{LinuxDeviceLibraries{}};  // GPIO only
  ManualClock clock_;
};

std::unique_ptr<DigitalIoHarness> gpio_sim() {
  if (!kernel_test::in_kernel_tier()) return nullptr;
  static std::atomic<int> made{0};
  const std::string name = "hubrt-dio-" + std::to_string(::getpid()) + "-" + std::to_string(made++);
  auto chip = kernel_test::ScopedGpioSimChip::create(name, kLines);
  if (!chip) {
    ADD_FAILURE() << chip.error().message;
    return nullptr;
  }
  return std::make_unique<GpioSimHarness>(std::move(*chip));
}

INSTANTIATE_TEST_SUITE_P(Linux, DigitalIoContract,
                         ::testing::Values(DigitalIoContractBackend{"GpioSim", gpio_sim,
                                                                    kernel_test::kNotInKernelTier}),
                         DigitalIoContractName{});

}  // namespace
}  // namespace hubrt::hal::contract
