// The DDS Security documents of a station, as text (the OMG DDS Security 1.1 schemas that
// Cyclone's access control plugin parses: src/security/builtin_plugins/access_control/src/
// access_control_parser.c in Cyclone 0.10.2, whose tests' etc/ folders hold examples).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace hubrt::security {

// The domain ids the documents cover: all Cyclone's access control accepts. Its parsers refuse a
// domain id above 230 (access_control_parser.c, governance_element_data_cb and
// permissions_element_data_cb: "value->value > 230"), so domains 231 and 232, which hubrt
// otherwise allows (dds::kMaxDomainId), cannot be secured.
inline constexpr int kFirstDomainId = 0;
inline constexpr int kLastDomainId = 230;

// The station's governance: for every domain, participants that cannot authenticate are not
// allowed (allow_unauthenticated_participants false) and join only with valid permissions
// (enable_join_access_control); discovery and liveliness are encrypted; for hubrt's topics
// (rt/*/command, rt/*/state, rt/*/*/state, rt/diagnostics, rt/sim/*) and any other topic, reading
// and writing are checked against the permissions, discovery and liveliness protected and the
// payload encrypted (data_protection_kind ENCRYPT).
std::string governance_xml();

// One participant's grant: who (the certificate subject), when, and which DDS topics (with the
// "rt/" ROS 2 prefix; '*' and '?' as fnmatch, '*' matching '/' as well: Cyclone's ac_fnmatch in
// access_control_utils.c) it may publish and subscribe. Everything else is denied.
struct Grant {
  std::string name;     // grant name, e.g. the identity
  std::string subject;  // e.g. "CN=dock_ecu,O=hubrt station"
  std::int64_t not_before_unix = 0;
  std::int64_t not_after_unix = 0;
  std::vector<std::string> publish;
  std::vector<std::string> subscribe;
  // The DDS domains it may join, ascending, each once, none above kLastDomainId; empty: every
  // domain the documents cover (kFirstDomainId to kLastDomainId). A plant with one domain per
  // station (docs/plant.md) keeps each station's identities to their station's domain.
  std::vector<std::uint32_t> domains;
};

std::string permissions_xml(const Grant& grant);

// `text` with &, <, >, " and ' escaped for XML.
std::string xml_escape(const std::string& text);

}  // namespace hubrt::security
