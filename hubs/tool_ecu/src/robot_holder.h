// Whether the robot holds the smart tool, as the smart tool's interlocks need it. The production
// source is the RSP ECU's State through a subscription (RspToolHolder); the interface keeps the
// logic testable and independent of how that State arrives.
#pragma once

#include <optional>
#include <string_view>

#include "hubrt/base/time.h"
#include "hubrt/hub_api/remote_state.h"

#include "rsp_reflect.h"
#include "rsp_typed.h"

namespace hubrt::tool_ecu {

struct HolderReading {
  bool known = false;  // a fresh State was available; false = lost, which counts as "not allowed"
  bool holds = false;  // the robot holds the smart tool (only meaningful when known)
  // Known: the tool the robot holds ("none", "smart_tool", ...). Lost: why. Valid until the next
  // read().
  std::string_view detail;
};

class ToolHolderView {
 public:
  virtual ~ToolHolderView() = default;
  // Called on the cycle thread; never allocates.
  virtual HolderReading read(Time now) noexcept = 0;
};

// From the RSP ECU's State: holds when a fresh RspState says tool == "smart_tool".
class RspToolHolder final : public ToolHolderView {
 public:
  static constexpr std::string_view kSmartTool = "smart_tool";

  // `rsp` must outlive this object (the hub's Subscriptions own it).
  explicit RspToolHolder(hub_api::RemoteState<hub_msgs::RspStateView>& rsp) : rsp_(&rsp) {}

  HolderReading read(Time now) noexcept override {
    const std::optional<hub_msgs::RspStateView> state = rsp_->fresh(now);
    if (!state) return HolderReading{false, false, rsp_->loss_reason(now)};
    const std::string_view tool = state->tool();
    return HolderReading{true, tool == kSmartTool, tool};
  }

 private:
  hub_api::RemoteState<hub_msgs::RspStateView>* rsp_;
};

}  // namespace hubrt::tool_ecu
