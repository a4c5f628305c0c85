#include "station_network.h"

#include <algorithm>
#include <map>

#include <arpa/inet.h>
#include <fmt/format.h>

#include "hubrt/config/yaml_map.h"
#include "hubrt/dds/ports.h"

namespace hubrt::hubctl {
namespace {

// Cyclone refuses participant indices of 120 and more (0.10.2 docs/manual/options.md,
// Discovery/ParticipantIndex: "a non-negative integer less than 120").
constexpr int kMaxCycloneParticipantIndex = 119;
constexpr int kMaxUdpPort = 65535;
constexpr std::size_t kMaxPlainNameLength = 63;

bool is_plain_name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
}

// Host and process names go into XML comments and namespace names: short, plain, no "--" (which
// an XML comment may not contain).
bool is_plain_name(std::string_view name) {
  return !name.empty() && name.size() <= kMaxPlainNameLength &&
         std::all_of(name.begin(), name.end(), is_plain_name_char) &&
         name.find("--") == std::string_view::npos && name.front() != '-';
}

// Linux interface names: at most 15 bytes (IFNAMSIZ - 1), no '/', no blanks; kept to what
// is_plain_name_char allows plus '.' and ':' (VLANs, aliases).
bool is_interface_name(std::string_view name) {
  return !name.empty() && name.size() <= 15 && std::all_of(name.begin(), name.end(), [](char c) {
    return is_plain_name_char(c) || c == '.' || c == ':';
  });
}

bool is_ipv4(const std::string& text) {
  in_addr parsed{};
  return inet_pton(AF_INET, text.c_str(), &parsed) == 1;
}

Expected<StationHost> load_host(const std::string& name, const config::YamlMap& map) {
  StationHost host;
  host.name = name;
  host.line = static_cast<int>(map.node().Mark().line) + 1;
  if (!is_plain_name(name)) {
    return map.error(fmt::format("host name '{}' must be 1 to {} letters, digits, '-' or '_' (not '--')",
                                 name, kMaxPlainNameLength));
  }
  if (auto ok = map.only_keys({"address", "interface", "runs"}); !ok) return std::move(ok).error();
  auto address = map.string("address");
  if (!address) return std::move(address).error();
  if (!is_ipv4(*address)) {
    return map.error_at("address", fmt::format("'{}' is not an IPv4 address (e.g. 10.8.0.11)", *address));
  }
  host.address = *address;
  auto interface = map.string_or("interface", "");
  if (!interface) return std::move(interface).error();
  if (!interface->empty() && !is_interface_name(*interface)) {
    return map.error_at("interface", fmt::format("'{}' is not a network interface name", *interface));
  }
  host.interface = *interface;
  auto runs = map.list_of_strings("runs", /*optional=*/true);
  if (!runs) return std::move(runs).error();
  for (const std::string& process : *runs) {
    if (!is_plain_name(process)) {
      return map.error_at(
          "runs", fmt::format("'{}' is not a process name (planner, hubsim or a hub's name)", process));
    }
  }
  host.runs = *runs;
  return host;
}

// Two hosts with one address, or one process on two hosts.
Expected<void> check_unique(const config::YamlMap& hosts_map, const std::vector<StationHost>& hosts) {
  std::map<std::string, const StationHost*> by_address;
  std::map<std::string, const StationHost*> by_process;
  for (const StationHost& host : hosts) {
    auto host_map = hosts_map.map(host.name);
    if (!host_map) return std::move(host_map).error();
    const auto [at, inserted] = by_address.emplace(host.address, &host);
    if (!inserted) {
      return host_map->error_at("address", fmt::format("{} is also the address of host '{}' (line {})",
                                                       host.address, at->second->name, at->second->line));
    }
    for (const std::string& process : host.runs) {
      const auto [where, added] = by_process.emplace(process, &host);
      if (!added) {
        return host_map->error_at(
            "runs", fmt::format("'{}' already runs on host '{}' (line {}): a process runs on one host only",
                                process, where->second->name, where->second->line));
      }
    }
  }
  return {};
}

}  // namespace

const StationHost* StationNetwork::find(std::string_view name) const {
  for (const StationHost& host : hosts) {
    if (host.name == name) return &host;
  }
  return nullptr;
}

std::string StationNetwork::host_names() const {
  std::string names;
  for (const StationHost& host : hosts) names += (names.empty() ? "" : ", ") + host.name;
  return names;
}

int StationNetwork::max_participant_index() const {
  std::size_t busiest = 0;
  for (const StationHost& host : hosts) busiest = std::max(busiest, host.runs.size());
  return std::max(0, static_cast<int>(busiest) + spare_participants - 1);
}

int StationNetwork::first_unicast_port() const {
  return dds::unicast_discovery_port(domain_id, 0);
}

int StationNetwork::last_unicast_port() const {
  return first_unicast_port() + 1 + 2 * max_participant_index();
}

namespace {

// The station of a loaded document.
Expected<StationNetwork> station_from_root(const Expected<config::YamlMap>& root) {
  if (!root) return root.error();
  if (auto ok = root->only_keys({"domain", "spare_participants", "hosts"}); !ok) return std::move(ok).error();
  StationNetwork station;
  station.file = root->file();
  // 232: the highest domain id whose ports fit (dds::kMaxDomainId); checked again below with the
  // participant indices.
  auto domain = root->integer_or("domain", 0, 0, 232);
  if (!domain) return std::move(domain).error();
  station.domain_id = static_cast<std::uint32_t>(*domain);
  auto spare = root->integer_or("spare_participants", 2, 0, kMaxCycloneParticipantIndex);
  if (!spare) return std::move(spare).error();
  station.spare_participants = static_cast<int>(*spare);
  auto hosts = root->named_maps("hosts");
  if (!hosts) return std::move(hosts).error();
  if (hosts->empty()) return root->error_at("hosts", "lists no host");
  for (const auto& [host_name, host_map] : *hosts) {
    auto host = load_host(host_name, host_map);
    if (!host) return std::move(host).error();
    station.hosts.push_back(std::move(*host));
  }
  auto hosts_map = root->map("hosts");
  if (!hosts_map) return std::move(hosts_map).error();
  if (auto ok = check_unique(*hosts_map, station.hosts); !ok) return std::move(ok).error();
  if (station.max_participant_index() > kMaxCycloneParticipantIndex) {
    return root->error_at("hosts",
                          fmt::format("a host would need participant index {}; Cyclone allows up to {}",
                                      station.max_participant_index(), kMaxCycloneParticipantIndex));
  }
  if (station.last_unicast_port() > kMaxUdpPort) {
    return root->error_at(
        "domain",
        fmt::format("domain {} with participant indices up to {} needs UDP port {} (> {})", station.domain_id,
                    station.max_participant_index(), station.last_unicast_port(), kMaxUdpPort));
  }
  return station;
}

}  // namespace

Expected<StationNetwork> load_station_network_string(const std::string& text, const std::string& name) {
  return station_from_root(config::YamlMap::load_string(text, name));
}

Expected<StationNetwork> load_station_network(const std::string& path) {
  return station_from_root(config::YamlMap::load_file(path));
}

}  // namespace hubrt::hubctl
