#include "hubrt/assembly/twin_rules.h"

#include <algorithm>
#include <charconv>
#include <map>

#include <fmt/format.h>

#include "hubrt/dds/ros_names.h"

namespace hubrt::assembly {
namespace {

constexpr std::string_view kStampKey = "hubrt.started_ns=";
constexpr std::string_view kIdentityKey = "hubrt.hub=";

// The value of `key` ("name=") in USER_DATA made of "key=value;" pairs (ROS 2 uses the same
// shape), found at a pair boundary; nullopt when absent, unterminated or empty.
std::optional<std::string_view> user_data_value(std::string_view user_data, std::string_view key) noexcept {
  std::size_t at = 0;
  for (;;) {
    at = user_data.find(key, at);
    if (at == std::string_view::npos) return std::nullopt;
    if (at == 0 || user_data[at - 1] == ';') break;
    at += key.size();
  }
  const std::string_view rest = user_data.substr(at + key.size());
  const std::size_t end = rest.find(';');
  if (end == std::string_view::npos || end == 0) return std::nullopt;
  return rest.substr(0, end);
}

}  // namespace

std::string start_stamp_user_data(std::int64_t started_ns) {
  return fmt::format("{}{};", kStampKey, started_ns);
}

std::string hub_user_data(std::int64_t started_ns, std::string_view ros_namespace, std::string_view hub) {
  return fmt::format("{}{};{}{}/{};", kStampKey, started_ns, kIdentityKey, ros_namespace, hub);
}

std::optional<std::int64_t> parse_start_stamp(std::string_view user_data) noexcept {
  const std::optional<std::string_view> text = user_data_value(user_data, kStampKey);
  if (!text) return std::nullopt;
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(text->data(), text->data() + text->size(), value);
  if (ec != std::errc() || ptr != text->data() + text->size()) return std::nullopt;
  return value;
}

std::optional<std::string_view> parse_hub_identity(std::string_view user_data) noexcept {
  return user_data_value(user_data, kIdentityKey);
}

StartupVerdict StartupCheck::update(const std::vector<dds::WatchedParticipant>& participants,
                                    std::uint64_t discovered, Time discovered_at, std::size_t twin_writers,
                                    Time now) {
  if (twin_writers > 0) return StartupVerdict::kTwin;
  if (discovered != discovered_) {
    discovered_ = discovered;
    last_new_ = std::max(last_new_, std::clamp(discovered_at, begin_, now));
  }
  bool unnamed_hub = false;
  for (const dds::WatchedParticipant& other : participants) {
    const std::optional<std::string_view> identity = parse_hub_identity(other.user_data);
    if (identity && *identity == identity_ && !claimed_) {
      claimed_ = true;
      claimed_at_ = now;
      claimant_ = other.key;
    }
    if (!identity && parse_start_stamp(other.user_data)) unnamed_hub = true;
  }
  unnamed_hub_ = unnamed_hub;
  const bool over = now - begin_ >= window_;
  if (claimed_) {
    if (!over && now - claimed_at_ < quiet_) return StartupVerdict::kWait;
    if (!twin_decided_at_) twin_decided_at_ = now;
    return StartupVerdict::kTwin;
  }
  if (over) return StartupVerdict::kAlone;
  if (!unnamed_hub && now - last_new_ >= quiet_) return StartupVerdict::kAlone;
  return StartupVerdict::kWait;
}

Time StartupCheck::decides_by() const noexcept {
  const Time window_end = begin_ + window_;
  if (claimed_) return std::min(window_end, claimed_at_ + quiet_);
  if (unnamed_hub_) return window_end;
  return std::min(window_end, last_new_ + quiet_);
}

bool is_later(const HubStamp& a, const HubStamp& b) noexcept {
  if (a.started_ns != b.started_ns) return a.started_ns > b.started_ns;
  return a.participant > b.participant;
}

bool is_own_state_topic(std::string_view dds_topic, std::string_view ros_namespace,
                        std::string_view hub) noexcept {
  const auto consume = [&dds_topic](std::string_view part) {
    if (!dds_topic.starts_with(part)) return false;
    dds_topic.remove_prefix(part.size());
    return true;
  };
  if (!consume("rt") || !consume(ros_namespace) || !consume("/") || !consume(hub) || !consume("/"))
    return false;
  if (dds_topic == "state") return true;  // hub layout
  const std::size_t slash = dds_topic.find('/');
  return slash != 0 && slash != std::string_view::npos && dds_topic.substr(slash) == "/state";
}

TwinSnapshot summarize_twins(const std::vector<dds::WatchedWriter>& writers) {
  TwinSnapshot snapshot;
  std::map<dds::Guid, TwinPeer*> by_participant;
  for (const dds::WatchedWriter& writer : writers) {
    const auto found = by_participant.find(writer.participant_key);
    if (found != by_participant.end()) {
      if (found->second != nullptr) ++found->second->topics;
      continue;
    }
    if (snapshot.count == TwinSnapshot::kMaxPeers) {
      ++snapshot.more;
      by_participant.emplace(writer.participant_key, nullptr);
      continue;
    }
    TwinPeer& peer = snapshot.peers[snapshot.count++];
    by_participant.emplace(writer.participant_key, &peer);
    peer.participant = writer.participant_key;
    peer.topic.assign(dds::dds_to_ros_topic(writer.topic_name).value_or(writer.topic_name));
    peer.topics = 1;
    peer.host.assign(writer.host);
    peer.pid.assign(writer.pid);
    peer.started_ns = parse_start_stamp(writer.user_data);
  }
  return snapshot;
}

void describe_origin(const TwinPeer& peer, runtime::TextBuffer<128>& out) noexcept {
  if (peer.host.empty() && peer.pid.empty()) {
    const auto& b = peer.participant.bytes;
    out.format("participant {:02x}{:02x}{:02x}{:02x}:{:02x}{:02x}{:02x}{:02x}:{:02x}{:02x}{:02x}{:02x}", b[0],
               b[1], b[2], b[3], b[4], b[5], b[6], b[7], b[8], b[9], b[10], b[11]);
    return;
  }
  out.format("host {} pid {}", peer.host.empty() ? "?" : peer.host.view(),
             peer.pid.empty() ? "?" : peer.pid.view());
}

void TwinMonitor::update(const TwinSnapshot& current, Time now, runtime::HubAlerts& alerts) noexcept {
  alerts.clear();
  runtime::TextBuffer<128> origin;
  for (std::size_t i = 0; i < current.count; ++i) {
    const TwinPeer& peer = current.peers[i];
    describe_origin(peer, origin);
    alerts.add("twin: another hub publishes {} from {}", peer.topic.view(), origin.view());
    if (peer.started_ns && !must_yield_ && is_later(self_, HubStamp{*peer.started_ns, peer.participant})) {
      must_yield_ = true;
      yielded_to_ = peer;
    }
  }
  if (current.more > 0) alerts.add("twin: and {} more participants publish this hub's States", current.more);
  const bool came_and_went = current.sightings != sightings_;
  sightings_ = current.sightings;
  if (current.count > 0) {
    last_seen_ = current.peers[0];
    last_seen_at_ = now;
    seen_ = true;
    return;
  }
  if (came_and_went) {  // it was there between the last cycle and this one
    last_seen_ = current.last;
    last_seen_at_ = now;
    seen_ = true;
  }
  if (seen_ && now - last_seen_at_ <= hold_) {
    describe_origin(last_seen_, origin);
    alerts.add("twin: another hub published {} from {} until {:.1f} s ago", last_seen_.topic.view(),
               origin.view(), to_seconds(now - last_seen_at_));
  }
}

}  // namespace hubrt::assembly
