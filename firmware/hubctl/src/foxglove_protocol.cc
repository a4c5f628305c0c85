#include "foxglove_protocol.h"

#include <limits>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "hubrt/base/utf8.h"

namespace hubrt::hubctl::foxglove {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;

// Server messages are built by us from names the domain announced: a topic or type name that is
// not UTF-8 is replaced rather than make dump() throw.
std::string dump(const ordered_json& value) {
  return value.dump(-1, ' ', false, ordered_json::error_handler_t::replace);
}

// A client's message that does not follow the spec: thrown inside the parser, caught at the top.
struct Malformed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void malformed(const std::string& message) {
  throw Malformed(message);
}

const json& field(const json& object, const char* name, const std::string& where) {
  const auto it = object.find(name);
  if (it == object.end()) malformed(fmt::format("{}: no \"{}\"", where, name));
  return *it;
}

std::uint32_t uint32_at(const json& object, const char* name, const std::string& where) {
  const json& value = field(object, name, where);
  if (!value.is_number_unsigned() || value.get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max())
    malformed(fmt::format("{}.{}: expected an unsigned 32-bit integer, got {}", where, name,
                          value.dump(-1, ' ', false, json::error_handler_t::replace).substr(0, 40)));
  return static_cast<std::uint32_t>(value.get<std::uint64_t>());
}

std::string string_at(const json& object, const char* name, const std::string& where) {
  const json& value = field(object, name, where);
  if (!value.is_string()) malformed(fmt::format("{}.{}: expected a string", where, name));
  std::string text = value.get<std::string>();
  if (text.size() > kMaxNameBytes)
    malformed(fmt::format("{}.{}: {} bytes, at most {}", where, name, text.size(), kMaxNameBytes));
  // nlohmann's lexer refuses invalid UTF-8 already; the project's validator is the one word on it.
  if (!is_valid_utf8(text)) malformed(fmt::format("{}.{}: not valid UTF-8", where, name));
  return text;
}

const json& array_at(const json& object, const char* name, const std::string& where) {
  const json& value = field(object, name, where);
  if (!value.is_array()) malformed(fmt::format("{}.{}: expected an array", where, name));
  if (value.size() > kMaxRequestEntries)
    malformed(fmt::format("{}.{}: {} entries, at most {} in one request", where, name, value.size(),
                          kMaxRequestEntries));
  return value;
}

std::vector<std::uint32_t> ids_at(const json& object, const char* name, const std::string& where) {
  const json& list = array_at(object, name, where);
  std::vector<std::uint32_t> ids;
  ids.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const json& value = list[i];
    if (!value.is_number_unsigned() || value.get<std::uint64_t>() > std::numeric_limits<std::uint32_t>::max())
      malformed(fmt::format("{}.{}[{}]: expected an unsigned 32-bit integer", where, name, i));
    ids.push_back(static_cast<std::uint32_t>(value.get<std::uint64_t>()));
  }
  return ids;
}

// The objects of the array `name` of `op`'s message, each read by `read(entry, where)`.
template <class Entry, class Read>
std::vector<Entry> objects_at(const json& message, const char* name, std::string_view op, Read read) {
  const json& list = array_at(message, name, std::string(op));
  std::vector<Entry> out;
  out.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = fmt::format("{}: {}[{}]", op, name, i);
    if (!list[i].is_object()) malformed(where + ": expected an object");
    out.push_back(read(list[i], where));
  }
  return out;
}

SubscribeRequest parse_subscribe(const json& message) {
  return {objects_at<SubscribeRequest::Entry>(
      message, "subscriptions", "subscribe", [](const json& entry, const std::string& where) {
        return SubscribeRequest::Entry{uint32_at(entry, "id", where), uint32_at(entry, "channelId", where)};
      })};
}

ClientAdvertiseRequest parse_advertise(const json& message) {
  return {objects_at<ClientChannel>(
      message, "channels", "advertise", [](const json& entry, const std::string& where) {
        return ClientChannel{uint32_at(entry, "id", where), string_at(entry, "topic", where),
                             string_at(entry, "encoding", where), string_at(entry, "schemaName", where)};
      })};
}

// The ops of capabilities this server does not declare ("Server Info": parameters,
// parametersSubscribe, services, connectionGraph, assets).
bool is_other_capability(std::string_view op) {
  for (std::string_view known :
       {"getParameters", "setParameters", "subscribeParameterUpdates", "unsubscribeParameterUpdates",
        "subscribeConnectionGraph", "unsubscribeConnectionGraph", "fetchAsset"})
    if (op == known) return true;
  return false;
}

ClientRequest parse_request(const json& message) {
  if (!message.is_object()) malformed("expected a JSON object with an \"op\"");
  const json& op = field(message, "op", "the message");
  if (!op.is_string()) malformed("\"op\": expected a string");
  const std::string name = op.get<std::string>();
  if (name == "subscribe") return parse_subscribe(message);
  if (name == "unsubscribe") return UnsubscribeRequest{ids_at(message, "subscriptionIds", "unsubscribe")};
  if (name == "advertise") return parse_advertise(message);
  if (name == "unadvertise") return ClientUnadvertiseRequest{ids_at(message, "channelIds", "unadvertise")};
  if (is_other_capability(name)) return UnsupportedRequest{name};
  malformed(fmt::format("unknown op \"{}\"", name.substr(0, kMaxNameBytes)));
}

void put_le(std::uint8_t* out, std::uint64_t value, int bytes) noexcept {
  for (int i = 0; i < bytes; ++i) out[i] = static_cast<std::uint8_t>(value >> (8 * i));
}

std::uint32_t get_le32(const std::uint8_t* in) noexcept {
  return static_cast<std::uint32_t>(in[0]) | static_cast<std::uint32_t>(in[1]) << 8 |
         static_cast<std::uint32_t>(in[2]) << 16 | static_cast<std::uint32_t>(in[3]) << 24;
}

}  // namespace

std::string server_info_json(const ServerInfo& info) {
  ordered_json message = {{"op", "serverInfo"}, {"name", info.name}};
  message["capabilities"] =
      info.client_publish ? ordered_json::array({"clientPublish"}) : ordered_json::array();
  // Only with client publishing ("Server Info": supportedEncodings).
  if (info.client_publish) message["supportedEncodings"] = ordered_json::array({"cdr"});
  message["metadata"] = ordered_json::object();
  for (const auto& [key, value] : info.metadata) message["metadata"][key] = value;
  message["sessionId"] = info.session_id;
  return dump(message);
}

std::string status_json(StatusLevel level, std::string_view message, std::string_view id) {
  ordered_json status = {{"op", "status"}, {"level", static_cast<int>(level)}, {"message", message}};
  if (!id.empty()) status["id"] = id;
  return dump(status);
}

std::string advertise_json(std::span<const Channel> channels) {
  ordered_json list = ordered_json::array();
  for (const Channel& channel : channels) {
    list.push_back({{"id", channel.id},
                    {"topic", channel.topic},
                    {"encoding", "cdr"},
                    {"schemaName", channel.schema_name},
                    {"schema", channel.schema},
                    {"schemaEncoding", "ros2msg"}});
  }
  return dump({{"op", "advertise"}, {"channels", std::move(list)}});
}

std::string unadvertise_json(std::span<const std::uint32_t> channel_ids) {
  return dump({{"op", "unadvertise"}, {"channelIds", channel_ids}});
}

std::array<std::uint8_t, kMessageDataHeaderBytes> message_data_header(
    std::uint32_t subscription_id, std::uint64_t receive_time_ns) noexcept {
  std::array<std::uint8_t, kMessageDataHeaderBytes> header{};
  header[0] = 0x01;
  put_le(&header[1], subscription_id, 4);
  put_le(&header[5], receive_time_ns, 8);
  return header;
}

Expected<ClientRequest> parse_client_text(std::string_view text) {
  if (text.size() > kMaxClientMessageBytes)
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("a message of {} bytes, at most {}", text.size(), kMaxClientMessageBytes));
  try {
    // The callback sees every value's depth as the parser reaches it: a deeply nested message is
    // refused before its tree is built (and before anything recurses over it).
    const auto depth_guard = [](int depth, json::parse_event_t event, json&) {
      if ((event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) &&
          depth >= kMaxJsonDepth)
        malformed(fmt::format("nested deeper than {} levels", kMaxJsonDepth));
      return true;
    };
    const json message = json::parse(text, depth_guard);
    return parse_request(message);
  } catch (const Malformed& e) {
    return make_error(ErrorCode::kInvalidArgument, e.what());
  } catch (const json::exception& e) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("not JSON: {}", e.what()));
  }
}

Expected<ClientMessageData> parse_client_binary(std::span<const std::uint8_t> frame) {
  if (frame.size() > kMaxClientMessageBytes)
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("a message of {} bytes, at most {}", frame.size(), kMaxClientMessageBytes));
  if (frame.empty()) return make_error(ErrorCode::kInvalidArgument, "an empty binary message (no opcode)");
  switch (frame[0]) {
    case 0x01:
      if (frame.size() < 5)
        return make_error(
            ErrorCode::kInvalidArgument,
            fmt::format("Client Message Data of {} bytes: shorter than its 5-byte header", frame.size()));
      return ClientMessageData{get_le32(&frame[1]), frame.subspan(5)};
    case 0x02:
      return make_error(
          ErrorCode::kInvalidArgument,
          "a Service Call Request: this server offers no services (no \"services\" capability)");
    default:
      return make_error(ErrorCode::kInvalidArgument, fmt::format("unknown binary opcode 0x{:02x}", frame[0]));
  }
}

}  // namespace hubrt::hubctl::foxglove
