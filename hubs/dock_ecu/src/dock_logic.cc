#include "dock_logic.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

namespace hubrt::dock_ecu {

Expected<std::vector<SlotConfig>> parse_slots(const config::NodeConfig& node) {
  const config::YamlMap& settings = node.settings;
  if (auto ok = settings.only_keys({"type", "slots"}); !ok) return std::move(ok).error();
  auto entries = settings.list_of_maps("slots");
  if (!entries) return std::move(entries).error();
  if (entries->empty() || entries->size() > DockLogic::kMaxSlots) {
    return settings.error_at(
        "slots", fmt::format("a dock has 1 to {} slots, got {}", DockLogic::kMaxSlots, entries->size()));
  }
  std::vector<SlotConfig> slots;
  std::set<std::string> names;
  for (const config::YamlMap& entry : *entries) {
    if (auto ok = entry.only_keys({"name", "signal"}); !ok) return std::move(ok).error();
    auto name = entry.string("name");
    if (!name) return std::move(name).error();
    if (!config::is_ros_name_token(*name)) {
      return entry.error_at("name", fmt::format("'{}' is not a usable slot name: use letters, digits and "
                                                "underscores, starting with a letter",
                                                *name));
    }
    if (!names.insert(*name).second)
      return entry.error_at("name", fmt::format("slot '{}' is listed twice", *name));
    auto signal = entry.string("signal");
    if (!signal) return std::move(signal).error();
    slots.push_back(SlotConfig{*name, *signal});
  }
  return slots;
}

void add_requirements(const std::vector<SlotConfig>& slots, hal::BoardRequirements& requirements) {
  for (const SlotConfig& slot : slots) requirements.inputs.push_back(slot.signal);
}

Expected<DockLogic> DockLogic::create(const std::vector<SlotConfig>& slots,
                                      std::vector<hal::SupervisedInput> sensors) {
  if (sensors.size() != slots.size()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("dock: {} slots but {} sensors", slots.size(), sensors.size()));
  }
  DockLogic logic;
  logic.slots_.reserve(slots.size());
  for (std::size_t i = 0; i < slots.size(); ++i) {
    logic.slots_.push_back(Slot{slots[i].name, std::move(sensors[i])});
  }
  return logic;
}

void DockLogic::read_inputs(Time now) noexcept {
  for (Slot& slot : slots_) {
    const Result<bool> level = slot.sensor.read(now);
    slot.readable = level.is_ok();
    if (level.is_ok()) {
      slot.occupied = level.value();
    } else {
      // An unreadable slot reports "not occupied": never claim a tool is home without seeing it.
      slot.occupied = false;
      if (slot.sensor.is_open() || level.status().code() != ErrorCode::kUnavailable) {
        ++slot.failures;
        slot.last_failure = level.status().code();
      }
    }
  }
}

runtime::NodeCondition DockLogic::condition() const noexcept {
  const auto failed = [](const Slot& slot) { return slot.failures > 0; };
  const auto missing = [](const Slot& slot) { return !slot.sensor.is_open(); };
  if (std::any_of(slots_.begin(), slots_.end(), failed)) return runtime::NodeCondition::kFault;
  if (std::any_of(slots_.begin(), slots_.end(), missing)) return runtime::NodeCondition::kDevicesMissing;
  return runtime::NodeCondition::kOk;
}

void DockLogic::reset() noexcept {
  for (Slot& slot : slots_) {
    slot.failures = 0;
    slot.last_failure = ErrorCode::kOk;
  }
}

void DockLogic::report(State& state, runtime::ErrorList& errors, Time /*now*/) noexcept {
  // parse_slots() allows at most kMaxSlots, the sequence's bound, so every slot fits.
  const auto reported = state.slots();
  reported.resize(slots_.size());
  for (std::size_t i = 0; i < slots_.size(); ++i) {
    const Slot& slot = slots_[i];
    reported[i].set_name(slot.name);
    reported[i].set_occupied(slot.occupied);
    if (!slot.sensor.is_open()) {
      errors.add("slot '{}': sensor {} not available: {}", slot.name, slot.sensor.config().signal,
                 slot.sensor.error());
    } else if (slot.failures > 0) {
      errors.add("slot '{}': sensor {} failed to read {} time(s) since the last reset (last: {})", slot.name,
                 slot.sensor.config().signal, slot.failures, to_string(slot.last_failure));
    }
  }
}

}  // namespace hubrt::dock_ecu
