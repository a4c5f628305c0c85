#include "fake_line_device.h"

namespace hubrt::hal::fake {

FakeLineDevice::FakeLineDevice(FakeGpio& gpio, FakeGpioChip& chip, unsigned line, Polarity polarity) noexcept
    : gpio_(gpio),
      chip_(chip),
      line_(line),
      active_low_(polarity == Polarity::kActiveLow),
      generation_(chip.generation_) {}

FakeLineDevice::~FakeLineDevice() {
  if (!alive()) return;
  // Released lines keep their level (nothing drives them any more) and lose their bias request,
  // except an output's pull toward its safe level, which then decides the level.
  line().use = FakeGpioChip::Use::kFree;
  if (!keep_bias_on_release_) line().bias = Bias::kAsIs;
  settle();
}

bool FakeLineDevice::alive() const noexcept {
  return chip_.present_ && chip_.generation_ == generation_;
}

FakeDigitalInput::FakeDigitalInput(FakeGpio& gpio, FakeGpioChip& chip,
                                   const DigitalInputConfig& config) noexcept
    : FakeLineDevice(gpio, chip, config.line, config.polarity), catch_pulses_(config.catch_pulses) {
  line().use = FakeGpioChip::Use::kInput;
  line().bias = config.bias;
  settle();
  seen_changes_ = line().changes;
  // As the Linux backend: pulse catching starts from the level at the request.
  catcher_.report(line().level != active_low_, false);
}

Result<bool> FakeDigitalInput::do_read(Time /*now*/) noexcept {
  gpio_.advance();
  if (!alive()) return Status(ErrorCode::kUnavailable);
  if (line().fail_reads) return Status(ErrorCode::kIo);
  const bool active = line().level != active_low_;
  if (!catch_pulses_) return active;
  // The history plays the part of the kernel's edge events.
  const bool other = !catcher_.reported().value_or(active);
  const bool saw_other = was_at_since(other != active_low_, seen_changes_);
  seen_changes_ = line().changes;
  return catcher_.report(active, saw_other);
}

FakeDigitalOutput::FakeDigitalOutput(FakeGpio& gpio, FakeGpioChip& chip,
                                     const DigitalOutputConfig& config) noexcept
    : FakeLineDevice(gpio, chip, config.line, config.polarity), safe_(config.safe) {
  line().use = FakeGpioChip::Use::kOutput;
  line().output_level = config.initial != active_low_;
  if (config.bias_toward_safe) {
    // As the Linux backend's request flags (gpiod_output.cc): pull-up when the safe level is high.
    line().bias = config.safe != active_low_ ? Bias::kPullUp : Bias::kPullDown;
    keep_bias_on_release_ = true;
  }
  settle(/*force=*/true);
}

Status FakeDigitalOutput::do_write(bool active) noexcept {
  gpio_.advance();
  if (!alive()) return Status(ErrorCode::kUnavailable);
  if (line().fail_writes) return Status(ErrorCode::kIo);
  line().output_level = active != active_low_;
  settle();
  return Status::ok();
}

}  // namespace hubrt::hal::fake
