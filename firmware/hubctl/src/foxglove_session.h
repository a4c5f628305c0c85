// One Foxglove client of `hubctl foxglove`, without the WebSocket: what it subscribed to, what it
// may publish, and the frames waiting for it. The tap's side (the bridge's dispatcher thread) puts
// frames in, the connection's side (the I/O thread) takes them out and hands in what the client
// sent; neither ever waits for the client.
//
// A slow client costs its own messages only: Message Data frames wait in a queue bounded in bytes
// (SessionLimits::data_bytes); beyond it a sample is dropped for this client and counted, and the
// client gets a "Send buffer limit reached" warning (Foxglove shows it with a tip about the server's
// send buffer). JSON frames (advertisements, statuses) are never dropped — a client must not miss a
// channel — and have a bound of their own: past it the client is beyond help and overloaded() asks
// the connection to close it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

#include "foxglove_protocol.h"
#include "tap.h"

namespace hubrt::hubctl::foxglove {

// What one client may hold of hubctl's memory and make hubctl do.
struct SessionLimits {
  std::size_t data_bytes = 4 * 1024 * 1024;     // Message Data queued for it; beyond: dropped
  std::size_t control_bytes = 8 * 1024 * 1024;  // JSON queued for it; beyond: it is closed
  std::size_t max_subscriptions = 256;          // at a time (each for one channel)
  std::size_t max_client_channels = 16;         // channels it advertises to publish on
  double requests_per_s = 50;                   // text messages; as many at once (burst)
  double publish_per_s = 20;                    // messages it may make hubctl write; burst the same
};

// A token bucket: `per_second` tokens a second, at most `burst` saved up. Time is passed in.
class RateBudget {
 public:
  RateBudget(double per_second, double burst) noexcept;
  // Takes a token if there is one. `now` must not go backwards (a step back adds nothing).
  bool take(Time now) noexcept;

 private:
  double per_second_;
  double burst_;
  double tokens_;
  std::optional<Time> last_;
};

// A writer of one command topic (foxglove_commands.h), shared by every client channel on it.
class CommandWriter {
 public:
  virtual ~CommandWriter() = default;
  // Writes the bytes a client sent (encapsulation header and CDR payload) as one sample. Errors:
  // kInvalidArgument when they do not deserialize as the topic's type (nothing written); the DDS
  // write's code otherwise. Thread-safe.
  virtual Status write(std::span<const std::uint8_t> cdr) noexcept = 0;
};

// Where client publications go: the command writers (foxglove_commands.h) or a test's fake.
class CommandSink {
 public:
  virtual ~CommandSink() = default;
  // A writer for `topic` of the type named `schema_name`. Errors say why, for the client to read:
  // kInvalidArgument when the name is no registered command type; kPermissionDenied / Cyclone's
  // code when DDS refuses the writer (the identity's permissions, a topic of another type);
  // kOutOfRange past the budget of command topics. Called on the connection's thread.
  virtual Expected<std::shared_ptr<CommandWriter>> open(const std::string& topic,
                                                        std::string_view schema_name) = 0;
};

// Whether this client may publish, decided when it connected; when not, why (sent to it).
struct PublishPermission {
  bool allowed = false;
  std::string refusal;  // "hubctl foxglove runs without --allow-publish", ...
};

// True for a topic clients may publish on: a ROS name whose last part is "command" after at least
// one other ("/dock/command", "/tool_ecu/command", "/station1/lift/command"): the node-type and
// hub layouts' command topics (hub_api/topic_names.h). A State, /diagnostics or /sim/... is not.
bool is_command_topic(std::string_view topic) noexcept;

// One WebSocket message waiting for a client: a JSON text frame, or a Message Data frame — its
// header and the sample's bytes, shared with every other client that gets the same sample.
struct OutFrame {
  std::shared_ptr<const std::string> text;
  std::array<std::uint8_t, kMessageDataHeaderBytes> header{};
  std::shared_ptr<const TapSample> sample;
  std::uint32_t subscription_id = 0;
  [[nodiscard]] bool is_text() const noexcept { return text != nullptr; }
  [[nodiscard]] std::size_t bytes() const noexcept {
    return is_text() ? text->size() : header.size() + sample->cdr.size();
  }
};

struct SessionCounters {
  std::uint64_t messages_queued = 0;   // Message Data frames put in its queue
  std::uint64_t messages_dropped = 0;  // samples it should have got, dropped because it was behind
  std::uint64_t frames_sent = 0;       // frames taken by the connection (any kind)
  std::uint64_t published = 0;         // its messages hubctl wrote to DDS
  std::uint64_t publish_refused = 0;   // its messages hubctl did not write
};

using LogFn = std::function<void(std::string_view line)>;

class ClientSession {
 public:
  // `sink` may be null when publishing is off (then `publish.allowed` must be false). `log` gets
  // lines for hubctl's own output (drops, refused publications); it may be called with this
  // session's lock held and must not call back into it.
  ClientSession(std::uint32_t id, std::string peer, const SessionLimits& limits, PublishPermission publish,
                CommandSink* sink, LogFn log);

  [[nodiscard]] std::uint32_t id() const noexcept { return id_; }
  [[nodiscard]] const std::string& peer() const noexcept { return peer_; }

  // ---- The tap's side. Thread-safe. Each returns true when the queue was empty before, i.e. the
  // connection may be idle and must be woken.
  // A JSON frame as it is ("Server Info", a status).
  bool send_text(std::shared_ptr<const std::string> json);
  // Channels are advertised (`advertise` names them all) / one is no longer: its subscription ends
  // (the client may unsubscribe it again without an error).
  bool channels_added(std::span<const std::uint32_t> channel_ids,
                      std::shared_ptr<const std::string> advertise);
  bool channel_removed(std::uint32_t channel_id, std::shared_ptr<const std::string> unadvertise);
  // A sample of a channel: queued when the client subscribed to it and its data queue has room,
  // else dropped and counted (subscribed) or ignored (not subscribed).
  bool sample(std::uint32_t channel_id, const std::shared_ptr<const TapSample>& sample);
  // Called about once a second: when samples were dropped since the last call, a warning status
  // (one at a time in the queue) and, at most every 10 s, a line in hubctl's log.
  bool report_drops(Time now);

  // ---- The connection's side: one thread at a time.
  // What the client sent. Requests it may not make, or that break the spec, are answered with an
  // error status; nothing the client sends stops the session. Returns true when the queue was
  // empty before something was put in it.
  bool on_text(std::string_view text, Time now);
  bool on_binary(std::span<const std::uint8_t> frame, Time now);
  // The next frame to send, if any.
  std::optional<OutFrame> next_frame();
  // The JSON backlog passed SessionLimits::control_bytes: the client reads nothing; close it.
  [[nodiscard]] bool overloaded() const;

  [[nodiscard]] SessionCounters counters() const;
  [[nodiscard]] std::size_t queued_bytes() const;

 private:
  struct PublishChannel {
    std::string topic;
    std::shared_ptr<CommandWriter> writer;
  };
  // Under mutex_:
  bool push_text_locked(std::shared_ptr<const std::string> json);
  bool status_locked(StatusLevel level, const std::string& message, std::string_view id = {});
  // At most one status a second per kind of refusal that a flood of messages could repeat.
  bool throttled_status_locked(const std::string& kind, StatusLevel level, const std::string& message,
                               Time now);
  bool handle_subscribe_locked(const SubscribeRequest& request);
  bool handle_unsubscribe_locked(const UnsubscribeRequest& request);
  bool handle_unadvertise_locked(const ClientUnadvertiseRequest& request);
  // Outside the lock (opens DDS writers): advertise and publish.
  bool handle_advertise(const ClientAdvertiseRequest& request);
  bool publish(const ClientMessageData& message, Time now);
  std::optional<std::string> refuse_channel(const ClientChannel& channel) const;

  const std::uint32_t id_;
  const std::string peer_;
  const SessionLimits limits_;
  const PublishPermission publish_;
  CommandSink* const sink_;
  const LogFn log_;

  mutable std::mutex mutex_;  // guards what the two sides share:
  std::deque<OutFrame> queue_;
  std::size_t data_bytes_ = 0;
  std::size_t control_bytes_ = 0;
  std::set<std::uint32_t> channels_;                   // advertised to this client now
  std::map<std::uint32_t, std::uint32_t> by_channel_;  // channel -> its subscription
  std::map<std::uint32_t, std::uint32_t> by_id_;       // subscription -> its channel
  std::set<std::uint32_t> ended_;                      // subscriptions its channel's removal ended
  RateBudget requests_;
  // The connection's thread alone:
  std::map<std::uint32_t, PublishChannel> publishing_;
  RateBudget publications_;
  std::map<std::string, Time> last_status_;
  std::shared_ptr<const std::string> drop_status_;  // non-null while one is queued
  std::uint64_t drops_reported_ = 0;
  std::uint64_t drops_logged_ = 0;
  std::optional<Time> last_drop_log_;
  SessionCounters counters_;
};

}  // namespace hubrt::hubctl::foxglove
