// The answers' decoder: runs on the HTTP worker thread (it allocates while parsing), never throws.
// Malformed JSON, a missing field or one of the wrong type is a problem named in the reply.
#include <cmath>
#include <cstdint>
#include <limits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hubrt/protocol/mir_rest.h"

namespace hubrt::protocol::mir {
namespace {

using nlohmann::json;

bool has_number(const json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_number();
}
bool has_string(const json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_string();
}

// A JSON number may be any size: 1e300 as an int, or as a float, is undefined behaviour in a plain
// cast (nlohmann's get<int> is one; the fuzzer found it). These take a number only when the field's
// type holds it: an integer (or an integral float) in range, a finite float within float's range.
bool fits(const json& number, int& out) {
  if (number.is_number_integer()) {  // int64 or uint64: compare before narrowing
    if (number.is_number_unsigned()) {
      const auto value = number.get<std::uint64_t>();
      if (value > static_cast<std::uint64_t>(std::numeric_limits<int>::max())) return false;
      out = static_cast<int>(value);
      return true;
    }
    const auto value = number.get<std::int64_t>();
    if (value < std::numeric_limits<int>::min() || value > std::numeric_limits<int>::max()) return false;
    out = static_cast<int>(value);
    return true;
  }
  const double value = number.get<double>();
  if (!(value >= std::numeric_limits<int>::min() && value <= std::numeric_limits<int>::max()) ||
      value != std::trunc(value)) {
    return false;  // NaN fails the range test too
  }
  out = static_cast<int>(value);
  return true;
}
bool fits(const json& number, float& out) {
  const double value = number.get<double>();  // exact for floats, nearest for 64-bit integers
  if (!std::isfinite(value) || std::fabs(value) > std::numeric_limits<float>::max()) return false;
  out = static_cast<float>(value);
  return true;
}

// The field as T, or why not ("no number 'x'", "'x' is out of range: 1e+300").
template <class T>
bool read_number(const json& object, const char* key, T& out, std::string& why) {
  if (!has_number(object, key)) return why = fmt::format("no number '{}'", key), false;
  if (!fits(object[key], out))
    return why = fmt::format("'{}' is out of range: {}", key, object[key].dump()), false;
  return true;
}

template <std::size_t N>
void copy_string(hal::FixedText<N>& out, const json& value) {
  out.assign_cut(value.get_ref<const std::string&>());
}

void fail(MirReply& reply, std::string_view why) {
  reply.ok = false;
  reply.problem.assign_cut(why);
}

std::string_view http_reason(int status) {
  switch (status) {
    case 400:
      return "bad request";
    case 401:
      return "unauthorized: check the board's authorization";
    case 403:
      return "forbidden";
    case 404:
      return "not found";
    case 409:
      return "conflict";
    case 500:
      return "internal server error";
    case 503:
      return "service unavailable";
    default:
      return "unexpected status";
  }
}

// GET/PUT /status. Only the fields the hub uses must be there (RobotStatus of MiR REST API v2.0.0).
bool read_status(const json& body, MirStatus& out, std::string& why) {
  if (!read_number(body, "state_id", out.state_id, why)) return false;
  if (has_string(body, "state_text")) copy_string(out.state_text, body["state_text"]);
  if (!body.contains("position") || !body["position"].is_object()) return why = "no object 'position'", false;
  const json& position = body["position"];
  if (!read_number(position, "x", out.x, why) || !read_number(position, "y", out.y, why) ||
      !read_number(position, "orientation", out.yaw_deg, why)) {
    return why = fmt::format("'position': {}", why), false;
  }
  if (!read_number(body, "battery_percentage", out.battery_percent, why)) return false;
  out.mission_queue_id = 0;  // absent or null: no mission queued
  if (has_number(body, "mission_queue_id") &&
      !read_number(body, "mission_queue_id", out.mission_queue_id, why)) {
    return false;
  }
  if (has_string(body, "map_id")) copy_string(out.map_id, body["map_id"]);
  if (has_string(body, "mission_text")) copy_string(out.mission_text, body["mission_text"]);
  out.error_count = 0;
  if (body.contains("errors") && body["errors"].is_array()) {
    const json& errors = body["errors"];
    out.error_count = static_cast<int>(errors.size());
    if (!errors.empty()) {
      const json& first = errors.front();
      // The code is only shown: any number is shown as the platform sent it.
      const std::string code = has_number(first, "code") ? first["code"].dump() : "?";
      const std::string text =
          has_string(first, "description") ? first["description"].get<std::string>() : first.dump();
      out.first_error.assign_cut(fmt::format("{}: {}", code, text));
    }
  }
  return true;
}

bool read_mission(const json& body, MirReply& reply, std::string& why) {
  if (!read_number(body, "id", reply.mission_id, why)) return false;
  if (!has_string(body, "state")) return why = "no string 'state'", false;
  copy_string(reply.mission_state, body["state"]);
  return true;
}

bool read_answer(MirCall call, std::string_view key, const json& body, MirReply& reply, std::string& why) {
  switch (call) {
    case MirCall::kGetStatus:
    case MirCall::kSetState:
    case MirCall::kClearError:
      return read_status(body, reply.status, why);
    case MirCall::kFindPosition: {
      if (!body.is_array()) return why = "not a list of positions", false;
      for (const json& position : body) {
        if (has_string(position, "name") && position["name"].get_ref<const std::string&>() == key) {
          if (!has_string(position, "guid")) return why = "the position has no string 'guid'", false;
          copy_string(reply.guid, position["guid"]);
          return true;
        }
      }
      return why = fmt::format("the platform has no position named '{}'", key), false;
    }
    case MirCall::kPostPosition:
      if (!has_string(body, "guid")) return why = "no string 'guid'", false;
      copy_string(reply.guid, body["guid"]);
      return true;
    case MirCall::kPostMission:
    case MirCall::kGetMission:
      return read_mission(body, reply, why);
    case MirCall::kClearQueue:
    case MirCall::kNone:
      return true;
  }
  return true;
}

}  // namespace

void decode_reply(const hal::HttpRequest& request, const hal::HttpResponse& response,
                  MirReply& reply) noexcept {
  try {
    reply.call = static_cast<MirCall>(request.tag);
    reply.ok = false;
    if (response.status < 200 || response.status > 299) {
      fail(reply, fmt::format("{}: HTTP {} ({})", to_string(reply.call), response.status,
                              http_reason(response.status)));
      return;
    }
    if (reply.call == MirCall::kClearQueue) {  // 204, no body
      reply.ok = true;
      return;
    }
    // allow_exceptions = false: a parse error gives a discarded value instead of throwing.
    const json body = json::parse(response.body, nullptr, /*allow_exceptions=*/false);
    if (body.is_discarded()) {
      fail(reply, fmt::format("{}: malformed JSON in the answer ({} bytes)", to_string(reply.call),
                              response.body.size()));
      return;
    }
    std::string why;
    if (!read_answer(reply.call, request.key.view(), body, reply, why)) {
      fail(reply, fmt::format("{}: {}", to_string(reply.call), why));
      return;
    }
    reply.ok = true;
  } catch (const std::exception& e) {  // a number out of range, bad_alloc: not understood
    reply.ok = false;
    reply.problem.assign_cut(e.what());
  }
}

}  // namespace hubrt::protocol::mir
