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

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/test_support/hub_under_test.h"

#include "hubd_tool_links.h"
#include "rsp.h"

// The RSP ECU's State type, for the stand-in RSP ECU (its own hub library is not needed here).
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__RspState_, hub_msgs_msg_dds__RspState__desc);

namespace hubrt::integration::tool_test {

using std::chrono::milliseconds;
using std::chrono::seconds;
using test_support::HubUnderTest;
using RspState = hub_msgs_msg_dds__RspState_;

// Generous: a busy 2-core machine running sanitizer builds in parallel. These tests check
// behaviour, not timing; the benchmarks measure timing.
inline constexpr auto kPatience = seconds(20);

enum class Layout { kNodeType, kHub };

class HubdToolTest : public ::testing::TestWithParam<Layout> {
 protected:
  void SetUp() override {
    ASSERT_NO_FATAL_FAILURE(hub_.open());
    if (GetParam() == Layout::kHub) {
      link_ = std::make_unique<HubLink>(hub_.participant());
    } else {
      link_ = std::make_unique<NodeTypeLink>(hub_.participant());
    }
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(rsp_writer_, "/rsp_ecu/rsp/state"));
  }

  // The planner first (it writes through the link), then the link's endpoints, before hub_'s
  // participant goes.
  void TearDown() override {
    hub_.stop_planner();
    link_.reset();
  }

  // Starts hubd (the shipped hub file, or in the hub layout a copy of it with `layout: hub`), the
  // planner (commands every 100 ms) and the stand-in RSP ECU (State every 100 ms).
  void start() {
    const std::string hub = GetParam() == Layout::kHub ? hub_.hub_file("tool_ecu", "hub") : "tool_ecu";
    // hubd matching the RSP State writer: the Tool ECU subscribes to the RSP State.
    ASSERT_NO_FATAL_FAILURE(hub_.start({.hub = hub}));
    ASSERT_TRUE(link_->wait_for_hub(kPatience)) << hub_.output();
    hub_.plan([this] { tick(); }, milliseconds(100));
  }

  // One round of the planner and the RSP stand-in.
  void tick() {
    const std::lock_guard lock(mutex_);
    if (planning_) link_->send(tool_order_, lift_order_);
    if (rsp_alive_) {
      const std::string name = "rsp";
      RspState state{};
      hubrt::msgs::typed::assign(state.name, name);
      hubrt::msgs::typed::assign(state.tool, robot_tool_);
      state.locked = robot_tool_ != "none";
      EXPECT_TRUE(rsp_writer_->write(state).is_ok());
    }
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

  void sim_input(const std::string& signal, bool active) { hub_.sim_input("tool_ecu", signal, active); }
  void sim_fault(const std::string& device, const std::string& fault) {
    hub_.sim_fault("tool_ecu", device, fault);
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
        hub_.output());
  }
  // The arm leaves home (the simulation board starts it there) and the robot holds the tool.
  void make_ready() {
    sim_input("tool.arm.home", false);
    robot_holds("smart_tool");
    ASSERT_TRUE(wait_for([](const View& v) {
      return v.tool.arm_position == "operating" && v.tool.robot_holds_tool && v.tool.controller_online;
    })) << describe();
  }

  std::unique_ptr<Link> link_;
  dds::Writer<RspState>* rsp_writer_ = nullptr;
  View view_;

  std::mutex mutex_;  // guards the orders and the RSP stand-in's State
  ToolOrder tool_order_;
  LiftOrder lift_order_;
  bool planning_ = false;
  std::string robot_tool_ = "none";
  bool rsp_alive_ = true;
  HubUnderTest hub_{kPatience};
};
}  // namespace hubrt::integration::tool_test
