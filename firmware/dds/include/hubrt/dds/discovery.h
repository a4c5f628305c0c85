// What the domain looks like from one participant: who publishes and subscribes what (for
// `hubctl list`), read from Cyclone's builtin discovery topics.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/dds/guid.h"
#include "hubrt/dds/participant.h"

namespace hubrt::dds {

enum class EndpointDirection { kWriter, kReader };

// One writer or reader known to the participant (its own included).
struct DiscoveredEndpoint {
  EndpointDirection direction = EndpointDirection::kWriter;
  std::string topic_name;  // DDS name, e.g. "rt/dock/state"
  std::string type_name;   // DDS name, e.g. "hub_msgs::msg::dds_::DockState_"
  Guid key;
  Guid participant_key;
  bool local = false;  // belongs to a participant of this process
};

// One participant known in the domain (this process's own included).
struct DiscoveredParticipant {
  Guid key;
  std::string name;  // its entity name, empty if it published none
  bool local = false;
};

// The endpoints on one (topic, type) pair, summed up.
struct TopicSummary {
  std::string topic_name;
  std::string type_name;
  std::size_t writers = 0;
  std::size_t readers = 0;
  std::size_t local_writers = 0;
  std::size_t local_readers = 0;
  std::vector<Guid> participant_keys;  // sorted, unique: who has an endpoint on it
};

struct DiscoverySnapshot {
  std::vector<DiscoveredParticipant> participants;
  std::vector<DiscoveredEndpoint> endpoints;

  // Endpoints grouped by (topic_name, type_name), sorted by topic then type. A topic with two
  // type names shows up twice: that is a mismatch worth seeing.
  [[nodiscard]] std::vector<TopicSummary> topics() const;
};

// Reads every participant, writer and reader currently alive that `participant` has discovered
// (remote discovery takes a moment after start-up: poll with a deadline if you expect someone).
// Not atomic: participants are read before endpoints, so a snapshot can hold a just-discovered
// endpoint whose participant is not in `participants` yet; the next snapshot has both.
// Creates and deletes its builtin-topic readers on each call; not for the cycle.
// Errors: Cyclone's refusal as "read discovery topic DCPS...: DDS_RETCODE_...".
// Thread-safety: safe to call from any thread.
Expected<DiscoverySnapshot> discover(const Participant& participant);

}  // namespace hubrt::dds
