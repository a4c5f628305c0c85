#include "can_network_core.h"

#include <algorithm>

namespace hubrt::hal::fake::detail {
namespace {

constexpr std::uint32_t kMaxStandardId = 0x7FF;
constexpr std::uint32_t kMaxExtendedId = 0x1FFF'FFFF;
constexpr std::size_t kMaxFilters = 512;  // CAN_RAW_FILTER_MAX, so both backends agree

bool is_error_state(CanBusState state) noexcept {
  return state == CanBusState::kErrorWarning || state == CanBusState::kErrorPassive ||
         state == CanBusState::kBusOff;
}

}  // namespace

bool FrameQueue::push(const CanFrame& frame) noexcept {
  if (count_ == slots_.size()) return false;
  slots_[(head_ + count_) % slots_.size()] = frame;
  ++count_;
  return true;
}

bool FrameQueue::pop(CanFrame& out) noexcept {
  if (count_ == 0) return false;
  out = slots_[head_];
  head_ = (head_ + 1) % slots_.size();
  --count_;
  return true;
}

CanBusState effective_state(const CanNodeState& node) noexcept {
  return std::max(node.bus->state, node.own_state);
}

Status validate_frame(const CanFrame& frame) noexcept {
  if (frame.len > 8) return Status(ErrorCode::kInvalidArgument);
  if (frame.id > (frame.extended ? kMaxExtendedId : kMaxStandardId))
    return Status(ErrorCode::kInvalidArgument);
  return Status::ok();
}

Status validate_filters(std::span<const CanFilter> filters) noexcept {
  if (filters.size() > kMaxFilters) return Status(ErrorCode::kInvalidArgument);
  for (const CanFilter& f : filters) {
    const std::uint32_t limit = f.extended ? kMaxExtendedId : kMaxStandardId;
    if (f.id > limit || f.mask > limit) return Status(ErrorCode::kInvalidArgument);
  }
  return Status::ok();
}

void CanNetworkCore::attach(VirtualCanDevice& device) {
  const std::lock_guard lock(device_mutex_);
  if (std::find(devices_.begin(), devices_.end(), &device) == devices_.end()) devices_.push_back(&device);
}

void CanNetworkCore::detach(VirtualCanDevice& device) {
  const std::lock_guard lock(device_mutex_);
  std::erase(devices_, &device);
}

void CanNetworkCore::detach_all() noexcept {
  const std::lock_guard lock(device_mutex_);
  devices_.clear();
}

void CanNetworkCore::advance_devices() noexcept {
  const std::lock_guard lock(device_mutex_);
  if (devices_.empty()) return;
  // One reading for all devices, so that they agree on what "now" is.
  const Time now = clock_.now().mono;
  for (VirtualCanDevice* device : devices_) device->advance(now);
}

Time CanNetworkCore::next_device_wakeup() noexcept {
  const std::lock_guard lock(device_mutex_);
  Time earliest = Time::max();
  for (const VirtualCanDevice* device : devices_) earliest = std::min(earliest, device->next_wakeup());
  return earliest;
}

CanBusSegment& CanNetworkCore::bus_locked(std::string_view interface) {
  for (auto& bus : buses_) {
    if (bus->interface == interface) return *bus;
  }
  buses_.push_back(std::make_unique<CanBusSegment>(std::string(interface)));
  return *buses_.back();
}

CanNodeState* CanNetworkCore::add_node(std::string_view interface, std::vector<CanFilter> filters,
                                       std::size_t capacity, bool drives_devices) {
  const std::lock_guard lock(mutex);
  CanBusSegment& bus = bus_locked(interface);
  auto node = std::make_unique<CanNodeState>(&bus, capacity, drives_devices);
  node->filters = std::move(filters);
  bus.nodes.push_back(std::move(node));
  return bus.nodes.back().get();
}

void CanNetworkCore::remove_node(CanNodeState* node) noexcept {
  const std::lock_guard lock(mutex);
  std::erase_if(node->bus->nodes, [node](const auto& n) { return n.get() == node; });
}

void CanNetworkCore::set_bus_state(std::string_view interface, CanBusState state) {
  const std::lock_guard lock(mutex);
  CanBusSegment& bus = bus_locked(interface);
  if (bus.state == state) return;
  // Every controller on the bus sees the error frame that announces an error state.
  if (is_error_state(state)) ++bus.error_frames;
  bus.state = state;
  for (auto& node : bus.nodes) node->arrived.notify_all();
}

}  // namespace hubrt::hal::fake::detail
