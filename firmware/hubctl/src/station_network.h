// The station file of a station on several hosts: which host runs what, and at which address.
// `hubctl net-config` generates each host's Cyclone DDS configuration from it (net_config_xml.h);
// docs/deploy.md, "A station on several hosts".
//
//   domain: 0                  # DDS domain id of the station (ROS_DOMAIN_ID), default 0
//   spare_participants: 2      # hubctl & co. a host may run besides its processes, default 2
//   hosts:
//     planner-pc: {address: 10.8.0.1, runs: [planner]}
//     tool-pi:    {address: 10.8.0.11, interface: wg0, runs: [tool_ecu]}
//
// `runs` names the station's processes: `planner` (hubctl play or Sequence Planner), `hubsim`, or
// a hub instance name (the `name:` of its hub file, e.g. tool_ecu). Each runs on one host only.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hubrt/base/status.h"

namespace hubrt::hubctl {

struct StationHost {
  std::string name;
  std::string address;    // IPv4, dotted quad
  std::string interface;  // empty: the interface that carries `address`
  std::vector<std::string> runs;
  int line = 0;  // where the host is declared, for messages
};

struct StationNetwork {
  std::string file;
  std::uint32_t domain_id = 0;
  int spare_participants = 2;
  std::vector<StationHost> hosts;  // in file order

  // The host named `name`, or nullptr.
  [[nodiscard]] const StationHost* find(std::string_view name) const;
  // The host names, comma-separated, for messages.
  [[nodiscard]] std::string host_names() const;

  // Cyclone gives each process (one DDSI instance per domain) a participant index, probing from 0
  // upwards on its host (Discovery/ParticipantIndex auto), and sends discovery to every peer
  // address once per index below Discovery/MaxAutoParticipantIndex: the indices must cover the
  // busiest host's processes plus its spare participants, on every host alike. The highest index
  // a process may take (MaxAutoParticipantIndex is one more: net_config_xml.cc).
  [[nodiscard]] int max_participant_index() const;
  // The UDP ports the station uses, on every host (Cyclone 0.10.2
  // docs/manual/config/cyclonedds_specifics.rst, "Controlling Port Numbers", with the DDSI
  // defaults: B = 7400 + 250 * domain; participant index i listens on B + 10 + 2i (discovery) and
  // B + 11 + 2i (data); B and B + 1 are the multicast ports, unused here).
  [[nodiscard]] int first_unicast_port() const;
  [[nodiscard]] int last_unicast_port() const;
};

// Loads and checks a station file. Errors (kInvalidArgument, located "file:line:column: key: ..."
// as YamlMap does; kNotFound for a missing file): bad YAML, unknown keys, no hosts, a host name
// that is not a short name (letters, digits, '-', '_'), an address that is not an IPv4 address or
// is used by two hosts, a bad interface name, a process that is not a name or runs on two hosts,
// a domain id or participant count whose UDP ports would not fit (docs/deploy.md, the ports).
Expected<StationNetwork> load_station_network(const std::string& path);
// The same for text in memory; `name` stands in for the file name in messages.
Expected<StationNetwork> load_station_network_string(const std::string& text, const std::string& name);

}  // namespace hubrt::hubctl
