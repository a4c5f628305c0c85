#include "hubrt/dds/ports.h"

#include <charconv>
#include <fstream>
#include <iterator>

#include <fmt/format.h>

namespace hubrt::dds {

namespace {

// The DDSI default port mapping (Cyclone's Discovery/Ports defaults, Fast DDS's PortParameters).
constexpr int kPortBase = 7400;
constexpr int kDomainGain = 250;
constexpr int kUnicastDiscoveryOffset = 10;
constexpr int kParticipantGain = 2;
constexpr int kHighestPort = 65535;

// A decimal port number at the start of `text`, the rest of `text` after it.
std::optional<int> take_port(std::string_view& text) {
  const auto start = text.find_first_not_of(" \t");
  if (start == std::string_view::npos) return std::nullopt;
  text.remove_prefix(start);
  int port = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), port);
  if (error != std::errc{} || port < 1 || port > kHighestPort) return std::nullopt;
  text.remove_prefix(static_cast<std::size_t>(end - text.data()));
  return port;
}

}  // namespace

PortRange domain_port_band(std::uint32_t domain_id) {
  const int first = kPortBase + kDomainGain * static_cast<int>(domain_id);
  return PortRange{first, first + kDomainGain - 1};
}

int unicast_discovery_port(std::uint32_t domain_id, int index) {
  return domain_port_band(domain_id).first + kUnicastDiscoveryOffset + kParticipantGain * index;
}

bool disjoint(PortRange a, PortRange b) {
  return a.last < b.first || b.last < a.first;
}

std::optional<PortRange> parse_port_range(std::string_view text) {
  const auto first = take_port(text);
  if (!first) return std::nullopt;
  const auto last = take_port(text);
  if (!last || *last < *first) return std::nullopt;
  if (text.find_first_not_of(" \t\n") != std::string_view::npos) return std::nullopt;
  return PortRange{*first, *last};
}

PortRange ephemeral_port_range() {
  std::ifstream file("/proc/sys/net/ipv4/ip_local_port_range");
  const std::string text{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  return parse_port_range(text).value_or(kLinuxDefaultEphemeralPorts);
}

std::optional<std::string> ephemeral_port_hazard(std::uint32_t domain_id, PortRange ephemeral) {
  const PortRange band = domain_port_band(domain_id);
  if (disjoint(band, ephemeral)) return std::nullopt;
  // Short enough for one log line (hubd bounds them).
  return fmt::format(
      "DDS domain {}'s UDP ports {}-{} meet this host's ephemeral port range {}-{}: a Fast DDS planner of "
      "this domain can be matched from another domain on this host; choose a domain id outside that "
      "range (with Linux's default: 0-100 or 215-232) or use DDS Security (docs/deploy.md, \"Choosing "
      "the domain id\")",
      domain_id, band.first, band.last, ephemeral.first, ephemeral.last);
}

}  // namespace hubrt::dds
