// The shared internals of a VirtualCanNetwork: buses, node queues and the attached devices.
// Lock order: device_mutex before mutex, never the other way round (devices send on their own
// nodes while the network advances them).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/time.h"
#include "hubrt/hal/can_bus.h"
#include "hubrt/hal/fake/virtual_can_network.h"

namespace hubrt::hal::fake::detail {

struct CanBusSegment;

// Fixed-capacity FIFO: sized when the node opens, so the cycle's receive never allocates.
class FrameQueue {
 public:
  explicit FrameQueue(std::size_t capacity) : slots_(capacity) {}
  bool push(const CanFrame& frame) noexcept;
  bool pop(CanFrame& out) noexcept;
  [[nodiscard]] std::size_t size() const noexcept { return count_; }

 private:
  std::vector<CanFrame> slots_;
  std::size_t head_ = 0;
  std::size_t count_ = 0;
};

struct CanNodeState {
  CanNodeState(CanBusSegment* segment, std::size_t capacity, bool drives)
      : bus(segment), queue(capacity), drives_devices(drives) {}
  CanBusSegment* bus;
  std::vector<CanFilter> filters;
  FrameQueue queue;
  CanBusState own_state = CanBusState::kErrorActive;
  std::uint64_t dropped = 0;
  std::uint32_t error_frames = 0;
  bool drives_devices;
  std::condition_variable arrived;  // a frame was queued or the state changed
};

struct CanBusSegment {
  explicit CanBusSegment(std::string name) : interface(std::move(name)) {}
  std::string interface;
  CanBusState state = CanBusState::kErrorActive;
  std::uint32_t error_frames = 0;
  std::vector<std::unique_ptr<CanNodeState>> nodes;
};

class CanNetworkCore {
 public:
  explicit CanNetworkCore(const Clock& clock) noexcept : clock_(clock) {}

  [[nodiscard]] const Clock& clock() const noexcept { return clock_; }

  // Devices (device_mutex).
  void attach(VirtualCanDevice& device);
  void detach(VirtualCanDevice& device);
  void detach_all() noexcept;
  void advance_devices() noexcept;
  [[nodiscard]] Time next_device_wakeup() noexcept;

  // Buses and nodes (mutex).
  CanNodeState* add_node(std::string_view interface, std::vector<CanFilter> filters, std::size_t capacity,
                         bool drives_devices);
  void remove_node(CanNodeState* node) noexcept;
  void set_bus_state(std::string_view interface, CanBusState state);

  std::mutex mutex;

 private:
  CanBusSegment& bus_locked(std::string_view interface);

  const Clock& clock_;
  std::vector<std::unique_ptr<CanBusSegment>> buses_;  // guarded by mutex
  std::mutex device_mutex_;
  std::vector<VirtualCanDevice*> devices_;  // guarded by device_mutex_
};

// The worse of the bus's and the node's own state (the enum is ordered by severity).
CanBusState effective_state(const CanNodeState& node) noexcept;
// True in states where a controller neither sends nor receives.
constexpr bool is_off(CanBusState state) noexcept {
  return state >= CanBusState::kBusOff;
}

// kInvalidArgument for a frame SocketCAN could not carry either.
Status validate_frame(const CanFrame& frame) noexcept;
// kInvalidArgument for a filter whose id or mask does not fit its format, or too many filters.
Status validate_filters(std::span<const CanFilter> filters) noexcept;

}  // namespace hubrt::hal::fake::detail
