#include "foxglove_bridge.h"

#include <algorithm>

#include <fmt/format.h>

namespace hubrt::hubctl::foxglove {

Bridge::Bridge(BridgeOptions options, CommandSink* sink, LogFn log)
    : options_(std::move(options)), sink_(sink), log_(std::move(log)) {}

PublishPermission Bridge::permission_for(const std::string& origin) const {
  if (!options_.allow_publish || sink_ == nullptr)
    return {false, "publishing is off: hubctl foxglove runs without --allow-publish"};
  // A page the browser loaded from elsewhere can open a WebSocket to this server too (the same-origin
  // policy does not stop it): its pages may publish only when the user named its origin.
  if (!origin.empty() && std::find(options_.publish_origins.begin(), options_.publish_origins.end(),
                                   origin) == options_.publish_origins.end())
    return {false,
            fmt::format("pages from {} may not publish (hubctl foxglove --publish-origin {} allows them)",
                        origin, origin)};
  return {true, {}};
}

bool Bridge::reserve() {
  const std::lock_guard lock(mutex_);
  if (clients_.size() + reserved_ >= options_.max_clients) {
    ++counters_.refused_clients;
    return false;
  }
  ++reserved_;
  return true;
}

void Bridge::release() {
  const std::lock_guard lock(mutex_);
  if (reserved_ > 0) --reserved_;
}

std::shared_ptr<ClientSession> Bridge::connect(const std::string& peer, const std::string& origin,
                                               std::shared_ptr<ClientLink> link) {
  const std::lock_guard lock(mutex_);
  if (reserved_ > 0) --reserved_;
  const std::uint32_t id = next_client_++;
  PublishPermission permission = permission_for(origin);
  ServerInfo info;
  info.name = options_.server_name;
  info.client_publish = permission.allowed;
  info.metadata = options_.metadata;
  info.session_id = options_.session_id;
  auto session =
      std::make_shared<ClientSession>(id, peer, options_.limits, std::move(permission), sink_, log_);
  // "Server Info" first, then at least one "Advertise" (spec, "Server Info", "Advertise").
  session->send_text(std::make_shared<const std::string>(server_info_json(info)));
  std::vector<Channel> live;
  std::vector<std::uint32_t> ids;
  for (const auto& [channel_id, entry] : channels_) {
    if (!entry.live) continue;
    live.push_back(entry.channel);
    ids.push_back(channel_id);
  }
  session->channels_added(ids, std::make_shared<const std::string>(advertise_json(live)));
  clients_.emplace(id, Client{session, link});
  ++counters_.connections;
  if (log_)
    log_(fmt::format("client {} ({}{}) connected: {} of {} clients{}", id, peer,
                     origin.empty() ? "" : ", origin " + origin, clients_.size(), options_.max_clients,
                     info.client_publish ? ", may publish commands" : ""));
  link->wake();
  return session;
}

void Bridge::disconnect(std::uint32_t client_id) {
  std::shared_ptr<ClientSession> session;
  std::size_t left = 0;
  {
    const std::lock_guard lock(mutex_);
    const auto it = clients_.find(client_id);
    if (it == clients_.end()) return;
    session = it->second.session;
    clients_.erase(it);
    left = clients_.size();
  }
  const SessionCounters c = session->counters();
  if (log_)
    log_(fmt::format(
        "client {} ({}) left: {} messages queued for it, {} dropped, {} published, {} refused; {} clients",
        client_id, session->peer(), c.messages_queued, c.messages_dropped, c.published, c.publish_refused,
        left));
}

void Bridge::dispatch(const TapEvent& event) {
  const std::lock_guard lock(mutex_);
  const std::uint32_t id = event.topic->id;
  switch (event.kind) {
    case TapEvent::Kind::kTopic: {
      auto [it, added] = channels_.try_emplace(id);
      ChannelEntry& entry = it->second;
      if (added) {
        entry.channel = {id, event.topic->ros_name, event.topic->type_name, event.topic->schema};
        // The schema never changes for a topic id (tap.h: a revision changes the offered QoS only),
        // so the same id may be advertised again after it went away ("Advertise": ids).
        entry.advertise = std::make_shared<const std::string>(advertise_json({&entry.channel, 1}));
        if (event.topic->schema.empty() && log_)
          log_(fmt::format("{} ({}) is not offered: this hubctl has no .msg definition of its type",
                           event.topic->ros_name, event.topic->type_name));
      }
      if (entry.live || entry.channel.schema.empty()) return;
      entry.live = true;
      const std::uint32_t ids[] = {id};
      for (auto& [client_id, client] : clients_) {
        if (client.session->channels_added(ids, entry.advertise)) client.link->wake();
      }
      return;
    }
    case TapEvent::Kind::kTopicGone: {
      const auto it = channels_.find(id);
      if (it == channels_.end() || !it->second.live) return;
      it->second.live = false;
      const std::uint32_t ids[] = {id};
      auto unadvertise = std::make_shared<const std::string>(unadvertise_json(ids));
      for (auto& [client_id, client] : clients_) {
        if (client.session->channel_removed(id, unadvertise)) client.link->wake();
      }
      return;
    }
    case TapEvent::Kind::kSample: {
      const auto it = channels_.find(id);
      if (it == channels_.end() || !it->second.live || !event.sample) return;
      for (auto& [client_id, client] : clients_) {
        if (client.session->sample(id, event.sample)) client.link->wake();
      }
      return;
    }
  }
}

void Bridge::tick(Time now) {
  const std::lock_guard lock(mutex_);
  for (auto& [client_id, client] : clients_) {
    if (client.session->report_drops(now)) client.link->wake();
    if (client.session->overloaded()) {
      if (log_)
        log_(fmt::format("client {} ({}): closed, it read nothing of {} bytes of advertisements and statuses",
                         client_id, client.session->peer(), options_.limits.control_bytes));
      client.link->close();
    }
  }
}

BridgeCounters Bridge::counters() const {
  const std::lock_guard lock(mutex_);
  BridgeCounters out = counters_;
  out.clients = clients_.size();
  out.channels = static_cast<std::size_t>(
      std::count_if(channels_.begin(), channels_.end(), [](const auto& entry) { return entry.second.live; }));
  return out;
}

}  // namespace hubrt::hubctl::foxglove
