// The lamp node: one digital output driving a stack light. Its commands light it ("on"), put it
// out ("off") or clear a latched failure ("reset"). Safe state: out. The output is opened by the
// hub type (signal_lamp_hub_type.cc) and handed in as a supervised device, so that a lamp whose
// GPIO chip goes away is opened again with back-off, with no restart.
//
// What it latches: a write that failed for any reason but "the chip went away" (an I/O error on
// a line that is still there) is a fault until a reset — the operator sees a lamp that did not
// follow its command instead of a lamp that flickers.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_requirements.h"
#include "hubrt/hal/common/supervised_device.h"
#include "hubrt/runtime/node.h"

#include "lamp_messages.h"

namespace hubrt::signal_lamp {

// Reads and checks the node's settings: `signal: <board output>`. Errors name file:line.
Expected<std::string> parse_lamp_signal(const config::NodeConfig& node);

class LampLogic {
 public:
  using Command = hub_msgs::LampCommandView;
  using State = hub_msgs::LampState;
  static constexpr std::string_view kType = "lamp";
  static constexpr std::array<std::string_view, 3> kActions{"on", "off", "reset"};

  // `output`: the lamp's line, opened by the hub type; one that is not open is reported and
  // retried by every update().
  explicit LampLogic(hal::SupervisedOutput output) noexcept : output_(std::move(output)) {}
  LampLogic(LampLogic&&) noexcept = default;
  LampLogic& operator=(LampLogic&&) noexcept = default;

  // The action is already one of kActions and the command has no other fields: nothing to check.
  bool validate(const Command& /*command*/, runtime::Problem& /*problem*/) const noexcept { return true; }
  void read_inputs(Time /*now*/) noexcept {}  // no inputs
  // kFault: a write failed since the last reset (latched); kDevicesMissing: the line is not open.
  runtime::NodeCondition condition() const noexcept;
  // Lit only while operational with "on" in force; otherwise out (the safe state).
  void update(const Command* in_force, Time now) noexcept;
  void reset() noexcept;
  void report(State& state, runtime::ErrorList& errors, Time now) const noexcept;
  void enter_safe_state() noexcept;

  [[nodiscard]] bool lit() const noexcept { return output_.driven(); }

 private:
  hal::SupervisedOutput output_;
  Status last_write_ = Status::ok();
  std::uint32_t failures_ = 0;  // writes that failed (other than "gone") since the last reset
  ErrorCode last_failure_ = ErrorCode::kOk;
};

// What the node needs from the board.
void add_requirements(const std::string& signal, hal::BoardRequirements& requirements);

}  // namespace hubrt::signal_lamp
