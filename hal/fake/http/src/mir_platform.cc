#include "hubrt/hal/fake/mir_platform.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace hubrt::hal::fake {
namespace {

using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;

std::string_view state_text(int state_id) {
  switch (state_id) {
    case 3:
      return "Ready";
    case 4:
      return "Pause";
    case 5:
      return "Executing";
    case 12:
      return "Error";
    default:
      return "Unknown";
  }
}

MirAnswer error_answer(int status, std::string_view human) {
  return MirAnswer{status, json{{"error_code", std::to_string(status)}, {"error_human", human}}.dump()};
}

// Shortest signed angle from a to b, degrees.
double angle_to(double a, double b) {
  double d = std::fmod(b - a + 540.0, 360.0) - 180.0;
  return d;
}

}  // namespace

MirPlatform::MirPlatform(MirPlatformConfig config, Time now)
    : config_(std::move(config)),
      last_(now),
      x_(config_.start_x),
      y_(config_.start_y),
      yaw_deg_(config_.start_yaw_deg),
      battery_(config_.battery_start_percent) {}

std::string MirPlatform::add_position(std::string_view name, double x, double y, double yaw_deg) {
  const std::lock_guard lock(mutex_);
  Position p{fmt::format("00000000-0000-4000-8000-{:012x}", next_guid_++), std::string(name), x, y, yaw_deg};
  positions_.push_back(p);
  return p.guid;
}

void MirPlatform::advance(Time now) {
  const std::lock_guard lock(mutex_);
  advance_locked(now);
}

void MirPlatform::advance_locked(Time now) {
  const double dt = now > last_ ? to_seconds(now - last_) : 0.0;
  last_ = std::max(last_, now);
  bool moved = false;
  if (state_id_ == 3) start_next_mission();
  if (state_id_ == 5) {
    Mission* mission = executing();
    const Position* goal = mission != nullptr ? position(mission->position_guid) : nullptr;
    if (goal == nullptr) {
      if (mission != nullptr) mission->state = "Aborted";
      state_id_ = 3;
    } else {
      const double dx = goal->x - x_;
      const double dy = goal->y - y_;
      const double distance = std::hypot(dx, dy);
      const double step = config_.speed_m_s * dt;
      if (distance <= step) {
        x_ = goal->x;
        y_ = goal->y;
        const double turn = angle_to(yaw_deg_, goal->yaw_deg);
        const double max_turn = config_.turn_deg_s * dt;
        yaw_deg_ += std::clamp(turn, -max_turn, max_turn);
        if (std::abs(angle_to(yaw_deg_, goal->yaw_deg)) < 1e-6) {
          mission->state = "Done";
          state_id_ = 3;
          start_next_mission();
        }
      } else {
        x_ += dx / distance * step;
        y_ += dy / distance * step;
        yaw_deg_ = std::atan2(dy, dx) * 180.0 / kPi;
      }
      moved = dt > 0;
    }
  }
  battery_ =
      std::max(0.0, battery_ - dt * (moved ? config_.drain_moving_percent_s : config_.drain_idle_percent_s));
  if (battery_ <= 0.0 && state_id_ != 12) {
    error_code_ = 10001;
    error_text_ = "Battery empty";
    state_id_ = 12;
  }
}

void MirPlatform::start_next_mission() {
  for (Mission& mission : queue_) {
    if (mission.state == "Executing") {
      state_id_ = 5;
      return;
    }
    if (mission.state == "Pending") {
      mission.state = "Executing";
      state_id_ = 5;
      return;
    }
  }
}

MirPlatform::Mission* MirPlatform::executing() {
  for (Mission& mission : queue_) {
    if (mission.state == "Executing") return &mission;
  }
  return nullptr;
}

const MirPlatform::Position* MirPlatform::position(std::string_view guid) const {
  for (const Position& p : positions_) {
    if (p.guid == guid) return &p;
  }
  return nullptr;
}

void MirPlatform::inject_error(int code, std::string_view description, Time now) {
  const std::lock_guard lock(mutex_);
  advance_locked(now);
  error_code_ = code;
  error_text_ = std::string(description);
  state_id_ = 12;
}

void MirPlatform::set_battery_percent(double percent) {
  const std::lock_guard lock(mutex_);
  battery_ = percent;
}

MirPlatform::Snapshot MirPlatform::snapshot() const {
  const std::lock_guard lock(mutex_);
  Snapshot s;
  s.state_id = state_id_;
  s.x = x_;
  s.y = y_;
  s.yaw_deg = yaw_deg_;
  s.battery_percent = battery_;
  s.missions_pending = static_cast<int>(std::count_if(queue_.begin(), queue_.end(), [](const Mission& m) {
    return m.state == "Pending" || m.state == "Executing";
  }));
  s.pause_requests = pause_requests_;
  return s;
}

MirAnswer MirPlatform::handle(std::string_view method, std::string_view path, std::string_view body,
                              std::string_view authorization, Time now) {
  const std::lock_guard lock(mutex_);
  if (!config_.authorization.empty() && authorization != config_.authorization) {
    return error_answer(401, "Unauthorized");
  }
  advance_locked(now);
  if (path == "/status" && method == "GET") return status_json();
  if (path == "/status" && method == "PUT") return put_status(body, now);
  if (path == "/positions" && method == "GET") {
    json list = json::array();
    for (const Position& p : positions_) {
      list.push_back({{"guid", p.guid},
                      {"name", p.name},
                      {"type_id", 0},
                      {"map_id", config_.map_id},
                      {"url", "/v2.0.0/positions/" + p.guid}});
    }
    return {200, list.dump()};
  }
  if (path == "/positions" && method == "POST") return post_position(body);
  if (path == "/mission_queue" && method == "POST") return post_mission(body);
  if (path == "/mission_queue" && method == "DELETE") return clear_queue();
  if (path.starts_with("/mission_queue/") && method == "GET") {
    const std::string_view id_text = path.substr(15);
    int id = 0;
    for (char c : id_text) {
      if (c < '0' || c > '9' || id > 1'000'000) return error_answer(404, "Not found");
      id = id * 10 + (c - '0');
    }
    return mission_json(id);
  }
  return error_answer(404, fmt::format("No such endpoint: {} {}", method, path));
}

MirAnswer MirPlatform::status_json() const {
  json errors = json::array();
  if (state_id_ == 12)
    errors.push_back({{"code", error_code_}, {"description", error_text_}, {"module", "sim"}});
  int mission_queue_id = 0;
  std::string mission_text = "Waiting for new missions...";
  for (const Mission& m : queue_) {
    if (m.state == "Executing" || m.state == "Pending") {
      mission_queue_id = m.id;
      const Position* goal = position(m.position_guid);
      mission_text = fmt::format("Moving to '{}'", goal != nullptr ? goal->name : "?");
      break;
    }
  }
  json status = {{"robot_name", config_.robot_name},
                 {"state_id", state_id_},
                 {"state_text", state_text(state_id_)},
                 {"position", {{"x", x_}, {"y", y_}, {"orientation", yaw_deg_}}},
                 {"battery_percentage", battery_},
                 {"mission_queue_id", mission_queue_id},
                 {"mission_text", mission_text},
                 {"map_id", config_.map_id},
                 {"errors", errors}};
  return {200, status.dump()};
}

MirAnswer MirPlatform::put_status(std::string_view body, Time now) {
  const json request = json::parse(body, nullptr, false);
  if (request.is_discarded() || !request.is_object()) return error_answer(400, "Malformed body");
  if (request.contains("clear_error")) {
    if (!request["clear_error"].is_boolean()) return error_answer(400, "clear_error must be a boolean");
    if (request["clear_error"].get<bool>() && state_id_ == 12) {
      error_code_ = 0;
      error_text_.clear();
      state_id_ = 4;  // cleared: paused until told to continue
      if (battery_ <= 0.0) battery_ = 1.0;
    }
    return status_json();
  }
  if (!request.contains("state_id") || !request["state_id"].is_number_integer()) {
    return error_answer(400, "Expected state_id or clear_error");
  }
  // Compared as sent: narrowed to int first, 4294967299 would pass for 3.
  const json& wanted = request["state_id"];
  if (wanted != 3 && wanted != 4) return error_answer(400, "state_id must be 3 (ready) or 4 (pause)");
  if (state_id_ == 12) return error_answer(409, "The robot is in error: clear the error first");
  if (wanted == 4) {
    ++pause_requests_;
    state_id_ = 4;
  } else if (state_id_ == 4) {
    state_id_ = 3;
    advance_locked(now);  // a mission in the queue starts (again) at once
  }
  return status_json();
}

MirAnswer MirPlatform::post_position(std::string_view body) {
  const json request = json::parse(body, nullptr, false);
  if (request.is_discarded() || !request.is_object()) return error_answer(400, "Malformed body");
  for (const char* key : {"pos_x", "pos_y", "orientation"}) {
    if (!request.contains(key) || !request[key].is_number()) {
      return error_answer(400, fmt::format("Missing number '{}'", key));
    }
  }
  if (!request.contains("name") || !request["name"].is_string() ||
      request["name"].get<std::string>().empty() || request["name"].get<std::string>().size() > 40) {
    return error_answer(400, "name: 1 to 40 characters");
  }
  if (!request.contains("map_id") || request["map_id"] != config_.map_id)
    return error_answer(400, "Unknown map_id");
  if (!request.contains("type_id") || !request["type_id"].is_number_integer()) {
    return error_answer(400, "Missing integer 'type_id'");
  }
  const std::string name = request["name"].get<std::string>();
  Position* existing = nullptr;
  for (Position& p : positions_) {
    if (p.name == name) existing = &p;
  }
  if (existing == nullptr) {
    positions_.push_back(
        Position{fmt::format("00000000-0000-4000-8000-{:012x}", next_guid_++), name, 0, 0, 0});
    existing = &positions_.back();
  }
  // The simulator keeps one position per name: saving a name again moves it (its guid stays).
  existing->x = request["pos_x"].get<double>();
  existing->y = request["pos_y"].get<double>();
  existing->yaw_deg = request["orientation"].get<double>();
  return {201, json{{"guid", existing->guid}, {"name", existing->name}, {"map_id", config_.map_id}}.dump()};
}

MirAnswer MirPlatform::post_mission(std::string_view body) {
  const json request = json::parse(body, nullptr, false);
  if (request.is_discarded() || !request.is_object()) return error_answer(400, "Malformed body");
  if (!request.contains("mission_id") || request["mission_id"] != config_.move_mission_guid) {
    return error_answer(400, "Unknown mission_id");
  }
  std::string position_guid;
  if (request.contains("parameters") && request["parameters"].is_array()) {
    for (const json& parameter : request["parameters"]) {
      if (parameter.is_object() && parameter.contains("id") &&
          parameter["id"] == config_.position_parameter && parameter.contains("value") &&
          parameter["value"].is_string()) {
        position_guid = parameter["value"].get<std::string>();
      }
    }
  }
  if (position(position_guid) == nullptr) {
    return error_answer(400,
                        fmt::format("parameter '{}' is not a known position", config_.position_parameter));
  }
  queue_.push_back(Mission{next_mission_id_++, position_guid, "Pending"});
  const Mission& mission = queue_.back();
  json answer = {{"id", mission.id}, {"state", mission.state}, {"mission_id", config_.move_mission_guid}};
  if (state_id_ == 3) start_next_mission();
  return {201, answer.dump()};
}

MirAnswer MirPlatform::mission_json(int id) const {
  for (const Mission& m : queue_) {
    if (m.id == id) {
      return {200, json{{"id", m.id}, {"state", m.state}, {"mission_id", config_.move_mission_guid}}.dump()};
    }
  }
  return error_answer(404, "Not found");
}

MirAnswer MirPlatform::clear_queue() {
  for (Mission& m : queue_) {
    if (m.state == "Pending" || m.state == "Executing") m.state = "Aborted";
  }
  if (state_id_ == 5) state_id_ = 3;
  return {204, ""};
}

}  // namespace hubrt::hal::fake
