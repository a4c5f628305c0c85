#include <array>
#include <cerrno>
#include <cstdint>
#include <ctime>

#include <fmt/format.h>
#include <gpiod.h>

#include "hubrt/hal/common/pulse_catcher.h"
#include "hubrt/hal/linux/gpiod_lines.h"

#include "gpiod_chip.h"
#include "gpiod_errors.h"

namespace hubrt::hal {
namespace {

using gpiod_detail::line_io_status;
using gpiod_detail::LineHandle;

int polarity_flags(Polarity polarity) noexcept {
  return polarity == Polarity::kActiveLow ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
}

int bias_flags(Bias bias) noexcept {
  switch (bias) {
    case Bias::kAsIs:
      return 0;
    case Bias::kDisabled:
      return GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE;
    case Bias::kPullUp:
      return GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
    case Bias::kPullDown:
      return GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN;
  }
  return 0;
}

std::int64_t to_ns(const timespec& ts) noexcept {
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

std::int64_t monotonic_ns() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return to_ns(ts);
}

// The active-low flag makes the kernel invert the value we read, so levels here are logical.
//
// Pulses: the v1 uAPI stamps an edge event in the hard interrupt (CLOCK_MONOTONIC), but queues it
// from the interrupt *thread*, which also decides its rising/falling type from the line's level
// at that moment: after a short pulse both edges say "falling", and edges faster than the thread
// merge into one event. So types are not trusted and events are placed in time against our last
// two samples (each stamped just after its value was read):
//   - an event stamped after the last sample: the line changed since; if it shows the sampled
//     level now, it was at the other one in between;
//   - an event stamped between the two samples, when both read the same level, was queued too
//     late for the last read: a pulse came and went in that interval.
// Events queued more than one polling period late are not placed (the kernel delivers within
// milliseconds); a change between an interrupt and the sample's stamp counts as before the
// sample, which can lose a pulse of a few microseconds but never invents one.
class GpiodInput final : public DigitalInput {
 public:
  GpiodInput(LineHandle line, bool catch_pulses, bool initial_level) noexcept
      : line_(std::move(line)), catch_pulses_(catch_pulses) {
    last_ = previous_ = Sample{monotonic_ns(), initial_level};
    catcher_.report(initial_level, false);
  }

 private:
  struct Sample {
    std::int64_t at_ns = 0;  // CLOCK_MONOTONIC, as the kernel stamps events
    bool level = false;
  };
  // The kernel queues 16 events per line; a few rounds of that bound the work done per read even
  // when the line chatters faster than we can drain it (the pulse is caught by then anyway).
  static constexpr unsigned kEventsPerRead = 16;
  static constexpr int kMaxDrainRounds = 4;

  Result<bool> do_read(Time /*now*/) noexcept override {
    bool saw_other_level = false;
    if (catch_pulses_) {
      const Status drained = drain_events(saw_other_level);
      if (!drained.is_ok()) return drained;
    }
    errno = 0;
    const int value = gpiod_line_get_value(line_.line());
    if (value < 0) return line_io_status(errno);
    if (!catch_pulses_) return value == 1;
    previous_ = last_;
    last_ = Sample{monotonic_ns(), value == 1};
    return catcher_.report(value == 1, saw_other_level);
  }

  [[nodiscard]] bool shows_a_change(std::int64_t stamped_ns) const noexcept {
    if (stamped_ns > last_.at_ns) return true;
    return stamped_ns > previous_.at_ns && previous_.level == last_.level;
  }

  // Reads every queued event without waiting; notes whether one shows the line left its level.
  Status drain_events(bool& saw_other_level) noexcept {
    std::array<gpiod_line_event, kEventsPerRead> events{};
    const timespec no_wait{0, 0};
    for (int round = 0; round < kMaxDrainRounds; ++round) {
      errno = 0;
      const int ready = gpiod_line_event_wait(line_.line(), &no_wait);
      if (ready < 0) return line_io_status(errno);
      if (ready == 0) break;
      errno = 0;
      const int count = gpiod_line_event_read_multiple(line_.line(), events.data(), kEventsPerRead);
      if (count < 0) return line_io_status(errno);
      for (int i = 0; i < count; ++i) {
        if (shows_a_change(to_ns(events[static_cast<std::size_t>(i)].ts))) saw_other_level = true;
      }
    }
    return Status::ok();
  }

  LineHandle line_;
  bool catch_pulses_;
  Sample last_;
  Sample previous_;
  PulseCatcher catcher_;
};

}  // namespace

Expected<std::unique_ptr<DigitalInput>> open_gpiod_input(const DigitalInputConfig& config) {
  auto line = gpiod_detail::find_line(config.signal, config.chip, config.line);
  if (!line) return std::move(line).error();
  const int request_type =
      config.catch_pulses ? GPIOD_LINE_REQUEST_EVENT_BOTH_EDGES : GPIOD_LINE_REQUEST_DIRECTION_INPUT;
  const int flags = polarity_flags(config.polarity) | bias_flags(config.bias);
  auto requested = gpiod_detail::request_line(*line, config.signal, request_type, flags, 0);
  if (!requested) return std::move(requested).error();
  // The level at the request is where pulse catching starts from.
  errno = 0;
  const int initial = gpiod_line_get_value(line->line());
  if (initial < 0) {
    const int err = errno;
    return make_error(line_io_status(err).code(),
                      fmt::format("{}: cannot read {}: {}", config.signal, line->description(),
                                  gpiod_detail::errno_text(err)));
  }
  return std::unique_ptr<DigitalInput>(
      std::make_unique<GpiodInput>(std::move(*line), config.catch_pulses, initial == 1));
}

}  // namespace hubrt::hal
