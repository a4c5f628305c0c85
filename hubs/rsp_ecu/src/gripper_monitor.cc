#include "gripper_monitor.h"

#include <algorithm>

namespace hubrt::rsp_ecu {
namespace {

std::string_view on_off(bool active) noexcept {
  return active ? "on" : "off";
}

}  // namespace

void GripperMonitor::observe(bool a_readable, bool a, bool b_readable, bool b, Time now) noexcept {
  line_a_ = a;
  line_b_ = b;
  if (!a_readable || !b_readable) {
    // The input's own error says which line; nothing about the gripper can be confirmed, and
    // nothing is claimed either (no fault: a line that cannot be read is not a failed grip).
    disagree_since_.reset();
    confirm_ = Confirm::kUnknown;
    return;
  }
  if (a == b) {
    disagree_since_.reset();
    confirm_ = a ? Confirm::kConnected : Confirm::kNotConnected;
    return;
  }
  if (!disagree_since_) disagree_since_ = now;
  confirm_ = now - *disagree_since_ > confirm_time_ ? Confirm::kFailed : Confirm::kMoving;
}

void GripperMonitor::valve(bool grab, Time now) noexcept {
  if (grab_ && *grab_ == grab) return;
  grab_ = grab;
  grab_since_ = now;
}

void GripperMonitor::supervise(bool active, Time now) noexcept {
  if (!active || !grab_) {
    active_since_.reset();
    return;
  }
  if (!active_since_) active_since_ = now;
  if (faulted()) return;  // the first fault is the one to see
  if (confirm_ == Confirm::kFailed && disagree_since_) {
    fault_.format("gripper failed: confirm lines disagree (A {}, B {}) for more than {} ms", on_off(line_a_),
                  on_off(line_b_),
                  std::chrono::duration_cast<std::chrono::milliseconds>(confirm_time_).count());
    return;
  }
  // Lines that disagree ("moving") have their own clock above; this is the gripper that stays in
  // the other end position.
  const Confirm other = *grab_ ? Confirm::kNotConnected : Confirm::kConnected;
  const Time since = std::max(grab_since_, *active_since_);
  if (confirm_ == other && now - since > confirm_time_) {
    fault_.format("gripper failed to {}: confirm lines still show {} after {} ms (limit {} ms)",
                  *grab_ ? "grab" : "release", confirm_name(),
                  std::chrono::duration_cast<std::chrono::milliseconds>(now - since).count(),
                  std::chrono::duration_cast<std::chrono::milliseconds>(confirm_time_).count());
  }
}

std::string_view GripperMonitor::confirm_name() const noexcept {
  switch (confirm_) {
    case Confirm::kNotConnected:
      return "not_connected";
    case Confirm::kConnected:
      return "connected";
    case Confirm::kMoving:
      return "moving";
    case Confirm::kFailed:
      return "failed";
    case Confirm::kUnknown:
      return "unknown";
  }
  return "failed";
}

}  // namespace hubrt::rsp_ecu
