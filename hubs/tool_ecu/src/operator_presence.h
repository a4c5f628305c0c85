// Whether a verified operator is at the station, as the smart tool's collaborative interlock needs
// it: the planner may run the tool at the engine, where the operator works beside the robot, only
// while the operator hub says someone authorised has badged in (paper §4: RFIDCAM). The production
// source is the operator hub's panel State through a subscription (OperatorPanelPresence); the
// interface keeps the logic testable and independent of how that State arrives.
#pragma once

#include <optional>
#include <string_view>

#include "hubrt/base/time.h"
#include "hubrt/hub_api/remote_state.h"

#include "operator_panel_reflect.h"
#include "operator_panel_typed.h"

namespace hubrt::tool_ecu {

struct OperatorReading {
  bool verified = false;  // a fresh State says an operator is verified; a lost State counts as not
  // Not verified: why ("nobody verified", or why the State is lost). Valid until the next read().
  std::string_view detail;
};

class OperatorPresenceView {
 public:
  virtual ~OperatorPresenceView() = default;
  // Called on the cycle thread; never allocates.
  virtual OperatorReading read(Time now) noexcept = 0;
};

// From the operator hub's OperatorPanelState: verified when a fresh State says operator_verified.
class OperatorPanelPresence final : public OperatorPresenceView {
 public:
  // `panel` must outlive this object (the hub's Subscriptions own it).
  explicit OperatorPanelPresence(hub_api::RemoteState<hub_msgs::OperatorPanelStateView>& panel)
      : panel_(&panel) {}

  OperatorReading read(Time now) noexcept override {
    const std::optional<hub_msgs::OperatorPanelStateView> state = panel_->fresh(now);
    if (!state) return OperatorReading{false, panel_->loss_reason(now)};
    if (!state->operator_verified())
      return OperatorReading{false, "the operator hub reports nobody verified"};
    return OperatorReading{true, {}};
  }

 private:
  hub_api::RemoteState<hub_msgs::OperatorPanelStateView>* panel_;
};

}  // namespace hubrt::tool_ecu
