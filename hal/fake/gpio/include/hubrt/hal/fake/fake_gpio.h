// The fake GPIO world: chips keyed by name, the simulated devices wired to them, and the
// DigitalInput / DigitalOutput factories a FakeBackend hands out.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/digital_io.h"
#include "hubrt/hal/fake/fake_gpio_chip.h"
#include "hubrt/hal/fake/simulator.h"

namespace hubrt::hal::fake {

// Time comes from `clock` only: no threads, nothing moves between two calls, and with a
// ManualClock every run is the same. Before any read, write or hook, every simulator is brought up
// to the clock's now (advance()), so scheduled changes appear at their exact times.
//
// Not thread-safe: the FakeGpio, its chips, simulators and devices belong to one thread (a bridge
// that pokes it from elsewhere must hand its pokes to that thread). Never allocates after setup
// except when a device is opened.
class FakeGpio {
 public:
  // Lines keep this many level changes each (older ones are dropped).
  static constexpr std::size_t kDefaultHistoryCapacity = 256;

  // `clock` must outlive this object.
  explicit FakeGpio(const Clock& clock) noexcept : clock_(clock) {}
  FakeGpio(const FakeGpio&) = delete;
  FakeGpio& operator=(const FakeGpio&) = delete;

  // Adds a chip under `name`: the string configs put in `chip` to reach it (in host-sim.yaml the
  // chip's label, e.g. "sim-dock"). Precondition: no chip of that name yet, num_lines > 0.
  FakeGpioChip& add_chip(std::string name, unsigned num_lines,
                         std::size_t history_capacity = kDefaultHistoryCapacity);
  // The chip of that name, present or vanished; nullptr when there is none.
  [[nodiscard]] FakeGpioChip* chip(std::string_view name) noexcept;
  [[nodiscard]] std::vector<std::string> chip_names() const;

  // Takes ownership of a simulator; it is advanced before every operation from now on.
  template <class T>
  T& add_simulator(std::unique_ptr<T> simulator) {
    T& ref = *simulator;
    simulators_.push_back(std::move(simulator));
    return ref;
  }

  // Brings every simulator up to the clock's now. Re-entrant calls (a simulator reading a line
  // while it advances) do nothing.
  void advance() noexcept;
  [[nodiscard]] Time now() const noexcept { return clock_.now().mono; }
  [[nodiscard]] const Clock& clock() const noexcept { return clock_; }

  // Requests a line as the Linux backend would, with the same errors, consumer name ("hubrt") and
  // polarity rules. No debouncing here (FakeBackend adds it).
  // Errors: kNotFound (no such chip, or vanished: the message lists the chips present),
  // kPermissionDenied (deny_access), kOutOfRange (line beyond the chip), kBusy (line held: the
  // message names the holder). The devices fail with kUnavailable once their chip vanished and
  // with kIo while fail_reads / fail_writes is set. They must not outlive this FakeGpio.
  Expected<std::unique_ptr<DigitalInput>> open_input(const DigitalInputConfig& config);
  Expected<std::unique_ptr<DigitalOutput>> open_output(const DigitalOutputConfig& config);

 private:
  Expected<FakeGpioChip*> find_line(std::string_view signal, const std::string& chip, unsigned line);

  const Clock& clock_;
  std::vector<std::unique_ptr<FakeGpioChip>> chips_;
  std::vector<std::unique_ptr<Simulator>> simulators_;
  bool advancing_ = false;
};

}  // namespace hubrt::hal::fake
