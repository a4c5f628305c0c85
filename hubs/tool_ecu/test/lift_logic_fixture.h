// The lift logic's test fixture: the node on the manual clock in front of the lift drive model
// (hal/fake LiftDrive) through a scripted asynchronous Modbus device (scripted_async_modbus.h): a
// request the logic submits reaches the drive only when the test completes it, so every lift test
// is deterministic and nothing waits in real time.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/fake/lift_drive.h"
#include "hubrt/protocol/lift_drive_modbus.h"

#include "lift_logic.h"
#include "scripted_async_modbus.h"

namespace hubrt::tool_ecu::testing {

namespace ld = protocol::lift_drive;
using std::chrono::milliseconds;

inline constexpr auto kStep =
    milliseconds(100);  // manual time per cycle (the hub's 10 Hz); answer_within is 500 ms

struct Order {
  std::string action;
  std::string position;
  std::string target_name = "lift";
  std::string target_type = "lift";

  [[nodiscard]] hub_msgs::LiftCommand message() const {
    hub_msgs::LiftCommand command;
    command.set_target_type(target_type);
    command.set_target_name(target_name);
    command.set_action(action);
    command.set_position(position);
    return command;
  }
};

inline Order move(std::string position) {
  Order order;
  order.action = "move";
  order.position = std::move(position);
  return order;
}
inline Order action(std::string name) {
  Order order;
  order.action = std::move(name);
  return order;
}

class LiftLogicTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto config = config::load_hub_config(std::string(HUBRT_HUBS_DIR) + "/tool_ecu/tool_ecu.yaml");
    ASSERT_TRUE(config) << config.error().message;
    for (const auto& node : config->nodes) {
      if (node.type == LiftLogic::kType) {
        auto settings = parse_lift_settings(node);
        ASSERT_TRUE(settings) << settings.error().message;
        settings_ = std::move(*settings);
      }
    }
  }
  void TearDown() override { close(); }

  void start() {
    auto logic = LiftLogic::create(settings_, script_.open(), clock_.now().mono);
    ASSERT_TRUE(logic) << logic.error().message;
    logic_.emplace(std::move(*logic));
  }
  // Destroys the logic, and with it the device: its write-on-close reaches the drive now.
  void close() {
    script_.set_close_time(clock_.now().mono);
    logic_.reset();
  }

  // One cycle at the current manual time, as the Node runs it.
  void cycle(const Order* order) {
    const Time now = clock_.now().mono;
    if (order != nullptr) command_ = order->message();
    logic_->read_inputs(now);
    const hub_msgs::LiftCommandView in_force = command_.view();
    logic_->update(order == nullptr ? nullptr : &in_force, now);
    errors_.clear();
    state_ = hub_msgs::LiftState();
    logic_->report(state_, errors_, now);
  }
  // Advances the manual clock one step; the request the last cycle submitted runs at the new time
  // (the drive answers it, or — while `answering_` is false — the client's response timeout ends
  // it without reaching the drive); then cycles.
  void step(const Order* order) {
    clock_.advance(kStep);
    script_.complete(clock_.now().mono, answering_ ? ErrorCode::kOk : ErrorCode::kTimeout);
    cycle(order);
  }
  void steps(const Order& order, int n) {
    for (int i = 0; i < n; ++i) step(&order);
  }
  template <class Predicate>
  bool step_until(const Order* order, Predicate done, int limit = 80) {
    for (int i = 0; i < limit; ++i) {
      step(order);
      if (done()) return true;
    }
    return false;
  }
  void reset_command() {
    logic_->reset();
    const Order reset = action("reset");
    step(&reset);
  }
  [[nodiscard]] std::string errors() const {
    std::string out;
    for (std::size_t i = 0; i < errors_.size(); ++i) out += std::string(errors_.at(i)) + "; ";
    return out;
  }
  [[nodiscard]] std::uint16_t drive_control_word() { return drive_.read(clock_.now().mono).control_word(); }
  // The control word the last submitted request writes (0 when it writes nothing).
  [[nodiscard]] std::uint16_t submitted_control_word() const {
    const hal::ModbusBatch& last = script_.submitted().back();
    return last.write_count > 0 ? last.write_values[ld::holding::kControlWord] : 0;
  }

  ManualClock clock_;
  LiftSettings settings_;
  hal::fake::LiftDrive drive_{hal::fake::LiftDriveConfig{}, clock_.now().mono};
  DriveScript script_{drive_};
  bool answering_ = true;
  std::optional<LiftLogic> logic_;
  hub_msgs::LiftCommand command_;
  hub_msgs::LiftState state_;
  runtime::ErrorList errors_;
};

}  // namespace hubrt::tool_ecu::testing
