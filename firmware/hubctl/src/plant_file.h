// The plant file: the stations of a plant and the DDS domain of each (docs/plant.md). The
// plant-wide tools read it (`hubctl watch --plant plant.yaml`) and show each station's topics
// under its name.
//
//   stations:
//     cell_a: {domain: 10}
//     cell_b: {network: stations/cell_b.yaml}    # its station file (hubctl net-config): its domain
//     cell_c: {domain: 12, network: stations/cell_c.yaml}   # both: they must agree
//
// A station's name becomes the first part of its topics' names in the tools (/cell_a/dock_ecu/dock/state),
// so it is a ROS name token: a letter, then letters, digits or '_'.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hubrt/base/status.h"

namespace hubrt::hubctl {

struct PlantStation {
  std::string name;
  std::uint32_t domain_id = 0;
  std::string network;  // the station file named, as written ("" when none)
  int line = 0;         // where the station is declared, for messages
};

struct PlantFile {
  std::string file;
  std::vector<PlantStation> stations;  // in file order
};

// Loads and checks a plant file. A `network:` path is relative to the plant file's folder.
// Errors (kInvalidArgument, located "file:line:column: key: ..." as YamlMap does; kNotFound for a
// missing file): bad YAML, unknown keys, no stations or more than kMaxPlantDomains, a name that is
// not a ROS name token (at most 63 characters), a station with neither domain nor network, a
// domain above dds::kMaxDomainId, a station file that does not load or whose domain differs from
// `domain:`, two stations with one domain.
Expected<PlantFile> load_plant_file(const std::string& path);
// The same for text in memory; `name` stands in for the file name, and `network:` paths are
// relative to its folder.
Expected<PlantFile> load_plant_file_string(const std::string& text, const std::string& name);

// True for a ROS name token of at most 63 characters: [A-Za-z][A-Za-z0-9_]*. Thread-safe.
bool is_station_name(std::string_view name) noexcept;

}  // namespace hubrt::hubctl
