#include "hubrt/dds/discovery.h"

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <tuple>
#include <utility>

#include <dds/dds.h>

#include "hubrt/dds/entity.h"
#include "hubrt/dds/retcode.h"

#include "sertype_probe.h"

namespace hubrt::dds {
namespace {

constexpr std::size_t kBatch = 64;
constexpr std::uint32_t kAliveMask = DDS_ANY_SAMPLE_STATE | DDS_ANY_VIEW_STATE | DDS_ALIVE_INSTANCE_STATE;

std::string_view builtin_topic_name(dds_entity_t topic) {
  if (topic == DDS_BUILTIN_TOPIC_DCPSPARTICIPANT) return "DCPSParticipant";
  if (topic == DDS_BUILTIN_TOPIC_DCPSPUBLICATION) return "DCPSPublication";
  return "DCPSSubscription";
}

// Takes every alive sample of a builtin topic, handing each valid one to `visit`. A fresh reader
// of a builtin topic is filled synchronously with everything discovered so far.
template <class Sample, class Visit>
Expected<void> take_builtin(const Participant& participant, dds_entity_t builtin_topic, Visit&& visit) {
  const auto what = [&] { return "read discovery topic " + std::string(builtin_topic_name(builtin_topic)); };
  const EntityHandle reader(dds_create_reader(participant.handle(), builtin_topic, nullptr, nullptr));
  if (reader.get() < 0) return dds_error(reader.get(), what());
  for (;;) {
    std::array<void*, kBatch> samples{};  // null entries: Cyclone loans its own memory
    std::array<dds_sample_info_t, kBatch> infos{};
    const dds_return_t n =
        dds_take_mask(reader.get(), samples.data(), infos.data(), kBatch, kBatch, kAliveMask);
    if (n < 0) return dds_error(n, what());
    for (dds_return_t i = 0; i < n; ++i) {
      if (infos[i].valid_data) visit(*static_cast<const Sample*>(samples[i]));
    }
    if (n > 0) (void)dds_return_loan(reader.get(), samples.data(), n);
    if (static_cast<std::size_t>(n) < kBatch) return {};
  }
}

Expected<std::set<Guid>> local_participant_keys(std::uint32_t domain_id) {
  std::vector<dds_entity_t> handles(16);
  for (;;) {
    const dds_return_t n = dds_lookup_participant(domain_id, handles.data(), handles.size());
    if (n < 0)
      return dds_error(n, "look up this process's participants in domain " + std::to_string(domain_id));
    // Cyclone fills at most handles.size() entries but reports how many exist.
    if (static_cast<std::size_t>(n) <= handles.size()) {
      handles.resize(static_cast<std::size_t>(n));
      break;
    }
    handles.resize(static_cast<std::size_t>(n));
  }
  std::set<Guid> keys;
  for (const dds_entity_t handle : handles) {
    dds_guid_t guid{};
    // A participant deleted meanwhile is simply not local any more.
    if (dds_get_guid(handle, &guid) >= 0) keys.insert(Guid::from(guid));
  }
  return keys;
}

}  // namespace

Expected<DiscoverySnapshot> discover(const Participant& participant) {
  auto local = local_participant_keys(participant.domain_id());
  if (!local) return std::move(local).error();
  DiscoverySnapshot snapshot;

  auto participants = take_builtin<dds_builtintopic_participant_t>(
      participant, DDS_BUILTIN_TOPIC_DCPSPARTICIPANT, [&](const dds_builtintopic_participant_t& p) {
        DiscoveredParticipant entry;
        entry.key = Guid::from(p.key);
        entry.local = local->contains(entry.key);
        char* name = nullptr;
        if (p.qos != nullptr && dds_qget_entity_name(p.qos, &name) && name != nullptr) {
          entry.name = name;
          dds_free(name);
        }
        snapshot.participants.push_back(std::move(entry));
      });
  if (!participants) return std::move(participants).error();

  for (const auto& [topic, direction] :
       {std::pair{DDS_BUILTIN_TOPIC_DCPSPUBLICATION, EndpointDirection::kWriter},
        std::pair{DDS_BUILTIN_TOPIC_DCPSSUBSCRIPTION, EndpointDirection::kReader}}) {
    auto endpoints = take_builtin<dds_builtintopic_endpoint_t>(
        participant, topic, [&, dir = direction](const dds_builtintopic_endpoint_t& e) {
          if (detail::is_sertype_probe(e.qos)) return;  // there only while a writer is made
          DiscoveredEndpoint entry;
          entry.direction = dir;
          entry.topic_name = e.topic_name != nullptr ? e.topic_name : "";
          entry.type_name = e.type_name != nullptr ? e.type_name : "";
          entry.key = Guid::from(e.key);
          entry.participant_key = Guid::from(e.participant_key);
          entry.local = local->contains(entry.participant_key);
          snapshot.endpoints.push_back(std::move(entry));
        });
    if (!endpoints) return std::move(endpoints).error();
  }
  return snapshot;
}

std::vector<TopicSummary> DiscoverySnapshot::topics() const {
  std::map<std::pair<std::string, std::string>, TopicSummary> by_topic;
  for (const DiscoveredEndpoint& e : endpoints) {
    TopicSummary& summary = by_topic[{e.topic_name, e.type_name}];
    summary.topic_name = e.topic_name;
    summary.type_name = e.type_name;
    const bool writer = e.direction == EndpointDirection::kWriter;
    (writer ? summary.writers : summary.readers) += 1;
    if (e.local) (writer ? summary.local_writers : summary.local_readers) += 1;
    summary.participant_keys.push_back(e.participant_key);
  }
  std::vector<TopicSummary> out;
  out.reserve(by_topic.size());
  for (auto& [key, summary] : by_topic) {
    std::sort(summary.participant_keys.begin(), summary.participant_keys.end());
    summary.participant_keys.erase(
        std::unique(summary.participant_keys.begin(), summary.participant_keys.end()),
        summary.participant_keys.end());
    out.push_back(std::move(summary));
  }
  return out;
}

}  // namespace hubrt::dds
