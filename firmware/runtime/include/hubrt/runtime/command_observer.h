// A hook on the command path: every command a node takes, with its source timestamp and the
// instant the cycle took it, and what became of it. For a recorder of the hub's commands (a black
// box) or a test; the node's own reports (error_list, log, /diagnostics) do not need it.
#pragma once

#include <cstdint>
#include <string_view>

#include "hubrt/runtime/command_age.h"

namespace hubrt::runtime {

// What became of one command a node took from its source (CommandObserver).
enum class CommandOutcome : std::uint8_t {
  kNotAddressed,  // for another node of the type (node-type layout): not this node's
  kTookEffect,    // valid, young, new content (or nothing was in force): acts now
  kRepeat,        // valid, young, the content in force: fed the watchdog
  kRejected,      // invalid, stamped in the future beyond the tolerance, or too large to hold
  kStale,         // older than the command timeout (command_age.h)
  kQueued,        // taken while the hub caught up after a stall: discarded
};

// Sees every command a node takes, with when it was written and taken and what became of it
// (e.g. a recorder of the command path). Called on the cycle thread; must not block or allocate.
// `command` is the node's Command wire struct, valid during the call only.
class CommandObserver {
 public:
  virtual ~CommandObserver() = default;
  virtual void on_command(std::string_view node, const void* command, const CommandTimes& times,
                          CommandOutcome outcome) noexcept = 0;
};

}  // namespace hubrt::runtime
