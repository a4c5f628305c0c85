// Which DDS domain a participant joins and with which Cyclone configuration.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "hubrt/base/status.h"

namespace hubrt::dds {

// The domain id and the Cyclone XML configuration for a participant.
//   cyclone_xml empty     -> Cyclone's defaults, or whatever CYCLONEDDS_URI says.
//   cyclone_xml non-empty -> this configuration (XML fragments or file URIs, as CYCLONEDDS_URI
//                            accepts), applied by creating the domain explicitly.
// Cyclone keeps one configuration per domain per process: the first participant that creates a
// domain decides its configuration, and later participants in the same process and domain share
// it whatever their cyclone_xml says, until every participant of that domain is gone.
struct DomainConfig {
  std::uint32_t domain_id = 0;
  std::string cyclone_xml;
};

// Highest domain id usable with Cyclone's default port mapping (7400 + 250 * id + offsets must
// stay below 65536).
inline constexpr std::uint32_t kMaxDomainId = 232;

// How many participants (processes) of one domain loopback_config_xml() admits on the host: 64
// hubs, hubctl, a planner and room for more (Cyclone's default MaxAutoParticipantIndex of 9 admits
// 9). Domain kMaxDomainId admits kLoopbackParticipantsInLastDomain: its port numbers end at 65535.
inline constexpr int kLoopbackParticipantsPerHost = 100;
inline constexpr int kLoopbackParticipantsInLastDomain = 63;

// The configuration that keeps a participant on the loopback interface: interface "lo", no
// multicast, unicast discovery to 127.0.0.1 with automatic participant indices (up to
// kLoopbackParticipantsPerHost participants on the host), a 192 KiB
// receive buffer instead of 1 MiB (bounds the RSS saw-tooth of incoming traffic: docs/soak.md),
// and sample_bounds_config_xml().
// Valid for any domain id. Used by tests and by single-machine demos. Thread-safe.
std::string loopback_config_xml();

// What every configuration hubrt writes carries inside its <Domain>, whatever the network: a
// 192 KiB receive buffer instead of 1 MiB (bounds the RSS saw-tooth of incoming traffic:
// docs/soak.md) and sample_bounds_config_xml()'s Internal/MaxSampleSize. Used by
// loopback_config_xml() and by `hubctl net-config` (a station on several hosts). Thread-safe.
std::string resource_bounds_elements_xml();

// The largest serialised sample a hubrt process sends or accepts. The largest legitimate one is
// a hub-layout State with every error list full (Tool ECU: three lists of 16 entries of up to 191
// bytes, ~9.4 KiB, ~12 KiB in all) or a /diagnostics array (~1.7 KiB per node): 64 KiB leaves
// more than 5x that. README.md, "The wire contract".
inline constexpr std::uint32_t kMaxSampleSizeBytes = 64 * 1024;

// A Cyclone XML source that sets Internal/MaxSampleSize to kMaxSampleSizeBytes: Cyclone then
// discards larger incoming samples on their first datagram, before reassembling them, with a
// warning that dds/oversize_samples.h counts. Thread-safe.
std::string sample_bounds_config_xml();

// sample_bounds_config_xml() followed by `cyclone_xml`, or when that is empty by the value of
// $CYCLONEDDS_URI (nothing when unset): the configuration hubd creates its domain with, so that
// every hub is bounded whatever the station's configuration says, unless that configuration sets
// MaxSampleSize itself (a later source overrides an earlier one).
// Thread-safety: reads the environment; do not call while another thread calls setenv().
std::string with_sample_bounds(std::string_view cyclone_xml);

// The environment variable from which Cyclone reads its configuration.
inline constexpr const char* kCycloneUriEnvVar = "CYCLONEDDS_URI";

// The environment variable that carries the domain id to hubd and hubctl, as in ROS 2.
inline constexpr const char* kDomainIdEnvVar = "ROS_DOMAIN_ID";

// DomainConfig from the process environment: domain id from ROS_DOMAIN_ID (0 when unset), empty
// cyclone_xml so that Cyclone itself reads CYCLONEDDS_URI.
// Errors: kInvalidArgument naming the variable and its value when ROS_DOMAIN_ID is not an integer
// in 0..kMaxDomainId.
// Thread-safety: reads the environment; do not call while another thread calls setenv().
Expected<DomainConfig> domain_config_from_environment();

}  // namespace hubrt::dds
