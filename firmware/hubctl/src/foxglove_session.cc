#include "foxglove_session.h"

#include <algorithm>
#include <variant>

#include <fmt/format.h>

namespace hubrt::hubctl::foxglove {
namespace {

// The text Foxglove recognises and explains ("Server is dropping messages to the client...") — the
// status foxglove_bridge sends when its send buffer is full. The id makes each repeat replace the
// last one instead of piling up.
constexpr std::string_view kSendBufferFull = "Send buffer limit reached";
constexpr std::string_view kSendBufferStatusId = "hubctl-send-buffer";
constexpr auto kDropLogInterval = std::chrono::seconds(10);
constexpr auto kStatusInterval = std::chrono::seconds(1);

bool is_name_part(std::string_view part) noexcept {
  if (part.empty() || (part[0] >= '0' && part[0] <= '9')) return false;
  return std::all_of(part.begin(), part.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
  });
}

std::string first_errors(const std::vector<std::string>& errors) {
  std::string out;
  for (std::size_t i = 0; i < errors.size() && i < 3; ++i) out += (i == 0 ? "" : "; ") + errors[i];
  if (errors.size() > 3) out += fmt::format("; and {} more", errors.size() - 3);
  return out;
}

}  // namespace

bool is_command_topic(std::string_view topic) noexcept {
  constexpr std::string_view kSuffix = "/command";
  if (!topic.starts_with('/') || !topic.ends_with(kSuffix) || topic.size() <= kSuffix.size() + 1)
    return false;
  std::string_view rest = topic.substr(1, topic.size() - kSuffix.size() - 1);
  while (!rest.empty()) {
    const auto slash = rest.find('/');
    if (!is_name_part(rest.substr(0, slash))) return false;
    rest = slash == std::string_view::npos ? std::string_view() : rest.substr(slash + 1);
    if (slash != std::string_view::npos && rest.empty()) return false;  // "//command" or "/a//command"
  }
  return true;
}

RateBudget::RateBudget(double per_second, double burst) noexcept
    : per_second_(per_second), burst_(burst), tokens_(burst) {}

bool RateBudget::take(Time now) noexcept {
  if (last_ && now > *last_) {
    const double elapsed = std::chrono::duration<double>(now - *last_).count();
    tokens_ = std::min(burst_, tokens_ + elapsed * per_second_);
  }
  if (!last_ || now > *last_) last_ = now;
  if (tokens_ < 1.0) return false;
  tokens_ -= 1.0;
  return true;
}

ClientSession::ClientSession(std::uint32_t id, std::string peer, const SessionLimits& limits,
                             PublishPermission publish, CommandSink* sink, LogFn log)
    : id_(id),
      peer_(std::move(peer)),
      limits_(limits),
      publish_(std::move(publish)),
      sink_(sink),
      log_(std::move(log)),
      requests_(limits.requests_per_s, limits.requests_per_s),
      publications_(limits.publish_per_s, limits.publish_per_s) {}

bool ClientSession::push_text_locked(std::shared_ptr<const std::string> json) {
  const bool was_empty = queue_.empty();
  control_bytes_ += json->size();
  OutFrame frame;
  frame.text = std::move(json);
  queue_.push_back(std::move(frame));
  return was_empty;
}

bool ClientSession::status_locked(StatusLevel level, const std::string& message, std::string_view id) {
  return push_text_locked(std::make_shared<const std::string>(status_json(level, message, id)));
}

bool ClientSession::throttled_status_locked(const std::string& kind, StatusLevel level,
                                            const std::string& message, Time now) {
  auto last = last_status_.find(kind);
  if (last != last_status_.end() && now - last->second < kStatusInterval) return false;
  last_status_[kind] = now;
  if (log_) log_(fmt::format("client {} ({}): {}", id_, peer_, message));
  return status_locked(level, message);
}

bool ClientSession::send_text(std::shared_ptr<const std::string> json) {
  const std::lock_guard lock(mutex_);
  return push_text_locked(std::move(json));
}

bool ClientSession::channels_added(std::span<const std::uint32_t> channel_ids,
                                   std::shared_ptr<const std::string> advertise) {
  const std::lock_guard lock(mutex_);
  channels_.insert(channel_ids.begin(), channel_ids.end());
  return push_text_locked(std::move(advertise));
}

bool ClientSession::channel_removed(std::uint32_t channel_id,
                                    std::shared_ptr<const std::string> unadvertise) {
  const std::lock_guard lock(mutex_);
  channels_.erase(channel_id);
  if (auto sub = by_channel_.find(channel_id); sub != by_channel_.end()) {
    // Its frames already queued go first: they precede the unadvertise, as the spec needs.
    const std::uint32_t subscription_id = sub->second;
    by_id_.erase(subscription_id);
    by_channel_.erase(sub);
    if (ended_.size() >= limits_.max_subscriptions) ended_.clear();
    ended_.insert(subscription_id);
  }
  return push_text_locked(std::move(unadvertise));
}

bool ClientSession::sample(std::uint32_t channel_id, const std::shared_ptr<const TapSample>& sample) {
  const std::lock_guard lock(mutex_);
  const auto sub = by_channel_.find(channel_id);
  if (sub == by_channel_.end()) return false;
  OutFrame frame;
  frame.header = message_data_header(sub->second, static_cast<std::uint64_t>(std::max<std::int64_t>(
                                                      0, sample->receive_time.ns_since_epoch)));
  frame.sample = sample;
  frame.subscription_id = sub->second;
  if (data_bytes_ + frame.bytes() > limits_.data_bytes) {
    ++counters_.messages_dropped;  // this client is behind: its loss, nobody else's
    return false;
  }
  const bool was_empty = queue_.empty();
  data_bytes_ += frame.bytes();
  ++counters_.messages_queued;
  queue_.push_back(std::move(frame));
  return was_empty;
}

bool ClientSession::report_drops(Time now) {
  const std::lock_guard lock(mutex_);
  const std::uint64_t dropped = counters_.messages_dropped;
  if (dropped == drops_reported_) return false;
  drops_reported_ = dropped;
  if (log_ && (!last_drop_log_ || now - *last_drop_log_ >= kDropLogInterval)) {
    log_(
        fmt::format("client {} ({}): {} messages dropped so far (+{}): it reads slower than the station "
                    "writes (its queue holds {} bytes at most)",
                    id_, peer_, dropped, dropped - drops_logged_, limits_.data_bytes));
    drops_logged_ = dropped;
    last_drop_log_ = now;
  }
  if (drop_status_) return false;  // the last one is still waiting: one is enough
  drop_status_ = std::make_shared<const std::string>(
      status_json(StatusLevel::kWarning, kSendBufferFull, kSendBufferStatusId));
  return push_text_locked(drop_status_);
}

std::optional<OutFrame> ClientSession::next_frame() {
  const std::lock_guard lock(mutex_);
  if (queue_.empty()) return std::nullopt;
  OutFrame frame = std::move(queue_.front());
  queue_.pop_front();
  if (frame.is_text()) {
    control_bytes_ -= frame.text->size();
    if (frame.text == drop_status_) drop_status_.reset();
  } else {
    data_bytes_ -= frame.bytes();
  }
  ++counters_.frames_sent;
  return frame;
}

bool ClientSession::overloaded() const {
  const std::lock_guard lock(mutex_);
  return control_bytes_ > limits_.control_bytes;
}

SessionCounters ClientSession::counters() const {
  const std::lock_guard lock(mutex_);
  return counters_;
}

std::size_t ClientSession::queued_bytes() const {
  const std::lock_guard lock(mutex_);
  return data_bytes_ + control_bytes_;
}

bool ClientSession::on_text(std::string_view text, Time now) {
  {
    const std::lock_guard lock(mutex_);
    if (!requests_.take(now)) {
      return throttled_status_locked(
          "requests", StatusLevel::kWarning,
          fmt::format("too many requests: at most {:g} a second per client; the excess is ignored",
                      limits_.requests_per_s),
          now);
    }
  }
  auto request = parse_client_text(text);
  // Advertising opens DDS writers: not under the lock the tap's side takes for every sample.
  if (request) {
    if (const auto* advertise = std::get_if<ClientAdvertiseRequest>(&*request))
      return handle_advertise(*advertise);
  }
  const std::lock_guard lock(mutex_);
  if (!request) return status_locked(StatusLevel::kError, request.error().message);
  if (const auto* subscribe = std::get_if<SubscribeRequest>(&*request))
    return handle_subscribe_locked(*subscribe);
  if (const auto* unsubscribe = std::get_if<UnsubscribeRequest>(&*request))
    return handle_unsubscribe_locked(*unsubscribe);
  if (const auto* unadvertise = std::get_if<ClientUnadvertiseRequest>(&*request))
    return handle_unadvertise_locked(*unadvertise);
  return status_locked(StatusLevel::kError,
                       fmt::format("\"{}\" is not offered: this server declares only the capabilities in its "
                                   "serverInfo",
                                   std::get<UnsupportedRequest>(*request).op));
}

bool ClientSession::handle_subscribe_locked(const SubscribeRequest& request) {
  std::vector<std::string> errors;
  for (const SubscribeRequest::Entry& entry : request.subscriptions) {
    if (channels_.count(entry.channel_id) == 0) {
      errors.push_back(fmt::format("channel {} is not advertised", entry.channel_id));
    } else if (by_id_.count(entry.id) != 0) {
      errors.push_back(fmt::format("subscription id {} is in use", entry.id));
    } else if (auto had = by_channel_.find(entry.channel_id); had != by_channel_.end()) {
      errors.push_back(fmt::format("channel {} has subscription {} already (one per channel)",
                                   entry.channel_id, had->second));
    } else if (by_id_.size() >= limits_.max_subscriptions) {
      errors.push_back(
          fmt::format("subscription {}: at most {} per client", entry.id, limits_.max_subscriptions));
    } else {
      by_id_.emplace(entry.id, entry.channel_id);
      by_channel_.emplace(entry.channel_id, entry.id);
      ended_.erase(entry.id);
    }
  }
  if (errors.empty()) return false;
  return status_locked(StatusLevel::kError, "subscribe: " + first_errors(errors));
}

bool ClientSession::handle_unsubscribe_locked(const UnsubscribeRequest& request) {
  std::vector<std::string> errors;
  std::set<std::uint32_t> ended;
  for (const std::uint32_t id : request.subscription_ids) {
    if (const auto sub = by_id_.find(id); sub != by_id_.end()) {
      by_channel_.erase(sub->second);
      by_id_.erase(sub);
      ended.insert(id);
    } else if (ended_.erase(id) == 0) {
      // Ended by an unadvertise, Foxglove unsubscribes again: that is no error.
      errors.push_back(fmt::format("no subscription {}", id));
    }
  }
  // What was queued for them is not wanted any more: one pass over the queue for the request.
  if (!ended.empty()) {
    std::erase_if(queue_, [&](const OutFrame& frame) {
      if (frame.is_text() || ended.count(frame.subscription_id) == 0) return false;
      data_bytes_ -= frame.bytes();
      return true;
    });
  }
  if (errors.empty()) return false;
  return status_locked(StatusLevel::kWarning, "unsubscribe: " + first_errors(errors));
}

std::optional<std::string> ClientSession::refuse_channel(const ClientChannel& channel) const {
  if (!publish_.allowed) return publish_.refusal;
  if (publishing_.count(channel.id) != 0) return fmt::format("channel id {} is in use", channel.id);
  if (publishing_.size() >= limits_.max_client_channels)
    return fmt::format("at most {} channels per client", limits_.max_client_channels);
  if (channel.encoding != "cdr")
    return fmt::format("encoding \"{}\": this server takes \"cdr\" only (its supportedEncodings)",
                       channel.encoding);
  if (!is_command_topic(channel.topic))
    return fmt::format(
        "\"{}\" is not a command topic: clients may publish on /<node_type>/command and "
        "/<hub>/command only",
        channel.topic);
  return std::nullopt;
}

bool ClientSession::handle_advertise(const ClientAdvertiseRequest& request) {
  std::vector<std::string> errors;
  for (const ClientChannel& channel : request.channels) {
    auto refusal = refuse_channel(channel);
    if (!refusal) {
      auto writer = sink_->open(channel.topic, channel.schema_name);
      if (writer) {
        publishing_.emplace(channel.id, PublishChannel{channel.topic, std::move(*writer)});
        if (log_)
          log_(fmt::format("client {} ({}) publishes on {} ({})", id_, peer_, channel.topic,
                           channel.schema_name));
        continue;
      }
      refusal = writer.error().message;
    }
    errors.push_back(fmt::format("channel {} on {}: {}", channel.id, channel.topic, *refusal));
  }
  if (errors.empty()) return false;
  const std::lock_guard lock(mutex_);
  const std::string message = "advertise refused: " + first_errors(errors) + "; nothing will be written";
  if (log_) log_(fmt::format("client {} ({}): {}", id_, peer_, message));
  return status_locked(StatusLevel::kError, message);
}

bool ClientSession::handle_unadvertise_locked(const ClientUnadvertiseRequest& request) {
  std::vector<std::string> errors;
  for (const std::uint32_t id : request.channel_ids) {
    if (publishing_.erase(id) == 0) errors.push_back(fmt::format("no channel {} of this client", id));
  }
  if (errors.empty()) return false;
  return status_locked(StatusLevel::kWarning, "unadvertise: " + first_errors(errors));
}

bool ClientSession::on_binary(std::span<const std::uint8_t> frame, Time now) {
  auto message = parse_client_binary(frame);
  if (!message) {
    const std::lock_guard lock(mutex_);
    ++counters_.publish_refused;
    return throttled_status_locked("binary", StatusLevel::kError, message.error().message, now);
  }
  return publish(*message, now);
}

bool ClientSession::publish(const ClientMessageData& message, Time now) {
  std::string refusal;
  std::string kind;
  const auto channel = publishing_.find(message.channel_id);
  if (!publish_.allowed) {
    kind = "not allowed";
    refusal = publish_.refusal;
  } else if (channel == publishing_.end()) {
    kind = "no channel";
    refusal = fmt::format("message on channel {}, which this client has not advertised (or was refused)",
                          message.channel_id);
  } else {
    if (!publications_.take(now)) {
      kind = "budget";
      refusal = fmt::format("{}: more than {:g} messages a second from this client", channel->second.topic,
                            limits_.publish_per_s);
    } else if (const Status written = channel->second.writer->write(message.payload); !written.is_ok()) {
      kind = "write";
      refusal =
          written.code() == ErrorCode::kInvalidArgument
              ? fmt::format("{}: the payload does not deserialize as the topic's type", channel->second.topic)
              : fmt::format("{}: the DDS write failed ({})", channel->second.topic,
                            to_string(written.code()));
    }
  }
  const std::lock_guard lock(mutex_);
  if (refusal.empty()) {
    ++counters_.published;
    return false;
  }
  ++counters_.publish_refused;
  return throttled_status_locked(kind, StatusLevel::kError, "message not written: " + refusal, now);
}

}  // namespace hubrt::hubctl::foxglove
