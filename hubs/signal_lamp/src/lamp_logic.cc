#include "lamp_logic.h"

namespace hubrt::signal_lamp {

Expected<std::string> parse_lamp_signal(const config::NodeConfig& node) {
  const config::YamlMap& settings = node.settings;
  if (auto ok = settings.only_keys({"type", "signal"}); !ok) return std::move(ok).error();
  return settings.string("signal");
}

void add_requirements(const std::string& signal, hal::BoardRequirements& requirements) {
  requirements.outputs.push_back(signal);
}

runtime::NodeCondition LampLogic::condition() const noexcept {
  if (failures_ > 0) return runtime::NodeCondition::kFault;
  if (!output_.is_open()) return runtime::NodeCondition::kDevicesMissing;
  return runtime::NodeCondition::kOk;
}

void LampLogic::update(const Command* in_force, Time now) noexcept {
  const bool on = in_force != nullptr && in_force->action() == "on";
  // write() also opens the line again once its back-off has passed (a vanished chip came back).
  last_write_ = output_.write(on, now);
  if (!last_write_.is_ok() && last_write_.code() != ErrorCode::kUnavailable) {
    ++failures_;
    last_failure_ = last_write_.code();
  }
}

void LampLogic::reset() noexcept {
  failures_ = 0;
  last_failure_ = ErrorCode::kOk;
}

void LampLogic::report(State& state, runtime::ErrorList& errors, Time /*now*/) const noexcept {
  state.set_lit(output_.driven());
  if (!output_.is_open()) {
    errors.add("lamp output {} not available: {}", output_.config().signal, output_.error());
  } else if (failures_ > 0) {
    errors.add("lamp output {} failed to write {} time(s) since the last reset (last: {})",
               output_.config().signal, failures_, to_string(last_failure_));
  }
}

void LampLogic::enter_safe_state() noexcept {
  output_.write_if_open(false).ignore();
}

}  // namespace hubrt::signal_lamp
