#include "hubrt/sim/station/station_model.h"

#include <algorithm>

#include <fmt/format.h>

namespace hubrt::sim::station {

std::string_view to_string(ToolPlace place) noexcept {
  switch (place) {
    case ToolPlace::kDock:
      return "dock";
    case ToolPlace::kRobot:
      return "robot";
    case ToolPlace::kDropped:
      return "dropped";
  }
  return "?";
}

std::string_view to_string(ArmReading reading) noexcept {
  switch (reading) {
    case ArmReading::kHome:
      return "home";
    case ArmReading::kPreHome:
      return "pre_home";
    case ArmReading::kOperating:
      return "operating";
    case ArmReading::kOutOfRange:
      return "out_of_range";
  }
  return "?";
}

std::string_view to_string(KitPlace place) noexcept {
  switch (place) {
    case KitPlace::kAtStation:
      return "at_station";
    case KitPlace::kAway:
      return "away";
    case KitPlace::kUnknown:
      return "unknown";
  }
  return "?";
}

StationModel::StationModel(StationConfig config) : config_(std::move(config)) {
  // With a platform, nobody has said yet that it brought the kit.
  if (config_.mobile_platform) kit_ = KitPlace::kUnknown;
  start_over();
}

std::string_view StationModel::kit_place() const noexcept {
  return config_.mobile_platform ? std::string_view(config_.mobile_platform->kit) : std::string_view();
}

std::string StationModel::fresh_frame_place() const {
  if (!kit_here() && config_.frame_start == kit_place()) return std::string(kAway);
  return config_.frame_start;
}

void StationModel::start_over() {
  tools_.assign(config_.tools.size(), ToolPlace::kDock);
  attached_.reset();
  for (std::size_t i = 0; i < config_.tools.size(); ++i) {
    if (config_.tools[i].starts_on_robot) {
      tools_[i] = ToolPlace::kRobot;
      attached_ = i;
    }
  }
  robot_at_ = config_.robot_start;
  moving_to_.clear();
  frame_at_ = fresh_frame_place();  // the kit stays where the platform is
  faults_.clear();
}

std::optional<std::size_t> StationModel::tool_index(std::string_view name) const noexcept {
  for (std::size_t i = 0; i < config_.tools.size(); ++i) {
    if (config_.tools[i].name == name) return i;
  }
  return std::nullopt;
}

const ToolConfig* StationModel::on_robot() const noexcept {
  return attached_ ? &config_.tools[*attached_] : nullptr;
}

void StationModel::advance(Time now) {
  if (!moving_to_.empty() && now >= arrives_at_) arrive();
  if (config_.mobile_platform && platform_heard_ &&
      now - *platform_heard_ > config_.mobile_platform->timeout) {
    platform_heard_.reset();
    kit_becomes(KitPlace::kUnknown);
  }
}

void StationModel::observe_platform(const PlatformReport& report, Time now) {
  if (!config_.mobile_platform) return;
  advance(now);
  platform_heard_ = now;
  const bool at_station = !report.moving && report.pose == config_.mobile_platform->at_station;
  kit_becomes(at_station ? KitPlace::kAtStation : KitPlace::kAway);
}

void StationModel::kit_becomes(KitPlace place) {
  const bool was_here = kit_here();
  kit_ = place;
  const std::string_view kit = kit_place();
  if (!was_here && kit_here()) {
    // A new kit with a new ladder frame on it (as restock: the frame shown is the new one),
    // unless the robot holds the frame.
    if (frame_at_ != kGripper) frame_at_ = kit;
    return;
  }
  if (!was_here || kit_here()) return;
  if (frame_at_ == kit) frame_at_ = kAway;  // it leaves with the kit
  if (moving_to_.empty() && robot_at_ == kit) {
    faults_.emplace_back("collision: the mobile platform left while the robot was at the kit");
  }
}

void StationModel::arrive() {
  robot_at_ = std::move(moving_to_);
  moving_to_.clear();
  const auto slot_of = tool_index(robot_at_);
  if (attached_ && slot_of && *slot_of != *attached_ && tools_[*slot_of] == ToolPlace::kDock) {
    faults_.push_back(fmt::format("collision: the robot carrying the {} went into the dock slot of the {}",
                                  config_.tools[*attached_].name, config_.tools[*slot_of].name));
  }
}

Expected<void> StationModel::command(std::string_view action, std::string_view location, Time now) {
  advance(now);
  if (action == "move_robot") {
    if (!config_.is_location(location)) {
      std::string known;
      for (const auto& place : config_.places) known += fmt::format("{}{}", known.empty() ? "" : ", ", place);
      for (const auto& tool : config_.tools) known += fmt::format(", {}", tool.name);
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("unknown location '{}' (the robot can go to: {})", location, known));
    }
    if (!kit_here() && location == kit_place()) {
      return make_error(ErrorCode::kInvalidArgument,
                        "no kit at the station: the mobile platform is not there");
    }
    if ((moving_to_.empty() && robot_at_ == location) || moving_to_ == location) return {};
    robot_at_.clear();
    moving_to_ = location;
    arrives_at_ = now + config_.robot_travel;
    advance(now);  // a travel time of 0 arrives at once
    return {};
  }
  if (action == "restock") {
    if (frame_at_ == kGripper) {
      return make_error(ErrorCode::kInvalidArgument,
                        "cannot restock: the robot holds the ladder frame (put it down first)");
    }
    frame_at_ = fresh_frame_place();
    return {};
  }
  if (action == "reset") {
    start_over();
    return {};
  }
  return make_error(ErrorCode::kInvalidArgument,
                    fmt::format("unknown action '{}' (expected one of: move_robot, restock, reset)", action));
}

void StationModel::observe_valve(std::string_view valve, bool energised, Time now) {
  advance(now);
  if (valve == config_.lock_valve) {
    const bool changed = lock_open_.has_value() && *lock_open_ != energised;
    lock_open_ = energised;
    if (changed && energised) lock_opened();
    if (changed && !energised) lock_closed();
  } else if (valve == config_.gripper_valve) {
    const bool changed = gripper_closed_.has_value() && *gripper_closed_ != energised;
    gripper_closed_ = energised;
    if (changed) gripper_changed(energised);
  }
}

void StationModel::observe_lift(std::string_view device, double position_mm) {
  if (device == config_.lift_device) lift_mm_ = position_mm;
}

void StationModel::lock_closed() {
  if (attached_ || !moving_to_.empty()) return;
  const auto slot = tool_index(robot_at_);
  if (!slot || tools_[*slot] != ToolPlace::kDock) return;  // nothing to lock onto
  tools_[*slot] = ToolPlace::kRobot;
  attached_ = slot;
}

void StationModel::lock_opened() {
  if (!attached_) return;
  const std::size_t tool = *attached_;
  attached_.reset();
  if (moving_to_.empty() && robot_at_ == config_.tools[tool].name) {
    tools_[tool] = ToolPlace::kDock;
    release_tool(tool, "");
    return;
  }
  tools_[tool] = ToolPlace::kDropped;
  faults_.push_back(fmt::format("the {} dropped {}: the tool changer opened away from its dock slot",
                                config_.tools[tool].name,
                                moving_to_.empty() ? fmt::format("at the {}", robot_at_)
                                                   : fmt::format("on the way to the {}", moving_to_)));
  release_tool(tool, "with the tool");
}

// What the tool held goes with it.
void StationModel::release_tool(std::size_t tool, std::string_view why) {
  if (config_.tools[tool].name != config_.frame_tool || frame_at_ != kGripper) return;
  frame_at_ = kDropped;
  faults_.push_back(fmt::format("the ladder frame dropped {}: its tool left the robot while gripping it",
                                why.empty() ? "at the dock" : why));
}

void StationModel::gripper_changed(bool closed) {
  if (!attached_ || config_.tools[*attached_].name != config_.frame_tool) return;
  const bool standing = moving_to_.empty();
  if (closed) {
    if (standing && frame_at_ == robot_at_) frame_at_ = kGripper;
    return;
  }
  if (frame_at_ != kGripper) return;
  const auto& rests = config_.frame_rests;
  const bool can_lie = robot_at_ != kit_place() || kit_here();  // no kit, nothing to lie on
  if (standing && can_lie && std::find(rests.begin(), rests.end(), robot_at_) != rests.end()) {
    frame_at_ = robot_at_;
    return;
  }
  frame_at_ = kDropped;
  faults_.push_back(fmt::format(
      "the ladder frame dropped {}: the gripper opened where it cannot lie",
      standing ? fmt::format("at the {}", robot_at_) : fmt::format("on the way to the {}", moving_to_)));
}

ArmReading StationModel::arm_in_holder() const noexcept {
  if (!lift_mm_) return ArmReading::kOutOfRange;  // nobody knows where it is: nothing may run it
  if (*lift_mm_ >= config_.home_above_mm) return ArmReading::kHome;
  if (*lift_mm_ >= config_.pre_home_above_mm) return ArmReading::kPreHome;
  return ArmReading::kOperating;
}

ArmReading StationModel::arm() const noexcept {
  const auto tool = tool_index(config_.arm_tool);
  if (!tool) return ArmReading::kOutOfRange;
  switch (tools_[*tool]) {
    case ToolPlace::kDock:
      return arm_in_holder();
    case ToolPlace::kRobot:
      if (!moving_to_.empty()) return ArmReading::kOutOfRange;
      if (robot_at_ == config_.arm_tool) return arm_in_holder();
      return robot_at_ == config_.operating_at ? ArmReading::kOperating : ArmReading::kOutOfRange;
    case ToolPlace::kDropped:
      return ArmReading::kOutOfRange;
  }
  return ArmReading::kOutOfRange;
}

std::vector<WorldInput> StationModel::inputs() const {
  std::vector<WorldInput> out;
  out.reserve(config_.tools.size() * 2 + 3);
  const bool standing = moving_to_.empty();
  for (std::size_t i = 0; i < config_.tools.size(); ++i) {
    const ToolConfig& tool = config_.tools[i];
    const bool on_changer = attached_ == i;
    out.push_back({HubRole::kRsp, tool.tool_id_signal, on_changer});
    const bool seated = tools_[i] == ToolPlace::kDock || (on_changer && standing && robot_at_ == tool.name);
    out.push_back({HubRole::kDock, tool.dock_signal, seated});
  }
  const ArmReading reading = arm();
  out.push_back({HubRole::kTool, config_.arm_home_signal, reading == ArmReading::kHome});
  out.push_back({HubRole::kTool, config_.arm_pre_home_signal, reading == ArmReading::kPreHome});
  out.push_back({HubRole::kTool, config_.arm_out_of_range_signal, reading == ArmReading::kOutOfRange});
  return out;
}

}  // namespace hubrt::sim::station
