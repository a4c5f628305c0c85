#include "operator_panel_logic.h"

#include <chrono>

namespace hubrt::operator_hub {
namespace {

float seconds_since(Time then, Time now) noexcept {
  return std::chrono::duration<float>(now - then).count();
}

}  // namespace

Expected<OperatorPanelLogic> OperatorPanelLogic::create(AllowList allow_list, OperatorDevices devices,
                                                        const ScreenConfirmInput* screen, Time /*now*/) {
  auto hasher = BadgeHasher::create();
  if (!hasher) return std::move(hasher).error();
  return OperatorPanelLogic(std::move(allow_list), std::move(devices), std::move(*hasher), screen);
}

OperatorPanelLogic::OperatorPanelLogic(AllowList allow_list, OperatorDevices devices, BadgeHasher hasher,
                                       const ScreenConfirmInput* screen) noexcept
    : allow_list_(std::move(allow_list)),
      devices_(std::move(devices)),
      hasher_(std::move(hasher)),
      screen_(screen) {
  // A press that the screen published before this hub started is no press for us.
  if (screen_ != nullptr) screen_samples_seen_ = screen_->received();
}

void OperatorPanelLogic::read_inputs(Time now) noexcept {
  badge_pending_ = false;
  press_pending_ = PressSource::kNone;

  const Result<bool> polled = hal::poll_badge(devices_.reader, badge_, now);
  if (polled.is_ok()) {
    badge_pending_ = polled.value();
  } else if (polled.status().code() != ErrorCode::kUnavailable) {
    ++read_failures_;
  }

  if (devices_.button) {
    const Result<bool> level = devices_.button->read(now);
    if (level.is_ok()) {
      // A press is the change to pressed; a button held at start (or when it came back) is none.
      if (button_level_.has_value() && !*button_level_ && level.value())
        press_pending_ = PressSource::kButton;
      button_level_ = level.value();
    } else {
      button_level_.reset();
    }
  }

  if (screen_ != nullptr && screen_->received() != screen_samples_seen_) {
    screen_samples_seen_ = screen_->received();
    const auto press = screen_->fresh(now);
    if (press && (!last_screen_press_ || *last_screen_press_ != press->press_id())) {
      last_screen_press_ = press->press_id();
      if (press_pending_ == PressSource::kNone) press_pending_ = PressSource::kScreen;
    }
  }
}

runtime::NodeCondition OperatorPanelLogic::condition() const noexcept {
  if (read_failures_ > 0) return runtime::NodeCondition::kFault;
  if (!devices_.reader.is_open()) return runtime::NodeCondition::kDevicesMissing;
  if (devices_.button && !devices_.button->is_open()) return runtime::NodeCondition::kDevicesMissing;
  return runtime::NodeCondition::kOk;
}

void OperatorPanelLogic::reject(std::string_view reason) noexcept {
  last_result_ = BadgeResult::kRejected;
  last_reason_.assign(reason);
}

void OperatorPanelLogic::take_badge(const Command* in_force, Time now) noexcept {
  if (!badge_pending_) return;
  ++badge_reads_;
  last_tag_set_ = false;
  if (badge_.malformed) {
    last_reason_.format("malformed: {}", badge_.problem);
    last_result_ = BadgeResult::kRejected;
    return;
  }
  BadgeDigest digest{};
  if (!hasher_.hash(allow_list_.salt(), badge_.text(), digest)) {
    reject("could not hash the badge (libcrypto failed)");
    return;
  }
  to_hex(std::span<const std::uint8_t>(digest.data(), last_tag_.size() / 2), last_tag_);
  last_tag_set_ = true;
  // The read is done with: its text is not kept.
  badge_.chars.fill('\0');
  badge_.length = 0;
  if (in_force == nullptr) {
    reject("not verifying: no verify command in force");
    return;
  }
  if (in_force->action() != "verify") {
    reject(in_force->action() == "logout" ? "logout in force" : "reset in force");
    return;
  }
  const AllowedOperator* found = allow_list_.find(digest);
  if (found == nullptr) {
    reject("unknown badge");
    return;
  }
  if (found != verified_) verified_since_ = now;
  verified_ = found;
  last_result_ = BadgeResult::kAccepted;
  last_reason_.assign("");
}

void OperatorPanelLogic::take_press(const Command* in_force, Time now) noexcept {
  if (press_pending_ == PressSource::kNone) return;
  // Only a verified operator confirms, and only while the planner listens (verify in force).
  if (in_force == nullptr || in_force->action() != "verify" || verified_ == nullptr) return;
  ++confirm_seq_;
  last_press_source_ = press_pending_;
  last_press_at_ = now;
}

void OperatorPanelLogic::update(const Command* in_force, Time now) noexcept {
  if (in_force == nullptr || in_force->action() != "verify") log_out();
  take_badge(in_force, now);
  take_press(in_force, now);
  badge_pending_ = false;
  press_pending_ = PressSource::kNone;
}

void OperatorPanelLogic::reset() noexcept {
  log_out();
  read_failures_ = 0;
  last_result_ = BadgeResult::kNone;
  last_tag_set_ = false;
  last_reason_.assign("");
}

void OperatorPanelLogic::report(State& state, runtime::ErrorList& errors, Time now) const noexcept {
  state.set_reader_open(devices_.reader.is_open());
  state.set_operator_verified(verified_ != nullptr);
  state.set_operator_name(verified_ != nullptr ? std::string_view(verified_->name) : std::string_view{});
  state.set_verified_for(verified_ != nullptr ? seconds_since(verified_since_, now) : 0.0F);
  state.set_badge_reads(badge_reads_);
  state.set_last_badge(last_result_ == BadgeResult::kAccepted   ? "accepted"
                       : last_result_ == BadgeResult::kRejected ? "rejected"
                                                                : "");
  state.set_last_badge_tag(last_tag_set_ ? std::string_view(last_tag_.data(), last_tag_.size()) : "");
  state.set_last_badge_reason(last_reason_.view());
  state.set_confirm_seq(confirm_seq_);
  state.set_confirm_source(last_press_source_ == PressSource::kButton   ? "button"
                           : last_press_source_ == PressSource::kScreen ? "screen"
                                                                        : "");
  state.set_confirm_age(confirm_seq_ > 0 ? seconds_since(last_press_at_, now) : 0.0F);

  if (!devices_.reader.is_open()) {
    errors.add("RFID reader {} not available: {}", devices_.reader.name(), devices_.reader.error());
  } else if (read_failures_ > 0) {
    errors.add("RFID reader {} failed to read {} time(s) since the last reset", devices_.reader.name(),
               read_failures_);
  }
  if (devices_.button && !devices_.button->is_open()) {
    errors.add("confirm button {} not available: {}", devices_.button->name(), devices_.button->error());
  }
}

}  // namespace hubrt::operator_hub
