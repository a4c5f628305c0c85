#include "scenario_traffic.h"

#include <set>
#include <thread>

#include <fmt/format.h>

#include "hubrt/dds/discovery.h"
#include "hubrt/dds/ros_names.h"
#include "hubrt/msgs/all_types.h"

#include "command_channel.h"
#include "command_qos.h"
#include "reader_wait.h"
#include "session.h"

namespace hubrt::hubctl {

ScenarioTraffic::ScenarioTraffic(const dds::Participant& participant, Duration discovery_timeout,
                                 Duration period, std::uint32_t command_lifespan_ms,
                                 std::string ros_namespace)
    : participant_(participant),
      discovery_timeout_(discovery_timeout),
      period_(period),
      command_lifespan_ms_(command_lifespan_ms),
      ros_namespace_(std::move(ros_namespace)) {}

// ---- the loop: samples in, due commands out -----------------------------------------------------

void ScenarioTraffic::pump() {
  for (auto& [topic, channel] : states_) {
    for (int i = 0; i < 256; ++i) {
      const Result<bool> taken = channel->reader->take_next(channel->sample->data());
      if (!taken.is_ok() || !taken.value()) break;
      // A sample that cannot be read is reported and skipped; the scenario goes on.
      auto value = channel->decoder->decode(*channel->type, channel->sample->data());
      if (!value) continue;
      channel->latest = std::move(*value);
      channel->received_at = SteadyClock::now();
      ++channel->generation;
    }
  }
  const auto now = SteadyClock::now();
  if (now >= next_send_) {
    for (auto& [key, plan] : plans_) send(plan);
    next_send_ += std::chrono::duration_cast<SteadyClock::duration>(period_);
    if (next_send_ < now) next_send_ = now;  // a stall: do not burst to catch up
  }
}

void ScenarioTraffic::pump_for(Duration span) {
  const auto until = SteadyClock::now() + span;
  while (SteadyClock::now() < until && !stop_requested()) {
    pump();
    std::this_thread::sleep_for(kPoll);
  }
}

void ScenarioTraffic::send(Plan& plan) {
  if (plan.sample && plan.writer != nullptr) plan.writer->writer->write(plan.sample->data()).ignore();
}

// ---- where things are ----------------------------------------------------------------------------

Expected<NodeEndpoints> ScenarioTraffic::locate(const StepTarget& target) {
  const std::string key = fmt::format("{}/{}", target.hub, target.node);
  if (auto known = located_.find(key); known != located_.end()) return known->second;
  auto found =
      find_node(participant_, msgs::all_types(), target.hub, target.node, discovery_timeout_, ros_namespace_);
  if (!found) return found;
  located_.emplace(key, *found);
  return found;
}

Expected<const msgs::TypeInfo*> ScenarioTraffic::known_type(std::string_view ros_name) {
  const msgs::TypeInfo* type = msgs::all_types().find(ros_name);
  if (type == nullptr || type->descriptor == nullptr) {
    return make_error(ErrorCode::kNotFound, fmt::format("this hubctl does not know the type {}", ros_name));
  }
  return type;
}

Expected<StateChannel*> ScenarioTraffic::channel(const std::string& topic, const msgs::TypeInfo& type) {
  if (auto it = states_.find(topic); it != states_.end()) return it->second.get();
  auto entry = std::make_unique<StateChannel>();
  entry->topic = topic;
  entry->type = &type;
  auto t = dds::UntypedTopic::create(participant_, *type.descriptor, topic);
  if (!t) return std::move(t).error();
  entry->dds_topic.emplace(std::move(*t));
  auto r = dds::UntypedReader::create(participant_, *entry->dds_topic);
  if (!r) return std::move(r).error();
  entry->reader.emplace(std::move(*r));
  entry->sample.emplace(*type.descriptor);
  entry->decoder.emplace("hubctl play", topic);
  StateChannel* raw = entry.get();
  states_.emplace(topic, std::move(entry));
  return raw;
}

Expected<std::pair<StateChannel*, std::string>> ScenarioTraffic::state_of(const StepTarget& target) {
  if (target.station) {
    auto type = known_type("hub_msgs/msg/StationState");
    if (!type) return std::move(type).error();
    auto c = channel(station_topic(kStationStateTopic), **type);
    if (!c) return std::move(c).error();
    return std::make_pair(*c, std::string());
  }
  auto endpoints = locate(target);
  if (!endpoints) return std::move(endpoints).error();
  auto c = channel(endpoints->state_topic, *endpoints->state_type);
  if (!c) return std::move(c).error();
  return std::make_pair(*c, endpoints->field);
}

Expected<WriterEntry*> ScenarioTraffic::writer(const std::string& topic, const msgs::TypeInfo& type,
                                               std::uint32_t readers) {
  return writer_with(topic, type, readers, dds::Qos::ros2_default());
}

Expected<WriterEntry*> ScenarioTraffic::command_writer(const std::string& topic, const msgs::TypeInfo& type) {
  return writer_with(topic, type, 1, command_writer_qos(command_lifespan_ms_));
}

Expected<WriterEntry*> ScenarioTraffic::writer_with(const std::string& topic, const msgs::TypeInfo& type,
                                                    std::uint32_t readers, const dds::Qos& qos) {
  auto it = writers_.find(topic);
  if (it == writers_.end()) {
    auto entry = std::make_unique<WriterEntry>();
    auto t = dds::UntypedTopic::create(participant_, *type.descriptor, topic);
    if (!t) return std::move(t).error();
    entry->topic.emplace(std::move(*t));
    auto w = dds::UntypedWriter::create(participant_, *entry->topic, announceable(qos));
    if (!w) return std::move(w).error();
    entry->writer.emplace(std::move(*w));
    it = writers_.emplace(topic, std::move(entry)).first;
    if (auto matched = wait_for_readers(*it->second, readers); !matched) return std::move(matched).error();
    // A step writes once: every reader matched should have heard the new writer first. One that
    // has not within the discovery timeout (a stopped hub) holds up the others no longer; a step
    // that needs that hub's answer finds out by waiting for it.
    (void)greet_readers(*it->second->writer, discovery_timeout_, topic, [this] { pump(); });
    return it->second.get();
  }
  if (auto matched = wait_for_readers(*it->second, readers); !matched) return std::move(matched).error();
  return it->second.get();
}

Expected<void> ScenarioTraffic::wait_for_readers(const WriterEntry& entry, std::uint32_t count) {
  const auto deadline = SteadyClock::now() + discovery_timeout_;
  while (true) {
    const auto matched = entry.writer->matched_readers();
    if (matched.is_ok() && matched.value() >= count) return {};
    if (SteadyClock::now() >= deadline || stop_requested()) {
      return make_error(ErrorCode::kTimeout,
                        fmt::format("nobody reads {} ({} of {} reader(s) matched after {:.1f} s)",
                                    entry.writer->topic_name(), matched.is_ok() ? matched.value() : 0, count,
                                    to_seconds(discovery_timeout_)));
    }
    pump();
    std::this_thread::sleep_for(kPoll);
  }
}

namespace {

// Remote readers of `dds_name` in a discovery snapshot, and whether one of them is the hub `hub`'s
// (a participant is named after its hub).
struct ReaderCount {
  std::uint32_t readers = 0;
  bool hub_listens = false;
};

ReaderCount count_readers(const dds::DiscoverySnapshot& snapshot, std::string_view dds_name,
                          std::string_view hub) {
  std::set<dds::Guid> hub_keys;
  for (const auto& p : snapshot.participants) {
    if (!p.local && !hub.empty() && p.name == hub) hub_keys.insert(p.key);
  }
  ReaderCount count;
  for (const auto& e : snapshot.endpoints) {
    if (e.local || e.direction != dds::EndpointDirection::kReader || e.topic_name != dds_name) continue;
    ++count.readers;
    count.hub_listens |= hub_keys.count(e.participant_key) != 0;
  }
  return count;
}

}  // namespace

Expected<std::uint32_t> ScenarioTraffic::readers_including(std::string_view ros_topic, std::string_view hub) {
  auto dds_name = dds::ros_to_dds_topic(ros_topic);
  if (!dds_name) return std::move(dds_name).error();
  const auto deadline = SteadyClock::now() + discovery_timeout_;
  while (true) {
    auto snapshot = dds::discover(participant_);
    if (!snapshot) return std::move(snapshot).error();
    const ReaderCount count = count_readers(*snapshot, *dds_name, hub);
    if (count.hub_listens) return count.readers;
    if (SteadyClock::now() >= deadline || stop_requested()) {
      return make_error(
          ErrorCode::kNotFound,
          fmt::format("hub '{}' does not listen to {} (is it running on the fake backend?)", hub, ros_topic));
    }
    pump();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

Expected<std::uint32_t> ScenarioTraffic::readers_now(std::string_view ros_topic) {
  auto dds_name = dds::ros_to_dds_topic(ros_topic);
  if (!dds_name) return std::move(dds_name).error();
  auto snapshot = dds::discover(participant_);
  if (!snapshot) return std::move(snapshot).error();
  return count_readers(*snapshot, *dds_name, {}).readers;
}

}  // namespace hubrt::hubctl
