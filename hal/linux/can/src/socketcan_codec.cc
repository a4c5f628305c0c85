#include "socketcan_codec.h"

#include <algorithm>
#include <cstring>

#include <linux/can/error.h>
#include <linux/can/netlink.h>
#include <linux/can/raw.h>

namespace hubrt::hal::socketcan {
namespace {

constexpr std::size_t kMaxFilters = CAN_RAW_FILTER_MAX;

bool fits(std::uint32_t value, bool extended) noexcept {
  return value <= (extended ? CAN_EFF_MASK : CAN_SFF_MASK);
}

}  // namespace

Status to_kernel_frame(const CanFrame& frame, can_frame& out) noexcept {
  if (frame.len > CAN_MAX_DLEN || !fits(frame.id, frame.extended)) return Status(ErrorCode::kInvalidArgument);
  std::memset(&out, 0, sizeof out);
  out.can_id = frame.id;
  if (frame.extended) out.can_id |= CAN_EFF_FLAG;
  if (frame.remote) out.can_id |= CAN_RTR_FLAG;
  out.len = frame.len;
  std::copy_n(frame.data.begin(), frame.len, out.data);
  return Status::ok();
}

CanFrame from_kernel_frame(const can_frame& in) noexcept {
  CanFrame frame;
  frame.extended = (in.can_id & CAN_EFF_FLAG) != 0;
  frame.remote = (in.can_id & CAN_RTR_FLAG) != 0;
  frame.id = in.can_id & (frame.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
  frame.len = std::min<std::uint8_t>(in.len, CAN_MAX_DLEN);
  if (!frame.remote) std::copy_n(in.data, frame.len, frame.data.begin());
  return frame;
}

Status to_kernel_filters(std::span<const CanFilter> filters, std::vector<can_filter>& out) {
  if (filters.size() > kMaxFilters) return Status(ErrorCode::kInvalidArgument);
  out.clear();
  if (filters.empty()) {
    out.push_back(can_filter{0, 0});
    return Status::ok();
  }
  for (const CanFilter& f : filters) {
    if (!fits(f.id, f.extended) || !fits(f.mask, f.extended)) return Status(ErrorCode::kInvalidArgument);
    // CAN_EFF_FLAG in the mask makes the kernel compare the frame format too; CAN_RTR_FLAG is
    // left out so that data and remote frames both pass, as in the HAL's rule.
    can_filter k{};
    k.can_id = f.id | (f.extended ? CAN_EFF_FLAG : 0U);
    k.can_mask = f.mask | CAN_EFF_FLAG;
    out.push_back(k);
  }
  return Status::ok();
}

void apply_error_frame(const can_frame& frame, CanBusStatus& status) noexcept {
  ++status.error_frames;
  const canid_t cls = frame.can_id & CAN_ERR_MASK;
  if ((cls & CAN_ERR_CNT) != 0) {
    status.tx_errors = frame.data[6];
    status.rx_errors = frame.data[7];
  }
  if ((cls & CAN_ERR_CRTL) != 0) {
    const std::uint8_t ctrl = frame.data[1];
    if ((ctrl & (CAN_ERR_CRTL_RX_PASSIVE | CAN_ERR_CRTL_TX_PASSIVE)) != 0) {
      status.state = CanBusState::kErrorPassive;
    } else if ((ctrl & (CAN_ERR_CRTL_RX_WARNING | CAN_ERR_CRTL_TX_WARNING)) != 0) {
      status.state = CanBusState::kErrorWarning;
    } else if ((ctrl & CAN_ERR_CRTL_ACTIVE) != 0) {
      status.state = CanBusState::kErrorActive;
    }
  }
  if ((cls & CAN_ERR_RESTARTED) != 0) status.state = CanBusState::kErrorActive;
  // Bus-off wins over anything else reported in the same frame.
  if ((cls & CAN_ERR_BUSOFF) != 0) status.state = CanBusState::kBusOff;
}

CanBusState from_netlink_state(int state) noexcept {
  switch (state) {
    case CAN_STATE_ERROR_ACTIVE:
      return CanBusState::kErrorActive;
    case CAN_STATE_ERROR_WARNING:
      return CanBusState::kErrorWarning;
    case CAN_STATE_ERROR_PASSIVE:
      return CanBusState::kErrorPassive;
    case CAN_STATE_BUS_OFF:
      return CanBusState::kBusOff;
    default:
      return CanBusState::kDown;  // stopped, sleeping
  }
}

}  // namespace hubrt::hal::socketcan
