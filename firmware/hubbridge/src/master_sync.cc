#include "master_sync.h"

#include <algorithm>

#include <spdlog/spdlog.h>

namespace hubrt::hubbridge {
namespace {

constexpr std::size_t kMaxNameLength = 256;

// A ROS graph resource name as a master hands it out ([A-Za-z0-9_/~], wiki.ros.org/Names), and
// short enough to log and publish.
bool plausible_name(const std::string& name) {
  return !name.empty() && name.size() <= kMaxNameLength && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '/' || c == '~';
  });
}

bool contains(const std::vector<std::string>& list, const std::string& item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

}  // namespace

MasterSync::MasterSync(Ros1Graph& graph, std::vector<SyncedEndpoint> endpoints, bool register_lost_publishers)
    : graph_(graph),
      endpoints_(std::move(endpoints)),
      register_lost_publishers_(register_lost_publishers),
      known_(endpoints_.size()),
      attempted_(endpoints_.size()),
      status_(endpoints_.size()) {}

MasterSync::Action MasterSync::turn(const std::vector<std::vector<std::string>>& heard) {
  const int pid = graph_.master_pid();
  master_pid_ = pid;
  if (pid == 0) return Action::kNone;  // away: the links carry on; nothing to tell anyone
  if (registered_with_ == 0) return Action::kRegisterFirst;
  if (pid != registered_with_) {
    spdlog::info("rosmaster restarted (pid {} -> {}): registering {} endpoints again, keeping their links",
                 registered_with_, pid, endpoints_.size());
    register_again(heard);
    registered_with_ = pid;
    ++registrations_;
  }
  const auto state = graph_.system_state();
  if (!state) return Action::kNone;
  learn(*state);
  static const std::vector<std::string> kNone;
  for (std::size_t i = 0; i < endpoints_.size(); ++i) {
    if (!endpoints_[i].subscribes) continue;
    const auto listed = state->publishers.find(endpoints_[i].topic);
    register_lost(i, i < heard.size() ? heard[i] : kNone,
                  listed == state->publishers.end() ? kNone : listed->second);
  }
  return Action::kNone;
}

void MasterSync::registered_first() {
  registered_with_ = master_pid_;
  ++registrations_;
}

void MasterSync::register_again(const std::vector<std::vector<std::string>>& heard) {
  for (std::size_t i = 0; i < endpoints_.size(); ++i) {
    attempted_[i].clear();
    status_[i].registered_for.clear();
  }
  const std::string name = graph_.own_name();
  const std::string uri = graph_.own_uri();
  const std::vector<Ros1Graph::Link> links = graph_.own_links();
  static const std::vector<std::string> kNone;
  // The publishers hubbridge hears first, so that whatever the new master tells a subscriber of
  // their topics (hubbridge included) lists them.
  for (std::size_t i = 0; i < endpoints_.size(); ++i) {
    if (endpoints_[i].subscribes) register_lost(i, i < heard.size() ? heard[i] : kNone, kNone);
  }
  // hubbridge's publishers, then the subscribers connected to them.
  for (std::size_t i = 0; i < endpoints_.size(); ++i) {
    const SyncedEndpoint& e = endpoints_[i];
    if (e.subscribes) continue;
    if (!graph_.register_publisher(name, uri, e.topic, e.type))
      spdlog::warn("rosmaster: registering the publisher of {} failed; trying again after its next restart",
                   e.topic);
    if (!register_lost_publishers_) continue;
    for (const Ros1Graph::Link& link : links) {
      if (!link.inbound && link.topic == e.topic && link.peer != name)
        (void)register_for(i, link.peer, false);
    }
  }
  // hubbridge's subscriptions: the publishers the new master lists join the ones connected.
  for (std::size_t i = 0; i < endpoints_.size(); ++i) {
    const SyncedEndpoint& e = endpoints_[i];
    if (!e.subscribes) continue;
    const auto listed = graph_.register_subscriber(name, uri, e.topic, e.type);
    if (!listed) {
      spdlog::warn("rosmaster: registering the subscriber of {} failed; trying again after its next restart",
                   e.topic);
      continue;
    }
    std::vector<std::string> publishers;
    for (const Ros1Graph::Link& link : links) {
      if (link.inbound && link.topic == e.topic && !contains(publishers, link.peer))
        publishers.push_back(link.peer);
    }
    bool news = false;
    for (const std::string& publisher : *listed) {
      if (publisher == uri || contains(publishers, publisher)) continue;
      publishers.push_back(publisher);
      news = true;
    }
    // Only when there is someone new: an update lacking a connected publisher would drop it.
    if (news) graph_.own_publisher_update(e.topic, publishers);
  }
}

void MasterSync::learn(const Ros1Graph::SystemState& state) {
  const std::string own = graph_.own_name();
  std::size_t lookups = 0;
  for (std::size_t i = 0; i < endpoints_.size(); ++i) {
    const auto& lists = endpoints_[i].subscribes ? state.publishers : state.subscribers;
    const auto listed = lists.find(endpoints_[i].topic);
    if (listed == lists.end()) continue;
    auto& known = known_[i];
    if (known.size() >= kMaxKnownPerEndpoint) {
      std::erase_if(known, [&](const auto& entry) { return !contains(listed->second, entry.first); });
    }
    // Every turn, not once: a node that restarted under its name has another URI now, and the
    // old one must never be registered for it.
    for (const std::string& name : listed->second) {
      if (name == own || !plausible_name(name) || lookups == kMaxLookupsPerTurn) continue;
      if (!known.contains(name) && known.size() >= kMaxKnownPerEndpoint) continue;
      ++lookups;
      if (auto uri = graph_.lookup_node(name)) known[name] = std::move(*uri);
    }
  }
}

void MasterSync::register_lost(std::size_t index, const std::vector<std::string>& heard,
                               const std::vector<std::string>& listed) {
  const std::string own = graph_.own_name();
  auto& unregistered = status_[index].unregistered;
  unregistered.clear();
  for (const std::string& name : heard) {
    if (name == own || contains(listed, name)) continue;
    if (register_lost_publishers_ && register_for(index, name, true)) continue;
    if (plausible_name(name)) unregistered.push_back(name);
  }
}

bool MasterSync::register_for(std::size_t index, const std::string& name, bool as_publisher) {
  const SyncedEndpoint& e = endpoints_[index];
  if (attempted_[index].contains(name)) return contains(status_[index].registered_for, name);
  const auto known = known_[index].find(name);
  if (known == known_[index].end()) return false;  // never listed for this topic: not ours to vouch for
  attempted_[index].insert(name);
  // A master that knows the name at another URI has heard from that node since: leave it be.
  if (const auto current = graph_.lookup_node(name); current && *current != known->second) {
    known->second = *current;
    return false;
  }
  const bool ok = as_publisher ? graph_.register_publisher(name, known->second, e.topic, e.type)
                               : graph_.register_subscriber(name, known->second, e.topic, e.type).has_value();
  if (!ok) {
    spdlog::warn("rosmaster: registering {} ({}) as a {} of {} on its behalf failed", name, known->second,
                 as_publisher ? "publisher" : "subscriber", e.topic);
    return false;
  }
  spdlog::info("rosmaster: registered {} ({}) as a {} of {} on its behalf: the master had lost it", name,
               known->second, as_publisher ? "publisher" : "subscriber", e.topic);
  status_[index].registered_for.push_back(name);
  return true;
}

}  // namespace hubrt::hubbridge
