// Helpers for the RSP ECU tests: commands whose strings they own, and a Dock ECU State fed into a
// RemoteState as the subscription stage would.
#pragma once

#include <cstring>
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include <dds/dds.h>

#include "hubrt/hub_api/remote_state.h"
#include "hubrt/runtime/ports.h"

#include "dock_messages.h"
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

// A command whose strings live as long as it does.
struct OwnedCommand {
  std::string target_type = "tool_changer";
  std::string target_name = "rsp";
  std::string action = "lock";
  std::string gripper;

  // The wire struct, pointing into this object; valid while it is unchanged.
  RspCommand wire() {
    RspCommand c{};
    c.target_type = target_type.data();
    c.target_name = target_name.data();
    c.action = action.data();
    c.gripper = gripper.data();
    return c;
  }
};

inline OwnedCommand command(std::string action, std::string gripper = "") {
  OwnedCommand c;
  c.action = std::move(action);
  c.gripper = std::move(gripper);
  return c;
}

// Commands handed to a node in order, one drain at a time.
class QueueSource final : public runtime::CommandSource<RspCommand> {
 public:
  void push(const OwnedCommand& c) {
    owned_.push_back(c);
    wires_.push_back(owned_.back().wire());
  }
  Result<const RspCommand*> next() noexcept override {
    if (wires_.empty()) return static_cast<const RspCommand*>(nullptr);
    current_ = wires_.front();
    wires_.pop_front();
    return &current_;
  }

 private:
  std::deque<OwnedCommand> owned_;  // deque: pushing does not move the strings wires point at
  std::deque<RspCommand> wires_;
  RspCommand current_{};
};

// States go nowhere.
class NullSink final : public runtime::StateSink<RspState> {
 public:
  Status publish(const RspState& /*state*/) noexcept override { return Status::ok(); }
};

// The Dock ECU's State as the RSP node receives it through its `dock` subscription.
class DockFeed {
 public:
  explicit DockFeed(Duration timeout)
      : input_("dock", "/dock_ecu/dock/state", timeout, hub_msgs_msg_dds__DockState__desc, 0) {}

  hub_api::RemoteState<dock_ecu::DockState>& input() noexcept { return input_; }

  // A State listing `slots` (name, occupied) arrives at `now`. Strings and buffers are allocated
  // the way Cyclone does when taking, since the RemoteState's sample frees them so.
  void arrive(const std::vector<std::pair<std::string, bool>>& slots, Time now) {
    auto* state = static_cast<dock_ecu::DockState*>(input_.sample_data());
    dds_sample_free(state, &hub_msgs_msg_dds__DockState__desc, DDS_FREE_CONTENTS);
    std::memset(state, 0, sizeof *state);
    state->name = dds_string_dup("dock");
    auto* buffer = static_cast<hub_msgs_msg_dds__DockSlot_*>(
        dds_alloc(sizeof(hub_msgs_msg_dds__DockSlot_) * slots.size()));
    for (std::size_t i = 0; i < slots.size(); ++i) {
      buffer[i].name = dds_string_dup(slots[i].first.c_str());
      buffer[i].occupied = slots[i].second;
    }
    state->slots._buffer = buffer;
    state->slots._length = static_cast<std::uint32_t>(slots.size());
    state->slots._maximum = state->slots._length;
    state->slots._release = true;
    input_.note_arrival(now);
  }

 private:
  hub_api::RemoteState<dock_ecu::DockState> input_;
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
