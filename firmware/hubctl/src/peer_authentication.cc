#include "peer_authentication.h"

#include <set>

#include <fmt/format.h>

#include "hubrt/dds/discovery.h"
#include "hubrt/security/participant_security.h"

namespace hubrt::hubctl {

PeersSeen peers_seen(const dds::Participant& participant) {
  PeersSeen seen;
  auto snapshot = dds::discover(participant);
  if (!snapshot) return seen;
  std::set<dds::Guid> with_topics;
  for (const auto& endpoint : snapshot->endpoints) {
    if (!endpoint.local) with_topics.insert(endpoint.participant_key);
  }
  for (const auto& p : snapshot->participants) {
    if (p.local) continue;
    ++seen.participants;
    if (with_topics.contains(p.key)) ++seen.with_topics;
  }
  return seen;
}

std::optional<std::string> authentication_problem(bool secured, const std::string& identity,
                                                  const dds::SecurityRefusalCounts& refusals,
                                                  const std::string& last_refusal, const PeersSeen& peers) {
  // Without security a participant with no topic may be anything (a tool, a test's observer): no
  // claim. A peer that shows topics authenticated: then authentication is not why nobody reads.
  const bool unauthenticated_peers = peers.participants > 0 && peers.with_topics == 0;
  if (!secured || peers.with_topics > 0 || (refusals.authentication == 0 && !unauthenticated_peers))
    return std::nullopt;
  const std::string seen =
      peers.participants == 0
          ? std::string("no participant shows a topic")
          : fmt::format("{} participant(s) on the domain, none authenticated", peers.participants);
  return fmt::format(
      "authentication failed: {}; Cyclone: {}. This participant is {}: peers authenticate it only when their "
      "identity CA is that one, and it them only when theirs is",
      seen,
      refusals.authentication > 0 && !last_refusal.empty()
          ? last_refusal
          : std::string("no handshake completed (the peers did not answer this participant's)"),
      identity);
}

std::optional<std::string> authentication_problem(const dds::Participant& participant,
                                                  const DomainOptions& options) {
  const bool secured = !options.security_dir.empty();
  const std::string identity = secured ? fmt::format("'{}' with {}", options.identity,
                                                     security::describe_identity(security::credentials_in(
                                                         options.security_dir, options.identity)))
                                       : std::string();
  return authentication_problem(secured, identity, dds::security_refusals(), dds::last_security_refusal(),
                                peers_seen(participant));
}

}  // namespace hubrt::hubctl
