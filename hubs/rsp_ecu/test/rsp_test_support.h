// Helpers for the RSP ECU tests: commands whose strings they own, a Dock ECU State fed into a
// RemoteState as the subscription stage would, and the logic tests' fixture (RspLogicTest).
#pragma once

#include <chrono>
#include <cstring>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"
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
  Result<runtime::ReceivedCommand<OwnedCommand::Wire>> next() noexcept override {
    if (commands_.empty()) return runtime::ReceivedCommand<OwnedCommand::Wire>{};
    current_ = commands_.front();
    commands_.pop_front();
    return runtime::ReceivedCommand<OwnedCommand::Wire>{&current_.wire(), std::nullopt, std::nullopt};
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

// The tool-changer logic on the simulation board's fake backend (host-sim.yaml, the hub file
// rsp_ecu.yaml) with a manual clock, the Dock ECU's State fed in as the subscription would: the
// fixture of the rsp_logic_*_test.cc files.
class RspLogicTest : public ::testing::Test {
 protected:
  static constexpr Duration kCycle = std::chrono::milliseconds(10);

  void SetUp() override {
    auto board = hal::load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml");
    ASSERT_TRUE(board) << board.error().message;
    board_ = std::move(*board);
    auto config = config::load_hub_config(std::string(HUBRT_HUBS_DIR) + "/rsp_ecu/rsp_ecu.yaml");
    ASSERT_TRUE(config) << config.error().message;
    auto settings = parse_rsp_settings(config->nodes.at(0));
    ASSERT_TRUE(settings) << settings.error().message;
    settings_ = std::move(*settings);
    auto fake = hal::fake::FakeBackend::create(board_, clock_);
    ASSERT_TRUE(fake) << fake.error().message;
    fake_ = std::move(*fake);
  }

  RspLogic make_logic() {
    auto logic = make_rsp_logic(settings_, board_, *fake_, dock_.input(), clock_.now().mono);
    EXPECT_TRUE(logic) << logic.error().message;
    return std::move(*logic);
  }

  // The Dock ECU keeps publishing this (every cycle) until dock_silent().
  void dock_reports(bool ladder_frame_home, bool filter_home, bool smart_home) {
    dock_slots_ = dock_slots(ladder_frame_home, filter_home, smart_home);
  }
  void dock_silent() { dock_slots_.reset(); }

  // The tool-ID lines show `tool` ("none": no line).
  void tool_on_changer(std::string_view tool) {
    for (const std::string_view name : {"ladder_frame_tool", "smart_tool", "filter_tool"}) {
      set_input(std::string("rsp.tool_id.") + std::string(name), tool == name);
    }
  }
  void set_input(const std::string& signal, bool active) {
    hal::fake::SettableInput* input = fake_->input(signal);
    ASSERT_NE(input, nullptr) << signal;
    input->set(active);
  }

  // One cycle at the current time; returns the State the logic reports.
  hub_msgs::RspState cycle(RspLogic& logic, OwnedCommand* in_force) {
    const Time now = clock_.now().mono;
    if (dock_slots_) dock_.arrive(*dock_slots_, now);
    logic.read_inputs(now);
    std::optional<hub_msgs::RspCommandView> view;
    if (in_force != nullptr) view = in_force->view();
    logic.update(view ? &*view : nullptr, now);
    errors_.clear();
    hub_msgs::RspState state;
    logic.report(state, errors_, now);
    return state;
  }
  // Cycles every 10 ms for `span` (the first at once); returns the last State.
  hub_msgs::RspState run_for(RspLogic& logic, Duration span, OwnedCommand* in_force) {
    hub_msgs::RspState state = cycle(logic, in_force);
    for (Duration t = kCycle; t <= span; t += kCycle) {
      clock_.advance(kCycle);
      state = cycle(logic, in_force);
    }
    return state;
  }

  bool output(std::string_view signal) {
    auto level = fake_->active(signal);
    EXPECT_TRUE(level.is_ok()) << signal;
    return level.value_or(false);
  }
  bool lock_valve_energised() { return output("rsp.lock_valve"); }
  bool gripper_valve_energised() { return output("rsp.gripper_valve"); }

  ManualClock clock_;
  hal::BoardConfig board_;
  RspSettings settings_;
  std::unique_ptr<hal::fake::FakeBackend> fake_;
  DockFeed dock_{std::chrono::milliseconds(500)};
  std::optional<std::vector<std::pair<std::string, bool>>> dock_slots_;
  runtime::ErrorList errors_;
};

}  // namespace hubrt::rsp_ecu::testing
