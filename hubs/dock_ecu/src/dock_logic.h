// The dock node: one presence sensor per slot, configured in the hub file. Inputs only: its
// commands ask it to report ("monitor") or to clear what it latched ("reset").
//
// What it latches: a sensor that failed to read, even once, is reported until a reset — an
// intermittent wire shows up to the operator instead of flickering past unseen.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_requirements.h"
#include "hubrt/hal/common/supervised_device.h"
#include "hubrt/runtime/node.h"

#include "dock_messages.h"

namespace hubrt::dock_ecu {

struct SlotConfig {
  std::string name;    // reported in the State, e.g. "smart_tool"
  std::string signal;  // board input signal, e.g. "dock.slot.smart_tool"
};

// Reads and checks the node's settings: `slots: [{name, signal}, ...]`, 1..16 slots, names unique
// and usable as identifiers. Errors name file:line.
Expected<std::vector<SlotConfig>> parse_slots(const config::NodeConfig& node);

class DockLogic {
 public:
  using Command = hub_msgs::DockCommandView;
  using State = hub_msgs::DockState;
  static constexpr std::string_view kType = "dock";
  static constexpr std::array<std::string_view, 2> kActions{"monitor", "reset"};
  static constexpr std::size_t kMaxSlots = 16;  // = the bound of DockState.slots in dock.idl

  // `sensors`: one per slot, in the order of `slots`, opened by the hub type
  // (open_slot_sensors()); one that is not open is reported and retried.
  // Errors: kInvalidArgument when the counts differ.
  static Expected<DockLogic> create(const std::vector<SlotConfig>& slots,
                                    std::vector<hal::SupervisedInput> sensors);

  DockLogic(DockLogic&&) noexcept = default;
  DockLogic& operator=(DockLogic&&) noexcept = default;

  bool validate(const Command& /*command*/, runtime::Problem& /*problem*/) const noexcept { return true; }
  void read_inputs(Time now) noexcept;
  // kFault: a sensor failed to read since the last reset (latched); kDevicesMissing: a sensor is
  // not open.
  runtime::NodeCondition condition() const noexcept;
  void update(const Command* /*in_force*/, Time /*now*/) noexcept {}  // no outputs
  void reset() noexcept;
  void report(State& state, runtime::ErrorList& errors, Time now) noexcept;
  void enter_safe_state() noexcept {}  // nothing to drive

  [[nodiscard]] std::size_t slot_count() const noexcept { return slots_.size(); }
  [[nodiscard]] bool occupied(std::size_t slot) const noexcept { return slots_[slot].occupied; }

 private:
  struct Slot {
    std::string name;
    hal::SupervisedInput sensor;
    bool occupied = false;
    bool readable = false;       // the last read worked
    std::uint32_t failures = 0;  // reads that failed since the last reset
    ErrorCode last_failure = ErrorCode::kOk;
  };

  DockLogic() = default;

  std::vector<Slot> slots_;
};

// What the node needs from the board.
void add_requirements(const std::vector<SlotConfig>& slots, hal::BoardRequirements& requirements);

}  // namespace hubrt::dock_ecu
