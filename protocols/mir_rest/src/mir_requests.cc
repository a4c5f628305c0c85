// Request builders: fixed-size, formatted in place (fmt::format_to_n), no allocation.
#include <algorithm>

#include <fmt/format.h>

#include "hubrt/protocol/mir_rest.h"

namespace hubrt::protocol::mir {
namespace {

template <std::size_t N, class... Args>
void format_into(hal::FixedText<N>& text, fmt::format_string<Args...> spec, Args&&... args) noexcept {
  try {
    const auto result = fmt::format_to_n(text.data(), N, spec, std::forward<Args>(args)...);
    if (result.size > N) {
      text.clear();  // does not fit: an empty path or body, which submit() refuses
      return;
    }
    text.set_length(result.size);
  } catch (...) {
    text.clear();
  }
}

hal::HttpRequest request(hal::HttpMethod method, std::string_view path, MirCall call) noexcept {
  hal::HttpRequest r;
  r.method = method;
  r.path.assign(path);
  r.tag = static_cast<std::uint32_t>(call);
  return r;
}

}  // namespace

std::string_view to_string(MirCall call) noexcept {
  switch (call) {
    case MirCall::kNone:
      return "none";
    case MirCall::kGetStatus:
      return "GET /status";
    case MirCall::kSetState:
      return "PUT /status (state_id)";
    case MirCall::kClearError:
      return "PUT /status (clear_error)";
    case MirCall::kFindPosition:
      return "GET /positions";
    case MirCall::kPostPosition:
      return "POST /positions";
    case MirCall::kPostMission:
      return "POST /mission_queue";
    case MirCall::kGetMission:
      return "GET /mission_queue/{id}";
    case MirCall::kClearQueue:
      return "DELETE /mission_queue";
  }
  return "?";
}

bool valid_position_name(std::string_view name) noexcept {
  return !name.empty() && name.size() <= kMaxPositionName &&
         std::all_of(name.begin(), name.end(), [](char c) {
           return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                  c == '-' || c == '.' || c == ' ';
         });
}

bool valid_guid(std::string_view guid) noexcept {
  return !guid.empty() && guid.size() <= 40 && std::all_of(guid.begin(), guid.end(), [](char c) {
    return (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F') || (c >= '0' && c <= '9') || c == '-';
  });
}

hal::HttpRequest get_status() noexcept {
  return request(hal::HttpMethod::kGet, "/status", MirCall::kGetStatus);
}

hal::HttpRequest set_state(int state_id) noexcept {
  hal::HttpRequest r = request(hal::HttpMethod::kPut, "/status", MirCall::kSetState);
  format_into(r.body, R"({{"state_id": {}}})", state_id);
  return r;
}

hal::HttpRequest clear_error() noexcept {
  hal::HttpRequest r = request(hal::HttpMethod::kPut, "/status", MirCall::kClearError);
  r.body.assign(R"({"clear_error": true})");
  return r;
}

hal::HttpRequest find_position(std::string_view name) noexcept {
  hal::HttpRequest r = request(hal::HttpMethod::kGet, "/positions", MirCall::kFindPosition);
  if (!valid_position_name(name) || !r.key.assign(name)) r.path.clear();
  return r;
}

hal::HttpRequest post_position(std::string_view name, float x, float y, float yaw_deg,
                               std::string_view map_id) noexcept {
  hal::HttpRequest r = request(hal::HttpMethod::kPost, "/positions", MirCall::kPostPosition);
  if (!valid_position_name(name) || !valid_guid(map_id)) {
    r.path.clear();
    return r;
  }
  r.key.assign(name);
  // type_id 0: a plain robot position (PostPositions: map_id, name, orientation, pos_x, pos_y, type_id).
  format_into(
      r.body,
      R"({{"name": "{}", "pos_x": {:.3f}, "pos_y": {:.3f}, "orientation": {:.2f}, "type_id": 0, "map_id": "{}"}})",
      name, x, y, yaw_deg, map_id);
  if (r.body.empty()) r.path.clear();
  return r;
}

hal::HttpRequest post_mission(std::string_view mission_guid, std::string_view parameter,
                              std::string_view position_guid) noexcept {
  hal::HttpRequest r = request(hal::HttpMethod::kPost, "/mission_queue", MirCall::kPostMission);
  if (!valid_guid(mission_guid) || !valid_guid(position_guid) || !valid_position_name(parameter)) {
    r.path.clear();
    return r;
  }
  format_into(r.body, R"({{"mission_id": "{}", "parameters": [{{"id": "{}", "value": "{}"}}]}})",
              mission_guid, parameter, position_guid);
  if (r.body.empty()) r.path.clear();
  return r;
}

hal::HttpRequest get_mission(int mission_id) noexcept {
  hal::HttpRequest r = request(hal::HttpMethod::kGet, "", MirCall::kGetMission);
  format_into(r.path, "/mission_queue/{}", mission_id);
  return r;
}

hal::HttpRequest clear_queue() noexcept {
  return request(hal::HttpMethod::kDelete, "/mission_queue", MirCall::kClearQueue);
}

}  // namespace hubrt::protocol::mir
