// The DigitalInput / DigitalOutput a FakeGpio hands out.
#pragma once

#include <cstdint>

#include "hubrt/hal/common/pulse_catcher.h"
#include "hubrt/hal/digital_io.h"
#include "hubrt/hal/fake/fake_gpio.h"

namespace hubrt::hal::fake {

// What both kinds of device share: the requested line, released when destroyed. Dead (every call
// fails with kUnavailable) once its chip vanished, even if the chip came back.
class FakeLineDevice {
 public:
  FakeLineDevice(FakeGpio& gpio, FakeGpioChip& chip, unsigned line, Polarity polarity) noexcept;
  ~FakeLineDevice();
  FakeLineDevice(const FakeLineDevice&) = delete;
  FakeLineDevice& operator=(const FakeLineDevice&) = delete;

 protected:
  [[nodiscard]] bool alive() const noexcept;
  FakeGpioChip::Line& line() noexcept { return chip_.lines_[line_]; }
  [[nodiscard]] Time now() const noexcept { return gpio_.now(); }
  void settle(bool force = false) noexcept { chip_.settle(line_, gpio_.now(), force); }
  [[nodiscard]] bool was_at_since(bool high, std::uint64_t since) const noexcept {
    return chip_.was_at_since(line_, high, since);
  }

  FakeGpio& gpio_;
  FakeGpioChip& chip_;
  unsigned line_;
  bool active_low_;
  // An output requested with a bias (DigitalOutputConfig::bias_toward_safe) keeps it once
  // released, as gpio-sim keeps a line's pull after its request is freed and sets the line to it
  // (gpio-sim.c, gpio_sim_free), and as the Pi's pinctrl turns a released line into an input with
  // its pull: the line falls to its safe level when the process that drove it is gone.
  bool keep_bias_on_release_ = false;

 private:
  std::uint32_t generation_;
};

class FakeDigitalInput final : public DigitalInput, private FakeLineDevice {
 public:
  FakeDigitalInput(FakeGpio& gpio, FakeGpioChip& chip, const DigitalInputConfig& config) noexcept;

 private:
  Result<bool> do_read(Time now) noexcept override;

  bool catch_pulses_;
  std::uint64_t seen_changes_ = 0;
  PulseCatcher catcher_;
};

class FakeDigitalOutput final : public DigitalOutput, private FakeLineDevice {
 public:
  FakeDigitalOutput(FakeGpio& gpio, FakeGpioChip& chip, const DigitalOutputConfig& config) noexcept;

 private:
  Status do_write(bool active) noexcept override;
  [[nodiscard]] bool do_safe_value() const noexcept override { return safe_; }

  bool safe_;
};

}  // namespace hubrt::hal::fake
