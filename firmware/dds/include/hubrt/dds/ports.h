// The UDP ports of a DDS domain and the kernel's ephemeral port range: a domain whose ports the
// kernel may hand to any socket bound to port 0 can be joined across domains (docs/deploy.md,
// "Choosing the domain id").
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace hubrt::dds {

// A range of UDP ports, both ends included.
struct PortRange {
  int first = 0;
  int last = 0;
};

// Linux's default net.ipv4.ip_local_port_range.
inline constexpr PortRange kLinuxDefaultEphemeralPorts{32768, 60999};

// Every UDP port a participant of `domain_id` may use under the DDSI default port mapping that
// Cyclone and Fast DDS share (7400 + 250 * id, up to the next domain's first port).
PortRange domain_port_band(std::uint32_t domain_id);

// The unicast discovery port of participant index `index` of `domain_id` under the same mapping
// (offset 10, participant gain 2); its unicast data port is the next one.
int unicast_discovery_port(std::uint32_t domain_id, int index);

// Whether the two ranges share no port.
bool disjoint(PortRange a, PortRange b);

// The text of /proc/sys/net/ipv4/ip_local_port_range ("32768\t60999"), or nullopt when it is not
// two ascending port numbers.
std::optional<PortRange> parse_port_range(std::string_view text);

// The ports the kernel hands to sockets bound to port 0 (net.ipv4.ip_local_port_range), or
// kLinuxDefaultEphemeralPorts when that file cannot be read or parsed.
PortRange ephemeral_port_range();

// Why a participant of `domain_id` may be joined from another domain on this host, or nullopt
// when its ports lie outside `ephemeral`.
//
// Cyclone 0.10 binds a transmit socket to port 0 and reads it, and takes a participant
// announcement that carries no domain id (Fast DDS 2.9's, Debian bookworm's) as
// one of its own domain. A Fast DDS planner announces itself to its domain's discovery ports; if
// a Cyclone process of any other domain on the host holds one of them as its transmit socket, the
// two match: that process reads the planner's commands. A domain outside the ephemeral range
// cannot be reached so.
std::optional<std::string> ephemeral_port_hazard(std::uint32_t domain_id, PortRange ephemeral);

}  // namespace hubrt::dds
