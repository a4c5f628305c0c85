#include "plant_file.h"

#include <filesystem>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/config/yaml_map.h"
#include "hubrt/dds/domain.h"

#include "domain_set.h"
#include "station_network.h"

namespace hubrt::hubctl {
namespace {

constexpr std::size_t kMaxStationNameLength = 63;

// The station's domain from `domain:`, from its station file, or both (then they must agree).
Expected<std::uint32_t> station_domain(const config::YamlMap& map, const std::string& network,
                                       const std::filesystem::path& base) {
  std::optional<std::uint32_t> domain;
  if (map.has("domain")) {
    auto value = map.integer("domain", 0, dds::kMaxDomainId);
    if (!value) return std::move(value).error();
    domain = static_cast<std::uint32_t>(*value);
  }
  if (!network.empty()) {
    const auto path =
        std::filesystem::path(network).is_absolute() ? std::filesystem::path(network) : base / network;
    auto station = load_station_network(path.string());
    if (!station) return map.error_at("network", station.error().message);
    if (domain && *domain != station->domain_id) {
      return map.error_at("domain", fmt::format("{} differs from the domain of its station file {} ({})",
                                                *domain, network, station->domain_id));
    }
    domain = station->domain_id;
  }
  if (!domain) return map.error("names neither a domain nor a station file (network:)");
  return *domain;
}

Expected<PlantFile> plant_from_root(const Expected<config::YamlMap>& root) {
  if (!root) return root.error();
  if (auto ok = root->only_keys({"stations"}); !ok) return std::move(ok).error();
  PlantFile plant;
  plant.file = root->file();
  const auto base = std::filesystem::path(plant.file).parent_path();
  auto stations = root->named_maps("stations");
  if (!stations) return std::move(stations).error();
  if (stations->empty()) return root->error_at("stations", "lists no station");
  if (stations->size() > kMaxPlantDomains) {
    return root->error_at("stations", fmt::format("{} stations: a tool joins at most {} domains",
                                                  stations->size(), kMaxPlantDomains));
  }
  std::map<std::uint32_t, const PlantStation*> by_domain;
  plant.stations.reserve(stations->size());
  for (const auto& [name, map] : *stations) {
    if (!is_station_name(name)) {
      return map.error(fmt::format(
          "station name '{}' must be a letter, then up to {} letters, digits or '_' (it names the "
          "station's topics in the tools)",
          name, kMaxStationNameLength - 1));
    }
    if (auto ok = map.only_keys({"domain", "network"}); !ok) return std::move(ok).error();
    auto network = map.string_or("network", "");
    if (!network) return std::move(network).error();
    auto domain = station_domain(map, *network, base);
    if (!domain) return std::move(domain).error();
    PlantStation station{name, *domain, *network, static_cast<int>(map.node().Mark().line) + 1};
    plant.stations.push_back(std::move(station));
    const auto [at, inserted] = by_domain.emplace(*domain, &plant.stations.back());
    if (!inserted) {
      return map.error(
          fmt::format("domain {} is also the domain of station '{}' (line {}): one domain per station",
                      *domain, at->second->name, at->second->line));
    }
  }
  return plant;
}

}  // namespace

bool is_station_name(std::string_view name) noexcept {
  return name.size() <= kMaxStationNameLength && config::is_ros_name_token(name);
}

Expected<PlantFile> load_plant_file(const std::string& path) {
  return plant_from_root(config::YamlMap::load_file(path));
}

Expected<PlantFile> load_plant_file_string(const std::string& text, const std::string& name) {
  return plant_from_root(config::YamlMap::load_string(text, name));
}

}  // namespace hubrt::hubctl
