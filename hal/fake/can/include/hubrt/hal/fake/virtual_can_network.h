// An in-process virtual CAN network: buses by interface name, any number of nodes per bus, every
// frame delivered to all *other* nodes whose filters pass it, bounded receive queues, and bus
// state injection (warning, passive, bus-off, down).
//
// Simulated devices (VirtualCanDevice) are advanced lazily from the network's Clock whenever a
// node is used, so a test with a ManualClock never sleeps: advance the clock, then send or
// receive (or call advance_devices()). A blocking receive() still works in real time for the
// running hub: it waits on a condition variable and wakes when a frame arrives or a device is due.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/can_bus.h"

namespace hubrt::hal::fake {

namespace detail {
class CanNetworkCore;
struct CanNodeState;
}  // namespace detail

// A simulated device attached to the network (for instance the smart tool controller).
// The network calls both functions with its device lock held, from whichever thread uses a node;
// implementations must therefore be thread-safe against their own fault-injection calls, and may
// send and receive on their own node (opened with drives_devices = false) but must not block.
class VirtualCanDevice {
 public:
  virtual ~VirtualCanDevice() = default;
  VirtualCanDevice(const VirtualCanDevice&) = delete;
  VirtualCanDevice& operator=(const VirtualCanDevice&) = delete;

  // Brings the device up to `now`: emits what fell due (in time order) and handles the frames it
  // received. `now` never goes backwards between calls.
  virtual void advance(Time now) noexcept = 0;
  // The earliest time the device will act on its own (e.g. its next heartbeat), so that a
  // blocked receiver knows when to wake up. Time::max() when nothing is scheduled.
  [[nodiscard]] virtual Time next_wakeup() const noexcept = 0;

 protected:
  VirtualCanDevice() = default;
};

struct VirtualCanNodeOptions {
  // Frames beyond this many waiting in the receive queue are dropped and counted (rx_dropped),
  // as a full socket receive buffer drops them.
  std::size_t rx_queue_capacity = 256;
  // Whether using this node advances the attached devices first. Devices' own nodes say false.
  bool drives_devices = true;
};

// One node (one "socket") on a virtual bus. Implements CanBus exactly as the interface documents,
// and adds test hooks. Thread-safe: unlike a real CanBus, a node may be used from several threads,
// and its hooks may be called from a test thread while the hub's cycle uses it.
class VirtualCanNode final : public CanBus {
 public:
  VirtualCanNode(std::shared_ptr<detail::CanNetworkCore> core, detail::CanNodeState* state) noexcept;
  ~VirtualCanNode() override;

  // Puts this node alone into `state` (e.g. its own controller going bus-off); the node's
  // effective state is the worse of this and the bus's state. kErrorActive clears it.
  void set_node_state(CanBusState state) noexcept;
  // Frames dropped because this node's receive queue was full.
  [[nodiscard]] std::uint64_t dropped_frames() const noexcept;
  // Frames waiting in the receive queue.
  [[nodiscard]] std::size_t queued_frames() const noexcept;

 private:
  Status do_send(const CanFrame& frame, Duration timeout) noexcept override;
  Result<CanFrame> do_receive(Duration timeout) noexcept override;
  Status do_set_filters(std::span<const CanFilter> filters) noexcept override;
  CanBusStatus do_status() noexcept override;

  std::shared_ptr<detail::CanNetworkCore> core_;
  detail::CanNodeState* state_;  // owned by core_, removed in the destructor
};

// The network. Nodes and attached devices may outlive neither the network's clock nor, for
// devices, the network object (detach first); nodes keep the network's internals alive.
// Thread-safe: every member may be called from any thread.
class VirtualCanNetwork {
 public:
  // `clock` drives the attached devices; it must outlive the network and every node.
  explicit VirtualCanNetwork(const Clock& clock);
  ~VirtualCanNetwork();
  VirtualCanNetwork(const VirtualCanNetwork&) = delete;
  VirtualCanNetwork& operator=(const VirtualCanNetwork&) = delete;

  // Opens a node on bus `config.interface` (the bus is created on first use) with
  // `config.filters`. Errors: kInvalidArgument (empty interface name, a filter whose id or mask
  // does not fit its frame format, more than 512 filters, zero queue capacity); the message names
  // config.bus and the interface.
  Expected<std::unique_ptr<VirtualCanNode>> open(const CanConfig& config, VirtualCanNodeOptions options = {});

  // Attaches / detaches a device. After detach() returns, the device is never called again.
  void attach(VirtualCanDevice& device);
  void detach(VirtualCanDevice& device);
  // Advances every attached device to clock().now().
  void advance_devices() noexcept;

  // Puts a whole bus into `state` (kErrorActive = healthy). Devices are advanced to now before
  // and after the change, so they react at the exact time. Creates the bus if it does not exist.
  void set_bus_state(std::string_view interface, CanBusState state);

  [[nodiscard]] const Clock& clock() const noexcept;

 private:
  std::shared_ptr<detail::CanNetworkCore> core_;
};

// Filter rule shared by the virtual network and the contract tests: a frame passes when
// (frame.id & mask) == (filter.id & mask) and the extended flags match; no filters = everything.
[[nodiscard]] bool passes_filters(const CanFrame& frame, std::span<const CanFilter> filters) noexcept;

}  // namespace hubrt::hal::fake
