// The lifecycle of a hub and of each of its nodes: a small set of explicit states, each entered
// for a reason that is logged once per transition, counted, and reported (every node State's
// header.lifecycle, /diagnostics).
//
//   hub:  configuring → opening_devices → (running: the worst state of its nodes) → stopping
//   node: opening_devices → safe | operational | fault | recovering, decided again every step
//         (Node::advance(), after the inputs are read, before the logic decides its outputs);
//         the hub stopping leaves every node safe for good.
//
// A node is in exactly one of:
//   - safe:        no command in force — none received yet, or the command watchdog tripped, or
//                  the hub is stopping;
//   - operational: a fresh valid command is in force and the logic reports nothing wrong;
//   - fault:       the logic holds a latched fault that only a reset command clears;
//   - recovering:  a device the node needs is not open; it is being retried.
// fault outranks recovering, which outranks safe: a planner that comes back to a faulted node
// learns that it must send a reset. The node's outputs follow the command in force only while it
// is operational; in every other state the runtime hands the logic no command (its safe state).
//
// The hub's own state is a phase while it has no cycle running (configuring, opening_devices,
// stopping) and, while it runs, the worst state of its nodes (fault > recovering > safe >
// operational).
//
// The numbers are on the wire (StateHeader.lifecycle; the LIFECYCLE_* constants of
// firmware/msgs/msg/StateHeader.msg): never renumber them.
#pragma once

#include <cstdint>
#include <string_view>

#include "hubrt/runtime/text_buffer.h"

namespace hubrt::runtime {

enum class Lifecycle : std::uint8_t {
  kConfiguring = 0,     // the hub reads its files (hub phase)
  kOpeningDevices = 1,  // the devices are being opened; no cycle has run yet
  kSafe = 2,
  kOperational = 3,
  kFault = 4,
  kRecovering = 5,
  kStopping = 6,  // the hub leaves its cycle, outputs driven safe (hub phase)
};

// What the logic knows of its own condition, asked once per step after it read its inputs.
enum class NodeCondition : std::uint8_t {
  kOk,              // nothing keeps the node from following its command
  kFault,           // a latched fault that needs a reset command
  kDevicesMissing,  // a device the node needs is not open (being retried)
};

// The name of a lifecycle state as the wire number carries it; "unknown" for any other number
// (a newer peer). Names are stable: tools and docs use them.
constexpr std::string_view lifecycle_name(std::uint8_t value) noexcept {
  switch (value) {
    case 0:
      return "configuring";
    case 1:
      return "opening_devices";
    case 2:
      return "safe";
    case 3:
      return "operational";
    case 4:
      return "fault";
    case 5:
      return "recovering";
    case 6:
      return "stopping";
    default:
      return "unknown";
  }
}
constexpr std::string_view lifecycle_name(Lifecycle state) noexcept {
  return lifecycle_name(static_cast<std::uint8_t>(state));
}

// How bad a running state is, for the hub's "worst of its nodes": operational 0, safe 1,
// recovering 2, fault 3; the phases without a running cycle rank with safe.
constexpr int severity(Lifecycle state) noexcept {
  switch (state) {
    case Lifecycle::kOperational:
      return 0;
    case Lifecycle::kRecovering:
      return 2;
    case Lifecycle::kFault:
      return 3;
    default:
      return 1;
  }
}

// The rule of a node's state for one step. `stopping`: the hub drives everything safe on its way
// out; `command_in_force`: the command tracker has a fresh valid command in force.
constexpr Lifecycle node_lifecycle(bool stopping, bool command_in_force, NodeCondition condition) noexcept {
  if (stopping) return Lifecycle::kSafe;
  if (condition == NodeCondition::kFault) return Lifecycle::kFault;
  if (condition == NodeCondition::kDevicesMissing) return Lifecycle::kRecovering;
  return command_in_force ? Lifecycle::kOperational : Lifecycle::kSafe;
}

// One lifecycle state machine's current state, the reason it was entered and the number of
// transitions. Fixed storage: never allocates. Thread-safety: cycle thread only.
class LifecycleState {
 public:
  static constexpr std::size_t kMaxReasonLength = 159;
  using Reason = TextBuffer<kMaxReasonLength>;

  explicit LifecycleState(Lifecycle initial, std::string_view reason) noexcept : state_(initial) {
    reason_.assign(reason);
  }

  // Moves to `next`, entered because of the formatted reason. Returns true when the state changed
  // (then the reason is replaced and the transition counted); staying in the same state changes
  // nothing, so the reason stays the one of the transition.
  template <class... Args>
  bool enter(Lifecycle next, fmt::format_string<Args...> reason, Args&&... args) noexcept {
    if (next == state_) return false;
    previous_ = state_;
    state_ = next;
    ++transitions_;
    reason_.format(reason, std::forward<Args>(args)...);
    reason_.make_valid_utf8();
    return true;
  }
  // Adds detail to the reason of the transition just made (e.g. the logic's first error, known
  // only once it reported). Cut at the capacity like any reason.
  void add_detail(std::string_view detail) noexcept {
    Reason joined;
    joined.format("{}: {}", reason_.view(), detail);
    reason_.assign(joined.view());
    reason_.make_valid_utf8();
  }

  [[nodiscard]] Lifecycle state() const noexcept { return state_; }
  [[nodiscard]] Lifecycle previous() const noexcept { return previous_; }
  [[nodiscard]] std::string_view name() const noexcept { return lifecycle_name(state_); }
  [[nodiscard]] std::string_view reason() const noexcept { return reason_.view(); }
  [[nodiscard]] std::uint64_t transitions() const noexcept { return transitions_; }

 private:
  Lifecycle state_;
  Lifecycle previous_ = Lifecycle::kConfiguring;
  Reason reason_;
  std::uint64_t transitions_ = 0;
};

}  // namespace hubrt::runtime
