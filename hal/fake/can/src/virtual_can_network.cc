#include "hubrt/hal/fake/virtual_can_network.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "can_network_core.h"

namespace hubrt::hal::fake {
namespace {

using detail::CanNodeState;
using RealClock = std::chrono::steady_clock;

// Error counters a controller reports in each state (the thresholds of ISO 11898-1), so that the
// fake's status() looks like what libsocketcan reads from a real controller.
std::uint16_t tx_errors_for(CanBusState state) noexcept {
  switch (state) {
    case CanBusState::kErrorWarning:
      return 96;
    case CanBusState::kErrorPassive:
      return 128;
    case CanBusState::kBusOff:
      return 256;
    case CanBusState::kErrorActive:
    case CanBusState::kDown:
      return 0;
  }
  return 0;
}

// Waiting for a device that is already due must still yield, or a blocked receiver would spin.
constexpr Duration kMinDeviceWait = std::chrono::milliseconds(1);
// Longer timeouts are cut to this so that deadline arithmetic cannot overflow.
constexpr Duration kMaxWait = std::chrono::hours(24);

}  // namespace

bool passes_filters(const CanFrame& frame, std::span<const CanFilter> filters) noexcept {
  if (filters.empty()) return true;
  return std::any_of(filters.begin(), filters.end(), [&frame](const CanFilter& f) {
    return f.extended == frame.extended && (frame.id & f.mask) == (f.id & f.mask);
  });
}

VirtualCanNode::VirtualCanNode(std::shared_ptr<detail::CanNetworkCore> core, CanNodeState* state) noexcept
    : core_(std::move(core)), state_(state) {}

VirtualCanNode::~VirtualCanNode() {
  core_->remove_node(state_);
}

void VirtualCanNode::set_node_state(CanBusState state) noexcept {
  const std::lock_guard lock(core_->mutex);
  if (state_->own_state == state) return;
  if (state == CanBusState::kErrorWarning || state == CanBusState::kErrorPassive ||
      state == CanBusState::kBusOff) {
    ++state_->error_frames;
  }
  state_->own_state = state;
  state_->arrived.notify_all();
}

std::uint64_t VirtualCanNode::dropped_frames() const noexcept {
  const std::lock_guard lock(core_->mutex);
  return state_->dropped;
}

std::size_t VirtualCanNode::queued_frames() const noexcept {
  const std::lock_guard lock(core_->mutex);
  return state_->queue.size();
}

Status VirtualCanNode::do_send(const CanFrame& frame, Duration /*timeout: delivery never waits*/) noexcept {
  if (const Status valid = detail::validate_frame(frame); !valid.is_ok()) return valid;
  if (state_->drives_devices) core_->advance_devices();
  {
    const std::lock_guard lock(core_->mutex);
    if (detail::is_off(detail::effective_state(*state_))) return Status(ErrorCode::kUnavailable);
    for (auto& other : state_->bus->nodes) {
      if (other.get() == state_ || detail::is_off(detail::effective_state(*other))) continue;
      if (!passes_filters(frame, other->filters)) continue;
      if (other->queue.push(frame)) {
        other->arrived.notify_all();
      } else {
        ++other->dropped;
      }
    }
  }
  // Devices answer at the time the frame was sent, as a real controller answers within a
  // millisecond or two.
  if (state_->drives_devices) core_->advance_devices();
  return Status::ok();
}

Result<CanFrame> VirtualCanNode::do_receive(Duration timeout) noexcept {
  const auto real_deadline = RealClock::now() + std::clamp(timeout, Duration::zero(), kMaxWait);
  for (;;) {
    auto wake_at = real_deadline;
    if (state_->drives_devices) {
      core_->advance_devices();
      const Time due = core_->next_device_wakeup();
      if (due != Time::max()) {
        // Device time runs on the network's clock; with a SystemClock this is the same timeline
        // as the real wait. With a ManualClock nothing becomes due while we wait, which is fine:
        // such tests poll with timeout 0 after advancing the clock.
        const Duration until_due = std::max(due - core_->clock().now().mono, kMinDeviceWait);
        wake_at = std::min(wake_at, RealClock::now() + until_due);
      }
    }
    std::unique_lock lock(core_->mutex);
    if (detail::is_off(detail::effective_state(*state_))) return Status(ErrorCode::kUnavailable);
    CanFrame frame;
    if (state_->queue.pop(frame)) return frame;
    if (RealClock::now() >= real_deadline) return Status(ErrorCode::kTimeout);
    state_->arrived.wait_until(lock, wake_at);
  }
}

Status VirtualCanNode::do_set_filters(std::span<const CanFilter> filters) noexcept {
  if (const Status valid = detail::validate_filters(filters); !valid.is_ok()) return valid;
  const std::lock_guard lock(core_->mutex);
  state_->filters.assign(filters.begin(), filters.end());
  return Status::ok();
}

CanBusStatus VirtualCanNode::do_status() noexcept {
  if (state_->drives_devices) core_->advance_devices();
  const std::lock_guard lock(core_->mutex);
  const CanBusState state = detail::effective_state(*state_);
  CanBusStatus status;
  status.state = state;
  status.tx_errors = tx_errors_for(state);
  status.error_frames = state_->bus->error_frames + state_->error_frames;
  status.rx_dropped = static_cast<std::uint32_t>(state_->dropped);
  return status;
}

VirtualCanNetwork::VirtualCanNetwork(const Clock& clock)
    : core_(std::make_shared<detail::CanNetworkCore>(clock)) {}

VirtualCanNetwork::~VirtualCanNetwork() {
  core_->detach_all();
}

Expected<std::unique_ptr<VirtualCanNode>> VirtualCanNetwork::open(const CanConfig& config,
                                                                  VirtualCanNodeOptions options) {
  const std::string where = config.bus + " (virtual CAN '" + config.interface + "')";
  if (config.interface.empty()) {
    return make_error(ErrorCode::kInvalidArgument, config.bus + ": no CAN interface named");
  }
  if (options.rx_queue_capacity == 0) {
    return make_error(ErrorCode::kInvalidArgument, where + ": receive queue capacity must be at least 1");
  }
  if (!detail::validate_filters(config.filters).is_ok()) {
    return make_error(
        ErrorCode::kInvalidArgument,
        where + ": invalid CAN filter (id or mask wider than its frame format, or more than 512)");
  }
  CanNodeState* state =
      core_->add_node(config.interface, config.filters, options.rx_queue_capacity, options.drives_devices);
  return std::make_unique<VirtualCanNode>(core_, state);
}

void VirtualCanNetwork::attach(VirtualCanDevice& device) {
  core_->attach(device);
}

void VirtualCanNetwork::detach(VirtualCanDevice& device) {
  core_->detach(device);
}

void VirtualCanNetwork::advance_devices() noexcept {
  core_->advance_devices();
}

void VirtualCanNetwork::set_bus_state(std::string_view interface, CanBusState state) {
  core_->advance_devices();
  core_->set_bus_state(interface, state);
  core_->advance_devices();
}

const Clock& VirtualCanNetwork::clock() const noexcept {
  return core_->clock();
}

}  // namespace hubrt::hal::fake
