// The Foxglove WebSocket protocol v1 (subprotocol "foxglove.websocket.v1") as `hubctl foxglove`
// speaks it: the messages the server sends and the client messages it accepts, each with the
// bounds a client's input must stay within. No I/O, no DDS: the WebSocket side
// (foxglove_server.cc) and the sessions (foxglove_session.h) use it.
//
// The specification: foxglove/ws-protocol, docs/spec.md, in its last revision (commit 305d217,
// 2025-07-14; the repository now points at foxglove-sdk, whose servers speak the same v1). Section
// names below are the spec's. Text messages are JSON objects with an "op"; binary messages start
// with a one-byte opcode; integers in binary messages are little-endian ("Binary messages").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "hubrt/base/status.h"

namespace hubrt::hubctl::foxglove {

inline constexpr std::string_view kSubprotocol = "foxglove.websocket.v1";

// The most a client may send in one WebSocket message (text or binary): its JSON requests and the
// commands it publishes are all far smaller. The server refuses a longer message before reading it
// (Beast's read_message_max) and the parsers check again.
inline constexpr std::size_t kMaxClientMessageBytes = 64 * 1024;
// Entries in one subscribe/unsubscribe/advertise/unadvertise request.
inline constexpr std::size_t kMaxRequestEntries = 256;
// A topic, schemaName or encoding a client names.
inline constexpr std::size_t kMaxNameBytes = 256;
// How deep a client's JSON may nest: the requests need 3 levels (object, array, object).
inline constexpr int kMaxJsonDepth = 8;

// ---- Sent by the server ----

// "Server Info": sent first on every connection.
struct ServerInfo {
  std::string name;
  bool client_publish = false;  // the "clientPublish" capability, with supportedEncodings ["cdr"]
  std::map<std::string, std::string> metadata;
  std::string session_id;
};
std::string server_info_json(const ServerInfo& info);

// "Status": level 0 info, 1 warning, 2 error; a status with an id replaces an earlier one of the
// same id in the client. Text that is not valid UTF-8 is replaced, never sent as is.
enum class StatusLevel : int { kInfo = 0, kWarning = 1, kError = 2 };
std::string status_json(StatusLevel level, std::string_view message, std::string_view id = {});

// A channel the server offers: one DDS topic, its samples in CDR as on the wire, its schema the
// ros2msg text of its type (the same encodings as the channels of a ros2-profile MCAP file).
struct Channel {
  std::uint32_t id = 0;
  std::string topic;        // the ROS name, "/dock_ecu/dock/state"
  std::string schema_name;  // "hub_msgs/msg/DockState"
  std::string schema;       // ros2msg text (hubrt/msgs/definitions.h)
};
// "Advertise" (encoding "cdr", schemaEncoding "ros2msg") and "Unadvertise".
std::string advertise_json(std::span<const Channel> channels);
std::string unadvertise_json(std::span<const std::uint32_t> channel_ids);

// "Message Data": opcode 0x01, subscription id (uint32), receive timestamp in ns (uint64), then the
// payload — here the CDR bytes as taken from DDS (encapsulation header included). The header alone,
// so that one payload can be sent to many clients without a copy each.
inline constexpr std::size_t kMessageDataHeaderBytes = 13;
std::array<std::uint8_t, kMessageDataHeaderBytes> message_data_header(std::uint32_t subscription_id,
                                                                      std::uint64_t receive_time_ns) noexcept;

// ---- Sent by clients ----

// "Subscribe": ids chosen by the client, each for one advertised channel.
struct SubscribeRequest {
  struct Entry {
    std::uint32_t id = 0;
    std::uint32_t channel_id = 0;
  };
  std::vector<Entry> subscriptions;
};
// "Unsubscribe".
struct UnsubscribeRequest {
  std::vector<std::uint32_t> subscription_ids;
};
// "Client Advertise": a channel the client will publish on. Its optional schema is not read:
// a published message must be of a type this hubctl has registered.
struct ClientChannel {
  std::uint32_t id = 0;
  std::string topic;
  std::string encoding;
  std::string schema_name;
};
struct ClientAdvertiseRequest {
  std::vector<ClientChannel> channels;
};
// "Client Unadvertise".
struct ClientUnadvertiseRequest {
  std::vector<std::uint32_t> channel_ids;
};
// A request of a capability this server does not declare (parameters, services, connection
// graph, assets): answered with a status naming it.
struct UnsupportedRequest {
  std::string op;
};
using ClientRequest = std::variant<SubscribeRequest, UnsubscribeRequest, ClientAdvertiseRequest,
                                   ClientUnadvertiseRequest, UnsupportedRequest>;

// A client's text message. Errors (kInvalidArgument), each saying what is wrong and where: over
// kMaxClientMessageBytes; not JSON (nlohmann's message: line, column, what it read); nested deeper
// than kMaxJsonDepth; not an object; no "op" or an unknown one; a field missing or of the wrong type
// ("subscriptions[2].channelId: expected an unsigned 32-bit integer"); more than kMaxRequestEntries
// entries; a name over kMaxNameBytes. Thread-safe (no state).
Expected<ClientRequest> parse_client_text(std::string_view text);

// "Client Message Data": opcode 0x01, channel id (uint32), then the payload. `payload` points into
// `frame`. Errors (kInvalidArgument): over kMaxClientMessageBytes, empty, shorter than its header,
// a "Service Call Request" (0x02: no services here) or an unknown opcode. Thread-safe.
struct ClientMessageData {
  std::uint32_t channel_id = 0;
  std::span<const std::uint8_t> payload;
};
Expected<ClientMessageData> parse_client_binary(std::span<const std::uint8_t> frame);

}  // namespace hubrt::hubctl::foxglove
