#include "hubrt/dds/domain.h"

#include <charconv>
#include <cstdlib>
#include <string>
#include <string_view>

namespace hubrt::dds {
namespace {

std::string max_sample_size_element() {
  // Internal/MaxSampleSize (Cyclone 0.10.2 src/core/ddsi/include/dds/ddsi/ddsi_cfgelems.h,
  // default 2147483647 B): src/core/ddsi/src/q_receive.c, handle_Data and handle_DataFrag, compare
  // the sample size a DATA or DATA_FRAG submessage announces (for a fragment: the sampleSize of
  // its header, valid_DataFrag) with it before anything else is done with the payload, and
  // drop_oversize() discards it: no defragmentation buffer, no deserialisation, the receive
  // buffer's message is released when the datagram is done. So a peer can no longer make us
  // reassemble and hold a 64 MB string; every fragment of it costs one datagram's time. The same
  // bound applies to what we write (q_transmit.c, write_sample_eot: larger samples are not sent).
  return "<Internal><MaxSampleSize>" + std::to_string(kMaxSampleSizeBytes) + " B</MaxSampleSize></Internal>";
}

std::string max_auto_participant_index_element(int participants) {
  return "<MaxAutoParticipantIndex>" + std::to_string(participants) + "</MaxAutoParticipantIndex>";
}

}  // namespace

std::string resource_bounds_elements_xml() {
  // Each receive thread bump-allocates the messages it hands to a delivery queue through one
  // receive buffer and replaces the buffer when less than a chunk (128 KiB) is left (Cyclone 0.10
  // src/core/ddsi/src/q_radmin.c: nn_rbuf_alloc, commit_rmsg_chunk, nn_rbuf_release). With the
  // default 1 MiB buffer a hub's RSS climbs ~900 kB per receive thread with discovery and command
  // traffic, then falls back: 3 kB per planner reconnect for ~300 reconnects (docs/soak.md).
  // 192 KiB keeps that tooth at ~64 kB.
  return "<Sizing><ReceiveBufferSize>192 KiB</ReceiveBufferSize></Sizing>" + max_sample_size_element();
}

std::string loopback_config_xml() {
  // Cyclone 0.10.2 admits MaxAutoParticipantIndex participants per host, not one more: rtps_init
  // (src/core/ddsi/src/q_init.c) tries indices 0..max but refuses the last ("Failed to find a free
  // participant index": its loop counter is one past the index found), and the unicast peer list
  // covers indices 0..max-1 (src/core/ddsi/src/q_addrset.c, add_addresses_to_addrset_1). Each
  // participant sends its SPDP to every one of those ports at start and every SPDPInterval (30 s).
  // Port numbers above 65535 are not refused but wrap in the socket address (ddsi_ipaddr.c), so
  // domain 232, whose ports reach 65535 at index 62, gets its own, smaller bound: a second source,
  // as a Domain element with a numeric id must be the first data of its source and is skipped for
  // other domains (src/core/ddsi/src/ddsi_config.c, uf_domainId).
  return "<CycloneDDS><Domain id=\"any\">"
         "<General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
         "<AllowMulticast>false</AllowMulticast></General>"
         "<Discovery><ParticipantIndex>auto</ParticipantIndex>" +
         max_auto_participant_index_element(kLoopbackParticipantsPerHost) +
         "<Peers><Peer address=\"127.0.0.1\"/></Peers></Discovery>" + resource_bounds_elements_xml() +
         "</Domain></CycloneDDS>,<CycloneDDS><Domain id=\"" + std::to_string(kMaxDomainId) +
         "\"><Discovery>" + max_auto_participant_index_element(kLoopbackParticipantsInLastDomain) +
         "</Discovery></Domain></CycloneDDS>";
}

std::string sample_bounds_config_xml() {
  // The receive buffer bound too: with a station's configuration (CYCLONEDDS_URI, /etc/default/hubd)
  // a hub otherwise runs with Cyclone's 1 MiB default, three pools of which (one per receive
  // thread and socket kind, nn_rbufpool_new) it fills over time: heaptrack showed 3.15 MB of
  // hubd's heap there. A station configuration that sets Sizing/ReceiveBufferSize still wins.
  return "<CycloneDDS><Domain id=\"any\">" + resource_bounds_elements_xml() + "</Domain></CycloneDDS>";
}

std::string with_sample_bounds(std::string_view cyclone_xml) {
  std::string sources = sample_bounds_config_xml();
  std::string_view rest = cyclone_xml;
  // NOLINTNEXTLINE(concurrency-mt-unsafe): documented as not to be raced with setenv().
  const char* uri = rest.empty() ? std::getenv(kCycloneUriEnvVar) : nullptr;
  if (uri != nullptr) rest = uri;
  if (!rest.empty()) {
    // Cyclone reads a comma-separated list of sources in order, a later value of a setting
    // replacing an earlier one (ddsi_config.c: ddsi_config_init, do_update), so a station's
    // configuration may still set MaxSampleSize itself.
    sources += ',';
    sources += rest;
  }
  return sources;
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
