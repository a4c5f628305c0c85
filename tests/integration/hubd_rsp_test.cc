// The RSP ECU as hubd runs it, on the fake HAL, over real Cyclone DDS on loopback in a private
// domain, in both layouts. The test plays the planner (commands), the Dock ECU (its State, which
// the RSP hub consumes through its `dock` subscription) and the world (pressure, via /sim/input),
// and watches the hub's State and the simulated actuators (/sim/rsp_ecu/signals).
#include <array>
#include <atomic>
#include <functional>
#include <mutex>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/dds/sample.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/sim/sim_bridge_stage.h"
#include "hubrt/test_support/hub_under_test.h"

#include "dock_messages.h"
#include "rsp_messages.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockState;
using rsp_ecu::RspCommand;
using rsp_ecu::RspEcuTypes;
using rsp_ecu::RspState;
using test_support::HubUnderTest;
using test_support::StateStream;

// Generous: a busy 2-core machine running sanitizer builds in parallel. These tests check
// behaviour, not timing.
constexpr auto kPatience = std::chrono::seconds(15);

enum class Layout { kNodeType, kHub };

// The node State's fields the tests look at, copied out of the sample.
struct Seen {
  std::string echo_action;
  bool fresh_msg = false;
  bool got_reset = false;
  std::vector<std::string> errors;
  std::string tool;
  bool locked = false;
  std::string lock;
  bool unlock_allowed = false;
  std::string unlock_blocked;
  std::string gripper;
  bool pressure_ok = false;
  bool safe_state = false;

  [[nodiscard]] bool has_error(std::string_view fragment) const {
    return std::any_of(errors.begin(), errors.end(),
                       [&](const std::string& e) { return e.find(fragment) != std::string::npos; });
  }
  [[nodiscard]] std::string describe() const {
    return fmt::format(
        "echo={} fresh={} tool={} locked={} lock={} allowed={} blocked='{}' pressure_ok={} safe={} "
        "errors=[{}]",
        echo_action, fresh_msg, tool, locked, lock, unlock_allowed, unlock_blocked, pressure_ok, safe_state,
        fmt::join(errors, "; "));
  }
};

std::string text(const char* s) {
  return s == nullptr ? std::string() : std::string(s);
}

Seen seen_from(const RspState& s) {
  Seen out;
  out.echo_action = text(s.echo.action);
  out.fresh_msg = s.fresh_msg;
  out.got_reset = s.got_reset;
  for (std::uint32_t i = 0; i < s.error_list._length; ++i)
    out.errors.push_back(text(s.error_list._buffer[i]));
  out.tool = text(s.tool);
  out.locked = s.locked;
  out.lock = text(s.lock);
  out.unlock_allowed = s.unlock_allowed;
  out.unlock_blocked = text(s.unlock_blocked);
  out.gripper = text(s.gripper);
  out.pressure_ok = s.pressure_ok;
  out.safe_state = s.safe_state;
  return out;
}

class HubdRspTest : public ::testing::TestWithParam<Layout> {
 protected:
  void SetUp() override {
    ASSERT_NO_FATAL_FAILURE(hub_.open());
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(dock_writer_, "/dock_ecu/dock/state"));
    if (GetParam() == Layout::kNodeType) {
      ASSERT_NO_FATAL_FAILURE(hub_.make_writer(node_writer_, "/tool_changer/command"));
      ASSERT_NO_FATAL_FAILURE(hub_.make_stream(node_states_, "/rsp_ecu/rsp/state"));
    } else {
      ASSERT_NO_FATAL_FAILURE(hub_.make_writer(hub_writer_, "/rsp_ecu/command"));
      ASSERT_NO_FATAL_FAILURE(hub_.make_stream(hub_states_, "/rsp_ecu/state"));
    }
    ASSERT_NO_FATAL_FAILURE(hub_.make_stream(signals_, sim::sim_signals_topic("rsp_ecu")));
    // The shipped configuration, in the hub layout for that case.
    const std::string hub = GetParam() == Layout::kHub ? hub_.hub_file("rsp_ecu", "hub") : "rsp_ecu";
    ASSERT_NO_FATAL_FAILURE(hub_.start({.hub = hub}));
    hub_.plan([this] { plan_once(); });
  }

  // The planner and the Dock ECU, every 50 ms: the wanted command (once one is set) and the
  // dock's State (while it is alive).
  void plan_once() {
    if (dock_alive_) publish_dock();
    std::string action;
    std::string gripper;
    {
      const std::lock_guard lock(mutex_);
      action = action_;
      gripper = gripper_;
    }
    if (!action.empty()) publish_command(action, gripper);
  }
  void publish_dock() {
    std::array<hub_msgs_msg_dds__DockSlot_, 3> slots{
        {{"ladder_frame_tool", true}, {"filter_tool", true}, {"smart_tool", smart_tool_home_.load()}}};
    DockState state{};
    hubrt::msgs::typed::assign(state.name, "dock");
    hubrt::msgs::typed::assign(state.echo.target_type, "");
    hubrt::msgs::typed::assign(state.echo.target_name, "");
    hubrt::msgs::typed::assign(state.echo.action, "");
    state.slots._buffer = slots.data();
    state.slots._length = static_cast<std::uint32_t>(slots.size());
    state.slots._maximum = state.slots._length;
    dock_writer_->write(state).ignore();
  }
  void publish_command(const std::string& action, const std::string& gripper) {
    RspCommand node{};
    hubrt::msgs::typed::assign(node.target_type, "tool_changer");
    hubrt::msgs::typed::assign(node.target_name, "rsp");
    hubrt::msgs::typed::assign(node.action, action);
    hubrt::msgs::typed::assign(node.gripper, gripper);
    if (node_writer_) {
      node_writer_->write(node).ignore();
      return;
    }
    RspEcuTypes::Command::Wire hub{};
    hubrt::msgs::typed::assign(hub.target_type, "rsp_ecu");
    hubrt::msgs::typed::assign(hub.target_name, "rsp_ecu");
    hubrt::msgs::typed::assign(hub.action, "apply");
    hub.rsp = node;
    hubrt::msgs::typed::assign(hub.rsp.target_type, "");  // empty: addressed to the node of this field
    hub_writer_->write(hub).ignore();
  }

  void command(std::string action, std::string gripper = "") {
    const std::lock_guard lock(mutex_);
    action_ = std::move(action);
    gripper_ = std::move(gripper);
  }

  void set_world(const char* signal, bool active) { hub_.sim_input("rsp_ecu", signal, active); }

  // Takes States until one satisfies `predicate`; false after the patience runs out. last_ holds
  // the last State seen, for messages.
  bool wait_for(const std::function<bool(const Seen&)>& predicate) {
    const auto take = [&](const auto& state) {
      last_ = seen_from(state);
      return predicate(last_);
    };
    if (node_states_) return node_states_->take_until(take, kPatience);
    return hub_states_->take_until(
        [&](const RspEcuTypes::State::Wire& s) {
          EXPECT_STREQ(s.rsp.name, "rsp") << "the collector fills the node's field";
          return take(s.rsp);
        },
        kPatience);
  }

  // Waits until the simulated lock actuator is in the given end position (energised = open).
  bool wait_for_lock_actuator(bool open) {
    return signals_->take_until(
        [open](const hub_msgs_msg_dds__SimSignals_& signals) {
          const auto& valves = signals.valves;
          for (std::uint32_t i = 0; i < valves._length; ++i) {
            if (text(valves._buffer[i].name) == "rsp.lock_valve" && valves._buffer[i].energised == open)
              return true;
          }
          return false;
        },
        kPatience);
  }

  std::string context() { return last_.describe() + "\n" + hub_.output(); }

  dds::Writer<DockState>* dock_writer_ = nullptr;
  dds::Writer<RspCommand>* node_writer_ = nullptr;
  StateStream<RspState>* node_states_ = nullptr;
  dds::Writer<RspEcuTypes::Command::Wire>* hub_writer_ = nullptr;
  StateStream<RspEcuTypes::State::Wire>* hub_states_ = nullptr;
  StateStream<hub_msgs_msg_dds__SimSignals_>* signals_ = nullptr;

  std::mutex mutex_;
  std::string action_;   // guarded by mutex_
  std::string gripper_;  // guarded by mutex_
  std::atomic<bool> dock_alive_{true};
  std::atomic<bool> smart_tool_home_{false};
  Seen last_;
  HubUnderTest hub_{kPatience};
};

TEST_P(HubdRspTest, UnlocksOnlyWithTheDocksConfirmationAndClosesWhenTheDockGoesQuiet) {
  command("lock", "grab");
  ASSERT_TRUE(wait_for([](const Seen& s) { return s.fresh_msg && s.echo_action == "lock" && s.locked; }))
      << context();
  EXPECT_EQ(last_.tool, "smart_tool") << "host-sim.yaml: the robot starts holding the smart tool";

  // The smart tool is not in its slot: refused, with the reason, and the lock stays closed.
  command("unlock", "grab");
  ASSERT_TRUE(wait_for([](const Seen& s) {
    return s.has_error(
        "unlock refused: the Dock ECU does not report smart_tool home (slot 'smart_tool' empty)");
  })) << context();
  EXPECT_EQ(last_.echo_action, "lock") << "the rejected unlock is not in force";
  EXPECT_EQ(last_.lock, "closed");
  EXPECT_TRUE(last_.locked);
  EXPECT_TRUE(wait_for_lock_actuator(false));

  // The robot puts the tool home: the next unlock is taken and the changer opens.
  smart_tool_home_ = true;
  ASSERT_TRUE(wait_for([](const Seen& s) { return s.echo_action == "unlock" && s.lock == "open"; }))
      << context();
  EXPECT_TRUE(last_.unlock_allowed);
  EXPECT_FALSE(last_.locked);
  EXPECT_TRUE(wait_for_lock_actuator(true)) << "the simulated lock really opened";

  // The Dock ECU goes quiet: its State goes stale (500 ms) and the changer closes.
  dock_alive_ = false;
  ASSERT_TRUE(wait_for([](const Seen& s) { return !s.unlock_allowed && s.lock != "open"; })) << context();
  EXPECT_NE(last_.unlock_blocked.find("Dock ECU State older than 0.50 s (/dock_ecu/dock/state)"),
            std::string::npos)
      << context();
  EXPECT_TRUE(wait_for_lock_actuator(false)) << "the simulated lock really closed";
}

TEST_P(HubdRspTest, APressureDropEndsInTheSafeStateAndResetWithAFreshCommandRecovers) {
  smart_tool_home_ = true;
  command("unlock", "grab");
  ASSERT_TRUE(wait_for([](const Seen& s) { return s.echo_action == "unlock" && s.lock == "open"; }))
      << context();

  set_world("main_air", false);
  ASSERT_TRUE(wait_for([](const Seen& s) { return s.has_error("pressure failure: supply pressure lost"); }))
      << context();
  EXPECT_TRUE(last_.safe_state);
  EXPECT_FALSE(last_.pressure_ok);
  EXPECT_NE(last_.lock, "open");
  EXPECT_EQ(last_.gripper, "grab") << "the gripper stays as it is";

  set_world("main_air", true);
  ASSERT_TRUE(wait_for([](const Seen& s) { return s.pressure_ok && s.lock == "closed"; })) << context();
  EXPECT_TRUE(last_.has_error("pressure failure")) << "latched until reset";
  EXPECT_TRUE(wait_for_lock_actuator(false)) << "with air back the lock closed";

  command("reset");
  ASSERT_TRUE(wait_for([](const Seen& s) { return s.got_reset && s.errors.empty(); })) << context();
  EXPECT_EQ(last_.lock, "closed");
  command("unlock", "grab");
  ASSERT_TRUE(wait_for([](const Seen& s) { return s.echo_action == "unlock" && s.lock == "open"; }))
      << context();
  EXPECT_TRUE(last_.errors.empty()) << context();
}

INSTANTIATE_TEST_SUITE_P(Layouts, HubdRspTest, ::testing::Values(Layout::kNodeType, Layout::kHub),
                         [](const ::testing::TestParamInfo<Layout>& param) {
                           return param.param == Layout::kNodeType ? "NodeTypeLayout" : "HubLayout";
                         });

}  // namespace
}  // namespace hubrt::integration
