// The RSP ECU as hubd runs it, on the fake HAL, over real Cyclone DDS on loopback in a private
// domain, in both layouts. The test plays the planner (commands), the Dock ECU (its State, which
// the RSP hub consumes through its `dock` subscription) and the world (pressure, via /sim/input),
// and watches the hub's State and the simulated actuators (/sim/rsp_ecu/signals).
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/sim/sim_bridge_stage.h"

#include "dock_messages.h"
#include "hub_process.h"
#include "rsp_messages.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockState;
using rsp_ecu::RspCommand;
using rsp_ecu::RspEcuTypes;
using rsp_ecu::RspState;
using std::chrono::milliseconds;
namespace fs = std::filesystem;

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

char* wire(const char* s) {
  return const_cast<char*>(s);
}  // NOLINT

class HubdRspTest : public ::testing::TestWithParam<Layout> {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    HubProcessOptions options;
    options.hub = "rsp_ecu";
    if (GetParam() == Layout::kHub) {
      // The shipped configuration with the hub layout.
      std::ifstream in(std::string(HUBRT_SOURCE_DIR) + "/hubs/rsp_ecu/rsp_ecu.yaml");
      std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      const auto at = text.find("layout: node_type");
      ASSERT_NE(at, std::string::npos);
      text.replace(at, 17, "layout: hub");
      hub_file_ = fs::temp_directory_path() / fmt::format("hubrt-rsp-hub-layout-{}.yaml", getpid());
      std::ofstream(hub_file_) << text;
      options.hub = hub_file_.string();
    }

    auto participant = dds::Participant::create(domain_->config(), "test-planner");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    ASSERT_NO_FATAL_FAILURE(make_endpoints());

    auto hub = HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(dock_writer_->wait_for_readers(1, kPatience)) << hub_->output();
    if (node_writer_) {
      ASSERT_TRUE(node_writer_->wait_for_readers(1, kPatience)) << hub_->output();
    } else {
      ASSERT_TRUE(hub_writer_->wait_for_readers(1, kPatience)) << hub_->output();
    }
    ASSERT_TRUE(sim_input_writer_->wait_for_readers(1, kPatience)) << hub_->output();
    planner_ = std::thread([this] { plan(); });
  }

  void TearDown() override {
    running_ = false;
    if (planner_.joinable()) planner_.join();
    if (!hub_file_.empty()) fs::remove(hub_file_);
  }

  void make_endpoints() {
    auto dock_topic = dds::Topic<DockState>::create(*participant_, "/dock_ecu/dock/state");
    ASSERT_TRUE(dock_topic) << dock_topic.error().message;
    dock_topic_.emplace(std::move(*dock_topic));
    auto dock_writer = dds::Writer<DockState>::create(*participant_, *dock_topic_);
    ASSERT_TRUE(dock_writer) << dock_writer.error().message;
    dock_writer_.emplace(std::move(*dock_writer));

    if (GetParam() == Layout::kNodeType) {
      auto command_topic = dds::Topic<RspCommand>::create(*participant_, "/tool_changer/command");
      ASSERT_TRUE(command_topic) << command_topic.error().message;
      node_command_topic_.emplace(std::move(*command_topic));
      auto writer = dds::Writer<RspCommand>::create(*participant_, *node_command_topic_);
      ASSERT_TRUE(writer) << writer.error().message;
      node_writer_.emplace(std::move(*writer));
      auto state_topic = dds::Topic<RspState>::create(*participant_, "/rsp_ecu/rsp/state");
      ASSERT_TRUE(state_topic) << state_topic.error().message;
      node_state_topic_.emplace(std::move(*state_topic));
      auto reader = dds::Reader<RspState>::create(*participant_, *node_state_topic_);
      ASSERT_TRUE(reader) << reader.error().message;
      node_reader_.emplace(std::move(*reader));
    } else {
      auto command_topic = dds::Topic<RspEcuTypes::Command::Wire>::create(*participant_, "/rsp_ecu/command");
      ASSERT_TRUE(command_topic) << command_topic.error().message;
      hub_command_topic_.emplace(std::move(*command_topic));
      auto writer = dds::Writer<RspEcuTypes::Command::Wire>::create(*participant_, *hub_command_topic_);
      ASSERT_TRUE(writer) << writer.error().message;
      hub_writer_.emplace(std::move(*writer));
      auto state_topic = dds::Topic<RspEcuTypes::State::Wire>::create(*participant_, "/rsp_ecu/state");
      ASSERT_TRUE(state_topic) << state_topic.error().message;
      hub_state_topic_.emplace(std::move(*state_topic));
      auto reader = dds::Reader<RspEcuTypes::State::Wire>::create(*participant_, *hub_state_topic_);
      ASSERT_TRUE(reader) << reader.error().message;
      hub_reader_.emplace(std::move(*reader));
    }

    auto signals_topic =
        dds::Topic<hub_msgs_msg_dds__SimSignals_>::create(*participant_, sim::sim_signals_topic("rsp_ecu"));
    ASSERT_TRUE(signals_topic) << signals_topic.error().message;
    signals_topic_.emplace(std::move(*signals_topic));
    auto signals_reader = dds::Reader<hub_msgs_msg_dds__SimSignals_>::create(*participant_, *signals_topic_);
    ASSERT_TRUE(signals_reader) << signals_reader.error().message;
    signals_reader_.emplace(std::move(*signals_reader));
    auto input_topic = dds::Topic<hub_msgs_msg_dds__SimInput_>::create(*participant_, sim::kSimInputTopic);
    ASSERT_TRUE(input_topic) << input_topic.error().message;
    sim_input_topic_.emplace(std::move(*input_topic));
    auto input_writer = dds::Writer<hub_msgs_msg_dds__SimInput_>::create(*participant_, *sim_input_topic_);
    ASSERT_TRUE(input_writer) << input_writer.error().message;
    sim_input_writer_.emplace(std::move(*input_writer));
  }

  // The planner and the Dock ECU, every 50 ms: the wanted command (once one is set) and the
  // dock's State (while it is alive).
  void plan() {
    while (running_) {
      if (dock_alive_) publish_dock();
      std::string action;
      std::string gripper;
      {
        const std::lock_guard lock(mutex_);
        action = action_;
        gripper = gripper_;
      }
      if (!action.empty()) publish_command(action, gripper);
      std::this_thread::sleep_for(milliseconds(50));
    }
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

  void set_world(const char* signal, bool active) {
    hub_msgs_msg_dds__SimInput_ input{};
    input.hub = wire("rsp_ecu");
    input.signal = wire(signal);
    input.active = active;
    ASSERT_TRUE(sim_input_writer_->write(input).is_ok());
  }

  // Takes States until one satisfies `predicate`; false after the patience runs out. last_ holds
  // the last State seen, for messages.
  bool wait_for(const std::function<bool(const Seen&)>& predicate) {
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < deadline) {
      std::optional<Seen> seen = take();
      if (!seen) {
        std::this_thread::sleep_for(milliseconds(2));
        continue;
      }
      last_ = std::move(*seen);
      if (predicate(last_)) return true;
    }
    return false;
  }
  std::optional<Seen> take() {
    if (node_reader_) {
      const Result<bool> taken = node_reader_->take_next(node_state_);
      if (!taken.is_ok() || !taken.value()) return std::nullopt;
      return seen_from(node_state_.get());
    }
    const Result<bool> taken = hub_reader_->take_next(hub_state_);
    if (!taken.is_ok() || !taken.value()) return std::nullopt;
    EXPECT_STREQ(hub_state_.get().rsp.name, "rsp") << "the collector fills the node's field";
    return seen_from(hub_state_.get().rsp);
  }

  // Waits until the simulated lock actuator is in the given end position (energised = open).
  bool wait_for_lock_actuator(bool open) {
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < deadline) {
      const Result<bool> taken = signals_reader_->take_next(signals_);
      if (!taken.is_ok() || !taken.value()) {
        std::this_thread::sleep_for(milliseconds(2));
        continue;
      }
      const auto& valves = signals_.get().valves;
      for (std::uint32_t i = 0; i < valves._length; ++i) {
        if (text(valves._buffer[i].name) == "rsp.lock_valve" && valves._buffer[i].energised == open)
          return true;
      }
    }
    return false;
  }

  std::string context() { return last_.describe() + "\n" + hub_->output(); }

  std::optional<test_support::TestDomain> domain_;
  fs::path hub_file_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<DockState>> dock_topic_;
  std::optional<dds::Writer<DockState>> dock_writer_;
  std::optional<dds::Topic<RspCommand>> node_command_topic_;
  std::optional<dds::Writer<RspCommand>> node_writer_;
  std::optional<dds::Topic<RspState>> node_state_topic_;
  std::optional<dds::Reader<RspState>> node_reader_;
  dds::Sample<RspState> node_state_;
  std::optional<dds::Topic<RspEcuTypes::Command::Wire>> hub_command_topic_;
  std::optional<dds::Writer<RspEcuTypes::Command::Wire>> hub_writer_;
  std::optional<dds::Topic<RspEcuTypes::State::Wire>> hub_state_topic_;
  std::optional<dds::Reader<RspEcuTypes::State::Wire>> hub_reader_;
  dds::Sample<RspEcuTypes::State::Wire> hub_state_;
  std::optional<dds::Topic<hub_msgs_msg_dds__SimSignals_>> signals_topic_;
  std::optional<dds::Reader<hub_msgs_msg_dds__SimSignals_>> signals_reader_;
  dds::Sample<hub_msgs_msg_dds__SimSignals_> signals_;
  std::optional<dds::Topic<hub_msgs_msg_dds__SimInput_>> sim_input_topic_;
  std::optional<dds::Writer<hub_msgs_msg_dds__SimInput_>> sim_input_writer_;
  std::optional<HubProcess> hub_;

  std::mutex mutex_;
  std::string action_;   // guarded by mutex_
  std::string gripper_;  // guarded by mutex_
  std::atomic<bool> dock_alive_{true};
  std::atomic<bool> smart_tool_home_{false};
  std::atomic<bool> running_{true};
  std::thread planner_;
  Seen last_;
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
