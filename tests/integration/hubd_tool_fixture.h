// The fixture of the hubd Tool ECU tests: hubd running the Tool ECU on the fake HAL, talked to
// over real Cyclone DDS on loopback in a private domain, in both layouts (node-type and hub). The
// RSP ECU is played by the test: it publishes hub_msgs/msg/RspState on /rsp_ecu/rsp/state,
// exactly what the Tool ECU's subscription consumes. The simulated world is changed over
// /sim/input and /sim/fault. Shared by the hubd_tool_*_test.cc files of one test binary. The
// planner's DDS links to the hub (commands out, States in as plain values) are hubd_tool_links.h.
#pragma once

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/sim/sim_bridge_stage.h"

#include "hub_process.h"
#include "hubd_tool_links.h"
#include "rsp.h"

// The RSP ECU's State type, for the stand-in RSP ECU (its own hub library is not needed here).
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__RspState_, hub_msgs_msg_dds__RspState__desc);

namespace hubrt::integration::tool_test {

using std::chrono::milliseconds;
using std::chrono::seconds;
using RspState = hub_msgs_msg_dds__RspState_;

// Generous: a busy 2-core machine running sanitizer builds in parallel. These tests check
// behaviour, not timing; the benchmarks measure timing.
inline constexpr auto kPatience = seconds(20);

enum class Layout { kNodeType, kHub };

class HubdToolTest : public ::testing::TestWithParam<Layout> {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-planner");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    if (GetParam() == Layout::kHub) {
      link_ = std::make_unique<HubLink>(*participant_);
    } else {
      link_ = std::make_unique<NodeTypeLink>(*participant_);
    }
    rsp_topic_.emplace(*dds::Topic<RspState>::create(*participant_, "/rsp_ecu/rsp/state"));
    rsp_writer_.emplace(*dds::Writer<RspState>::create(*participant_, *rsp_topic_));
    sim_input_topic_.emplace(
        *dds::Topic<hub_msgs_msg_dds__SimInput_>::create(*participant_, sim::kSimInputTopic));
    sim_input_writer_.emplace(
        *dds::Writer<hub_msgs_msg_dds__SimInput_>::create(*participant_, *sim_input_topic_));
    sim_fault_topic_.emplace(
        *dds::Topic<hub_msgs_msg_dds__SimFault_>::create(*participant_, sim::kSimFaultTopic));
    sim_fault_writer_.emplace(
        *dds::Writer<hub_msgs_msg_dds__SimFault_>::create(*participant_, *sim_fault_topic_));
  }

  void TearDown() override {
    running_ = false;
    if (planner_.joinable()) planner_.join();
    if (rsp_.joinable()) rsp_.join();
    if (!hub_file_dir_.empty()) std::filesystem::remove_all(hub_file_dir_);
  }

  // The shipped hub file, or (hub layout) a copy of it with `layout: hub`.
  std::string hub_argument() {
    if (GetParam() == Layout::kNodeType) return "tool_ecu";
    std::ifstream in(std::string(HUBRT_SOURCE_DIR) + "/hubs/tool_ecu/tool_ecu.yaml");
    std::stringstream yaml;
    yaml << in.rdbuf();
    std::string content = yaml.str();
    const std::string from = "layout: node_type";
    const auto at = content.find(from);
    EXPECT_NE(at, std::string::npos);
    content.replace(at, from.size(), "layout: hub");
    hub_file_dir_ = (std::filesystem::temp_directory_path() /
                     fmt::format("hubrt-tool-test-{}-{}", getpid(), domain_->domain_id()))
                        .string();
    std::filesystem::create_directories(hub_file_dir_);
    const std::string path = hub_file_dir_ + "/tool_ecu.yaml";
    std::ofstream(path) << content;
    return path;
  }

  // Starts hubd, the planner (commands every 100 ms) and the stand-in RSP ECU (State every 100 ms).
  void start() {
    HubProcessOptions options;
    options.hub = hub_argument();
    auto hub = HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(link_->wait_for_hub(kPatience)) << hub_->output();
    ASSERT_TRUE(sim_input_writer_->wait_for_readers(1, kPatience));
    ASSERT_TRUE(sim_fault_writer_->wait_for_readers(1, kPatience));
    ASSERT_TRUE(rsp_writer_->wait_for_readers(1, kPatience)) << "the Tool ECU subscribes to the RSP State";
    planner_ = std::thread([this] {
      while (running_) {
        {
          const std::lock_guard lock(mutex_);
          if (planning_) link_->send(tool_order_, lift_order_);
        }
        std::this_thread::sleep_for(milliseconds(100));
      }
    });
    rsp_ = std::thread([this] {
      const std::string name = "rsp";
      while (running_) {
        {
          const std::lock_guard lock(mutex_);
          if (rsp_alive_) {
            RspState state{};
            hubrt::msgs::typed::assign(state.name, name);
            hubrt::msgs::typed::assign(state.tool, robot_tool_);
            state.locked = robot_tool_ != "none";
            EXPECT_TRUE(rsp_writer_->write(state).is_ok());
          }
        }
        std::this_thread::sleep_for(milliseconds(100));
      }
    });
  }

  void order(ToolOrder tool, std::optional<LiftOrder> lift = std::nullopt) {
    const std::lock_guard lock(mutex_);
    tool_order_ = std::move(tool);
    if (lift) lift_order_ = std::move(*lift);
    planning_ = true;
  }
  void order_lift(LiftOrder lift) {
    const std::lock_guard lock(mutex_);
    lift_order_ = std::move(lift);
    planning_ = true;
  }
  void planner_goes_quiet() {
    const std::lock_guard lock(mutex_);
    planning_ = false;
  }
  void robot_holds(std::string tool) {
    const std::lock_guard lock(mutex_);
    robot_tool_ = std::move(tool);
  }
  void rsp_alive(bool alive) {
    const std::lock_guard lock(mutex_);
    rsp_alive_ = alive;
  }

  void sim_input(const std::string& signal, bool active) {
    const std::string hub = "tool_ecu";
    hub_msgs_msg_dds__SimInput_ input{wire(hub), wire(signal), active};
    ASSERT_TRUE(sim_input_writer_->write(input).is_ok());
  }
  void sim_fault(const std::string& device, const std::string& fault) {
    const std::string hub = "tool_ecu";
    hub_msgs_msg_dds__SimFault_ message{wire(hub), wire(device), wire(fault), 0};
    ASSERT_TRUE(sim_fault_writer_->write(message).is_ok());
  }

  // Takes States until `predicate` holds for the latest View; false after `timeout`. Between
  // takes it waits on the readers' data, not on a clock.
  bool wait_for(const std::function<bool(const View&)>& predicate, Duration timeout = kPatience) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    for (auto now = std::chrono::steady_clock::now(); now < deadline;
         now = std::chrono::steady_clock::now()) {
      if (link_->take(view_) && view_.tool.seen && view_.lift.seen && predicate(view_)) return true;
      link_->wait_for_data(deadline - now);
    }
    return false;
  }
  // Takes States until the hub's own clock (both nodes' State stamps) has moved on by `span` from
  // the latest State, calling `each` on every View on the way; false if that took longer than
  // kPatience. For "it stays so while the hub runs for a while": the hub says how long it ran, so a
  // slow machine only makes the test take longer, never makes it check less.
  bool watch_for(Duration span, const std::function<void(const View&)>& each) {
    if (!wait_for([](const View&) { return true; })) return false;
    const std::int64_t until = std::min(view_.tool.stamp_ns, view_.lift.stamp_ns) + span.count();
    return wait_for([&](const View& v) {
      each(v);
      return v.tool.stamp_ns >= until && v.lift.stamp_ns >= until;
    });
  }
  std::string describe() const {
    return fmt::format(
        "tool: output={} activity={} blocked_by='{}' result={}/{}/'{}' errors='{}'; lift: at='{}' "
        "errors='{}'\nhubd:\n{}",
        view_.tool.output, view_.tool.activity, view_.tool.blocked_by, view_.tool.result_run_id,
        view_.tool.result_ok, view_.tool.result_reasons, view_.tool.errors, view_.lift.at, view_.lift.errors,
        hub_ ? hub_->output() : "");
  }
  // The arm leaves home (the simulation board starts it there) and the robot holds the tool.
  void make_ready() {
    sim_input("tool.arm.home", false);
    robot_holds("smart_tool");
    ASSERT_TRUE(wait_for([](const View& v) {
      return v.tool.arm_position == "operating" && v.tool.robot_holds_tool && v.tool.controller_online;
    })) << describe();
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::unique_ptr<Link> link_;
  std::optional<dds::Topic<RspState>> rsp_topic_;
  std::optional<dds::Writer<RspState>> rsp_writer_;
  std::optional<dds::Topic<hub_msgs_msg_dds__SimInput_>> sim_input_topic_;
  std::optional<dds::Writer<hub_msgs_msg_dds__SimInput_>> sim_input_writer_;
  std::optional<dds::Topic<hub_msgs_msg_dds__SimFault_>> sim_fault_topic_;
  std::optional<dds::Writer<hub_msgs_msg_dds__SimFault_>> sim_fault_writer_;
  std::optional<HubProcess> hub_;
  std::string hub_file_dir_;
  View view_;

  std::mutex mutex_;  // guards the orders and the RSP stand-in's State
  ToolOrder tool_order_;
  LiftOrder lift_order_;
  bool planning_ = false;
  std::string robot_tool_ = "none";
  bool rsp_alive_ = true;
  std::atomic<bool> running_{true};
  std::thread planner_;
  std::thread rsp_;
};
}  // namespace hubrt::integration::tool_test
