#include "hubrt/dds/domain.h"

#include <charconv>
#include <cstdlib>
#include <string_view>

namespace hubrt::dds {

std::string loopback_config_xml() {
  return "<CycloneDDS><Domain id=\"any\">"
         "<General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
         "<AllowMulticast>false</AllowMulticast></General>"
         "<Discovery><ParticipantIndex>auto</ParticipantIndex>"
         "<MaxAutoParticipantIndex>32</MaxAutoParticipantIndex>"
         "<Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery>"
         // Each receive thread bump-allocates the messages it hands to a delivery queue through
         // one receive buffer and replaces the buffer when less than a chunk (128 KiB) is left
         // (Cyclone 0.10 src/core/ddsi/src/q_radmin.c: nn_rbuf_alloc, commit_rmsg_chunk,
         // nn_rbuf_release). With the default 1 MiB buffer a hub's RSS climbs ~900 kB per
         // receive thread with discovery and command traffic, then falls back: 3 kB per planner
         // reconnect for ~300 reconnects (docs/soak.md). 192 KiB keeps that tooth at ~64 kB.
         "<Sizing><ReceiveBufferSize>192 KiB</ReceiveBufferSize></Sizing>"
         "</Domain></CycloneDDS>";
}

Expected<DomainConfig> domain_config_from_environment() {
  DomainConfig config;
  // NOLINTNEXTLINE(concurrency-mt-unsafe): documented as not to be raced with setenv().
  const char* value = std::getenv(kDomainIdEnvVar);
  if (value == nullptr || *value == '\0') return config;
  const std::string_view text(value);
  std::uint32_t id = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
  if (ec != std::errc() || end != text.data() + text.size() || id > kMaxDomainId) {
    return make_error(ErrorCode::kInvalidArgument, std::string(kDomainIdEnvVar) + "='" + std::string(text) +
                                                       "' is not a DDS domain id (an integer from 0 to " +
                                                       std::to_string(kMaxDomainId) + ")");
  }
  config.domain_id = id;
  return config;
}

}  // namespace hubrt::dds
