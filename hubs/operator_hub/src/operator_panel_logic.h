// The operator panel node (the paper's RFIDCAM and the smart-watch confirm): an RFID reader that
// verifies the operator against the allow-list, and confirm presses from a GPIO button or from
// an operator screen's topic, each with a sequence number so the planner tells a new press from
// an old one.
//
// Safe state (not operational: no valid command in force, reader missing, fault): nobody is
// verified, badges are refused and presses are dropped — a confirm the planner did not see
// happen must never be taken later, and collaborative steps need a verified operator.
// What it latches: a reader that fails to read while it is there (kIo) is a fault until reset.
// Badges never appear in clear: the State and the errors show 8 hex digits of the salted hash.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>

#include "hubrt/hal/common/supervised_badge_reader.h"
#include "hubrt/hal/common/supervised_device.h"
#include "hubrt/hub_api/remote_state.h"
#include "hubrt/runtime/node.h"
#include "hubrt/runtime/text_buffer.h"

#include "allow_list.h"
#include "operator_messages.h"

namespace hubrt::operator_hub {

using ScreenConfirmInput = hub_api::RemoteState<hub_msgs::OperatorConfirmView>;

struct OperatorDevices {
  hal::SupervisedBadgeReader reader;
  std::optional<hal::SupervisedInput> button;  // none when the node has no confirm_button
};

class OperatorPanelLogic {
 public:
  using Command = hub_msgs::OperatorPanelCommandView;
  using State = hub_msgs::OperatorPanelState;
  static constexpr std::string_view kType = "operator_panel";
  static constexpr std::array<std::string_view, 3> kActions{"verify", "logout", "reset"};

  // `screen`: the screen's confirm topic (a subscription of the hub), or nullptr; it must
  // outlive the logic. Errors: kInternal when libcrypto has no SHA-256.
  static Expected<OperatorPanelLogic> create(AllowList allow_list, OperatorDevices devices,
                                             const ScreenConfirmInput* screen, Time now);

  bool validate(const Command& /*command*/, runtime::Problem& /*problem*/) const noexcept { return true; }
  // Takes at most one badge, the button's level and the screen's latest press.
  void read_inputs(Time now) noexcept;
  // kFault: the reader failed to read (latched); kDevicesMissing: the reader or button not open.
  runtime::NodeCondition condition() const noexcept;
  // Decides what the badge and the press of this cycle do, by the command in force.
  void update(const Command* in_force, Time now) noexcept;
  void reset() noexcept;
  void report(State& state, runtime::ErrorList& errors, Time now) const noexcept;
  void enter_safe_state() noexcept { log_out(); }

  [[nodiscard]] bool operator_verified() const noexcept { return verified_ != nullptr; }
  [[nodiscard]] std::uint32_t confirm_seq() const noexcept { return confirm_seq_; }

 private:
  enum class PressSource : std::uint8_t { kNone, kButton, kScreen };
  enum class BadgeResult : std::uint8_t { kNone, kAccepted, kRejected };

  OperatorPanelLogic(AllowList allow_list, OperatorDevices devices, BadgeHasher hasher,
                     const ScreenConfirmInput* screen) noexcept;
  void log_out() noexcept { verified_ = nullptr; }
  void take_badge(const Command* in_force, Time now) noexcept;
  void take_press(const Command* in_force, Time now) noexcept;
  void reject(std::string_view reason) noexcept;

  AllowList allow_list_;
  OperatorDevices devices_;
  BadgeHasher hasher_;
  const ScreenConfirmInput* screen_;

  // This cycle's inputs, decided by update().
  bool badge_pending_ = false;
  hal::BadgeRead badge_;
  PressSource press_pending_ = PressSource::kNone;

  // Inputs' history.
  std::optional<bool> button_level_;  // last level read; none until the first read
  std::uint64_t screen_samples_seen_ = 0;
  std::optional<std::uint32_t> last_screen_press_;
  std::uint32_t read_failures_ = 0;  // kIo from the reader since the last reset (latched)

  // What the State shows.
  const AllowedOperator* verified_ = nullptr;
  Time verified_since_{};
  std::uint32_t badge_reads_ = 0;
  BadgeResult last_result_ = BadgeResult::kNone;
  std::array<char, 8> last_tag_{};
  bool last_tag_set_ = false;
  runtime::TextBuffer<95> last_reason_;
  std::uint32_t confirm_seq_ = 0;
  PressSource last_press_source_ = PressSource::kNone;
  Time last_press_at_{};
};

}  // namespace hubrt::operator_hub
