// The test node type: opens a valve on "open", closes it otherwise; a latched "overpressure"
// fault, cleared by reset, keeps it closed. Its valve device can go missing (device_missing).
#pragma once

#include <array>
#include <string_view>
#include <vector>

#include "hubrt/runtime/node.h"

#include "valve_test_typed.h"

namespace hubrt::runtime::testing {

using ValveCommand = hubrt_test_msg_dds__ValveCommand_;  // the wire types, for the ports
using ValveState = hubrt_test_msg_dds__ValveState_;

struct ValveWorld {  // what the test observes and pokes, shared with the logic by reference
  bool open = false;
  bool overpressure_input = false;
  bool device_missing = false;            // the valve's device is not open (condition() reports it)
  bool last_update_with_command = false;  // what the last update() was given
  int updates_with_command = 0;
  int updates_without_command = 0;
  int resets = 0;
  int safe_state_entries = 0;
  std::string last_action;
};

class ValveLogic {
 public:
  using Command = hubrt_test::ValveCommandView;
  using State = hubrt_test::ValveState;
  static constexpr std::string_view kType = "valve";
  static constexpr std::array<std::string_view, 3> kActions{"open", "close", "reset"};

  explicit ValveLogic(ValveWorld& world) : world_(&world) {}

  bool validate(const Command& command, Problem& problem) const noexcept {
    if (command.pressure_bar() < 0.0f || command.pressure_bar() > 10.0f) {
      problem.format("pressure_bar {} is out of range [0, 10]", command.pressure_bar());
      return false;
    }
    return true;
  }
  void read_inputs(Time /*now*/) noexcept {
    if (world_->overpressure_input) fault_latched_ = true;
  }
  NodeCondition condition() const noexcept {
    if (fault_latched_) return NodeCondition::kFault;
    return world_->device_missing ? NodeCondition::kDevicesMissing : NodeCondition::kOk;
  }
  void update(const Command* command, Time /*now*/) noexcept {
    world_->last_update_with_command = command != nullptr;
    if (command == nullptr) {
      ++world_->updates_without_command;
      world_->open = false;
      return;
    }
    ++world_->updates_with_command;
    world_->last_action = command->action();  // test-only bookkeeping; allocation-free for short actions
    world_->open = !fault_latched_ && command->action() == "open";
  }
  void reset() noexcept {
    ++world_->resets;
    fault_latched_ = false;
  }
  void report(State& state, ErrorList& errors, Time /*now*/) noexcept {
    state.set_open(world_->open);
    if (fault_latched_) errors.add("overpressure: valve held closed until reset");
    if (world_->device_missing) errors.add("valve device not available");
  }
  void enter_safe_state() noexcept {
    ++world_->safe_state_entries;
    world_->open = false;
  }

 private:
  ValveWorld* world_;
  bool fault_latched_ = false;
};

static_assert(NodeLogic<ValveLogic>);

}  // namespace hubrt::runtime::testing
