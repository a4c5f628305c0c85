// A device that is opened again when it goes away: the one way every hub keeps its GPIO lines and
// CAN buses. It holds what it takes to open the device (the Backend and the device's config),
// opens it at start, and when the device is missing or goes away it drops it and opens it again
// with a back-off, so that a GPIO expander unplugged and plugged in again, or a chip that was not
// there at start-up, never needs a restart of the hub. Its health, the reason it is not open and
// its counters are there for the node's State and /diagnostics.
//
// Which failures mean "gone": a device's own contract says it (hubrt/hal/digital_io.h: a line
// fails with kUnavailable once its chip went away). A CAN bus is never dropped once open:
// SocketCAN re-binds a re-created interface and leaves bus-off by itself (open_socketcan.h), so its
// kUnavailable is a state of the bus, not a dead handle; only a bus that could not be opened yet
// (no such interface at start) is retried.
//
// Back-off: the first retry comes kDefaultBackOff.first (0.1 s) after the failure, each failed
// retry doubles the wait up to kDefaultBackOff.cap (2 s); a successful open starts over. Time is
// passed in: nothing here reads a clock.
//
// Outputs: while an output is not open nothing drives its line. The line sits where the hardware
// leaves an undriven line (its pull resistor, the driver de-energised), which the wiring must make
// the safe state (DESIGN.md: valves and run lines are safe de-energised); a line that is opened
// again starts at its board `initial` level before the caller's next write drives it.
//
// Allocation: opening (at start and on retry) allocates; reading or writing an open device, the
// health and the error text do not (the text lives in a fixed buffer).
// Thread-safety: none; one owner (the node, on the cycle thread).
#pragma once

#include <chrono>
#include <concepts>
#include <cstdint>
#include <memory>
#include <new>
#include <string_view>
#include <utility>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/backend.h"
#include "hubrt/hal/common/device_supervision.h"

namespace hubrt::hal {

// How to open each kind of device and which of its failures mean it is gone.
template <class Device>
struct DeviceOpener;

template <>
struct DeviceOpener<DigitalInput> {
  using Config = DigitalInputConfig;
  static Expected<std::unique_ptr<DigitalInput>> open(Backend& backend, const Config& config) {
    return backend.open_input(config);
  }
  static std::string_view name(const Config& config) noexcept { return config.signal; }
  static constexpr bool gone(ErrorCode code) noexcept { return code == ErrorCode::kUnavailable; }
};

template <>
struct DeviceOpener<DigitalOutput> {
  using Config = DigitalOutputConfig;
  static Expected<std::unique_ptr<DigitalOutput>> open(Backend& backend, const Config& config) {
    return backend.open_output(config);
  }
  static std::string_view name(const Config& config) noexcept { return config.signal; }
  static constexpr bool gone(ErrorCode code) noexcept { return code == ErrorCode::kUnavailable; }
};

template <>
struct DeviceOpener<CanBus> {
  using Config = CanConfig;
  static Expected<std::unique_ptr<CanBus>> open(Backend& backend, const Config& config) {
    return backend.open_can(config);
  }
  static std::string_view name(const Config& config) noexcept { return config.bus; }
  // Down and bus-off (kUnavailable) are recovered by the bus itself: see the header comment.
  static constexpr bool gone(ErrorCode /*code*/) noexcept { return false; }
};

template <class Device>
class SupervisedDevice {
 public:
  using Opener = DeviceOpener<Device>;
  using Config = typename Opener::Config;

  // Opens nothing yet (see open_now). `backend` must outlive this object.
  SupervisedDevice(Backend& backend, Config config, BackOff back_off = kDefaultBackOff)
      : backend_(&backend), config_(std::move(config)), supervision_(back_off) {}

  SupervisedDevice(SupervisedDevice&&) noexcept = default;
  SupervisedDevice& operator=(SupervisedDevice&&) noexcept = default;

  // Opens the device now (at the hub's start); a failure is kept (error()) and retried from
  // `now` + back-off. Allocates.
  void open_now(Time now) noexcept { try_open(now); }

  // The device, opened first if it is not open and a retry is due (that allocates); nullptr
  // while it is not open.
  Device* device(Time now) noexcept {
    if (device_ == nullptr && supervision_.retry_due(now)) try_open(now);
    return device_.get();
  }
  // The device if it is open; never opens it (for shutdown and faults, where no time is at hand).
  Device* device_if_open() noexcept { return device_.get(); }

  // Tells the supervisor how a call to the device ended: a failure that means the device is gone
  // drops it; it is opened again from `now` + back-off.
  void observe(ErrorCode code, Time now) noexcept {
    if (device_ == nullptr || !Opener::gone(code)) return;
    device_.reset();
    supervision_.dropped(now);
  }

  [[nodiscard]] bool is_open() const noexcept { return device_ != nullptr; }
  [[nodiscard]] DeviceHealth health() const noexcept { return supervision_.health(); }
  // Why the device is not open: the opener's message, or "device went away"; empty while open.
  [[nodiscard]] std::string_view error() const noexcept { return supervision_.error(); }
  [[nodiscard]] const DeviceSupervision& supervision() const noexcept { return supervision_; }
  [[nodiscard]] const Config& config() const noexcept { return config_; }
  [[nodiscard]] std::string_view name() const noexcept { return Opener::name(config_); }

  // --- Digital inputs ---------------------------------------------------------------------------
  // The level, opening the input first when a retry is due. Errors: kUnavailable while not open
  // (or it just went away: dropped); the device's own (kIo) otherwise.
  Result<bool> read(Time now) noexcept requires std::same_as<Device, DigitalInput> {
    DigitalInput* input = device(now);
    if (input == nullptr) return Status(ErrorCode::kUnavailable);
    const Result<bool> level = input->read(now);
    if (!level.is_ok()) observe(level.status().code(), now);
    return level;
  }

  // --- Digital outputs --------------------------------------------------------------------------
  // Drives `active`, opening the line first when a retry is due (it then starts at its `initial`
  // level). Errors: kUnavailable while not open (or it just went away: dropped); the device's own.
  Status write(bool active, Time now) noexcept requires std::same_as<Device, DigitalOutput> {
    DigitalOutput* output = device(now);
    if (output == nullptr) return Status(ErrorCode::kUnavailable);
    const Status written = output->write(active);
    if (written.is_ok()) {
      driven_ = active;
    } else {
      observe(written.code(), now);
    }
    return written;
  }
  // Drives `active` / the safe level if the line is open; never opens it. A line found gone is
  // dropped and opened again by the next write(). Errors: kUnavailable while not open; the device's.
  Status write_if_open(bool active) noexcept requires std::same_as<Device, DigitalOutput> {
    if (device_ == nullptr) return Status(ErrorCode::kUnavailable);
    const Status written = device_->write(active);
    if (written.is_ok()) {
      driven_ = active;
    } else if (Opener::gone(written.code())) {
      device_.reset();
      supervision_.dropped_without_time();
    }
    return written;
  }
  Status write_safe_if_open() noexcept requires std::same_as<Device, DigitalOutput> {
    return write_if_open(config_.safe);
  }
  // The level the line is driven to: its `initial` level once opened, then the last level
  // written successfully. False while it is not open (nothing drives it).
  [[nodiscard]] bool driven() const noexcept requires std::same_as<Device, DigitalOutput> {
    return device_ != nullptr && driven_;
  }

 private:
  void try_open(Time now) noexcept {
    try {
      auto opened = Opener::open(*backend_, config_);
      if (opened) {
        device_ = std::move(*opened);
        if constexpr (std::same_as<Device, DigitalOutput>) driven_ = config_.initial;
        supervision_.opened();
      } else {
        supervision_.open_failed(opened.error().message, now);
      }
    } catch (const std::bad_alloc&) {
      supervision_.open_failed("out of memory while opening", now);
    }
  }

  Backend* backend_;
  Config config_;
  std::unique_ptr<Device> device_;
  DeviceSupervision supervision_;
  bool driven_ = false;  // outputs only
};

using SupervisedInput = SupervisedDevice<DigitalInput>;
using SupervisedOutput = SupervisedDevice<DigitalOutput>;
using SupervisedCanBus = SupervisedDevice<CanBus>;

}  // namespace hubrt::hal
