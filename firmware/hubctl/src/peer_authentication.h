// Why hubctl found nobody to talk to when DDS Security is in the way (issue 34 point 3): a
// participant of another station's CA sees the station's participants (Cyclone puts a remote
// participant on DCPSParticipant before its handshake) but none of their topics (discovery is
// encrypted and only follows authentication), and a failed handshake shows only on Cyclone's log.
// "Nobody reads" would be wrong; "authentication failed" and why is what helps.
#pragma once

#include <optional>
#include <string>

#include "hubrt/dds/participant.h"
#include "hubrt/dds/security_refusals.h"

#include "session.h"

namespace hubrt::hubctl {

// What the domain showed while hubctl waited: remote participants, and how many of them showed
// at least one topic (which only an authenticated peer of a secured station does).
struct PeersSeen {
  std::size_t participants = 0;
  std::size_t with_topics = 0;
};

// Reads `participant`'s discovery now. Errors are taken as nothing seen.
PeersSeen peers_seen(const dds::Participant& participant);

// The sentence that replaces "nobody reads" when authentication is why, or nullopt:
//   secured, no peer showed a topic, and this process's Cyclone refused a handshake
//   (refusals.authentication > 0) or peers were seen: "authentication failed: ..." naming our
//   identity and its CA (`identity`, security::describe_identity) and Cyclone's reason
//   (`last_refusal`) or "no handshake completed". Never without security: a participant that
//   shows no topic there may be anything. Pure.
std::optional<std::string> authentication_problem(bool secured, const std::string& identity,
                                                  const dds::SecurityRefusalCounts& refusals,
                                                  const std::string& last_refusal, const PeersSeen& peers);

// authentication_problem for this process: its refusal counts and `participant`'s discovery.
std::optional<std::string> authentication_problem(const dds::Participant& participant,
                                                  const DomainOptions& options);

}  // namespace hubrt::hubctl
