// Helpers for the RSP ECU tests: commands whose strings they own, and a Dock ECU State fed into a
// RemoteState as the subscription stage would.
#pragma once

#include <cstring>
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "hubrt/hub_api/remote_state.h"
#include "hubrt/runtime/ports.h"

#include "dock_reflect.h"  // the Dock ECU's messages (its library is not ours to link)
#include "dock_typed.h"
#include "rsp_ecu_hub_type.h"
#include "rsp_logic.h"
#include "rsp_messages.h"

namespace hubrt::rsp_ecu::testing {

// The node as the hub type builds it: its devices opened from the board, then handed in.
inline Expected<RspLogic> make_rsp_logic(const RspSettings& settings, const hal::BoardConfig& board,
                                         hal::Backend& backend, DockInput& dock, Time now) {
  auto devices = open_rsp_devices(settings, board, backend, now);
  if (!devices) return std::move(devices).error();
  return RspLogic::create(settings, std::move(*devices), dock, now);
}

// A command, owning its strings (the generated owning type).
using OwnedCommand = hub_msgs::RspCommand;

inline OwnedCommand command(std::string_view action, std::string_view gripper = "") {
  OwnedCommand c;
  c.set_target_type("tool_changer");
  c.set_target_name("rsp");
  c.set_action(action);
  c.set_gripper(gripper);
  return c;
}

// Commands handed to a node in order, one drain at a time.
class QueueSource final : public runtime::CommandSource<OwnedCommand::Wire> {
 public:
  void push(const OwnedCommand& c) { commands_.push_back(c); }
  Result<const OwnedCommand::Wire*> next() noexcept override {
    if (commands_.empty()) return static_cast<const OwnedCommand::Wire*>(nullptr);
    current_ = commands_.front();
    commands_.pop_front();
    return &current_.wire();
  }

 private:
  std::deque<OwnedCommand> commands_;
  OwnedCommand current_;
};

// States go nowhere.
class NullSink final : public runtime::StateSink<hub_msgs::RspState::Wire> {
 public:
  Status publish(const hub_msgs::RspState::Wire& /*state*/) noexcept override { return Status::ok(); }
};

// The Dock ECU's State as the RSP node receives it through its `dock` subscription.
class DockFeed {
 public:
  explicit DockFeed(Duration timeout)
      : input_("dock", "/dock_ecu/dock/state", timeout, hub_msgs_msg_dds__DockState__desc, 0) {}

  hub_api::RemoteState<hub_msgs::DockStateView>& input() noexcept { return input_; }

  // A State listing `slots` (name, occupied) arrives at `now`: built in `sent_`, whose storage
  // the received sample then points into (its sequence is not the sample's to free).
  void arrive(const std::vector<std::pair<std::string, bool>>& slots, Time now) {
    sent_ = hub_msgs::DockState();
    sent_.set_name("dock");
    for (const auto& [name, occupied] : slots) {
      auto slot = sent_.slots().append();
      slot->set_name(name);
      slot->set_occupied(occupied);
    }
    std::memcpy(input_.sample_data(), &sent_.wire(), sizeof sent_.wire());
    input_.note_arrival(now);
  }

 private:
  hub_msgs::DockState sent_;  // declared first: outlives the sample that points into it
  hub_api::RemoteState<hub_msgs::DockStateView> input_;
};

// The dock as host-sim.yaml starts it, with the smart tool's slot as given.
inline std::vector<std::pair<std::string, bool>> dock_slots(bool ladder_frame_home, bool filter_home,
                                                            bool smart_home) {
  return {{"ladder_frame_tool", ladder_frame_home},
          {"filter_tool", filter_home},
          {"smart_tool", smart_home},
          {"spare", false}};
}

}  // namespace hubrt::rsp_ecu::testing
