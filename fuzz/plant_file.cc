// What a plant-wide tool is told (docs/plant.md): the --domain argument ("10-41", "3,5,7-9") and
// a plant file. Named as if it sat in hubs/station/, so a `network:` path can name the real
// station files next to it. An accepted domain set must read back the same after formatting;
// every station of an accepted plant file must have a station name and a domain of its own.
#include "plant_file.h"

#include <cstddef>
#include <cstdint>
#include <set>
#include <string>

#include "domain_set.h"
#include "station_files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (auto ids = hubrt::hubctl::parse_domain_set(text); ids) {
    auto again = hubrt::hubctl::parse_domain_set(hubrt::hubctl::format_domain_set(*ids));
    if (!again || *again != *ids) __builtin_trap();
  }
  static const std::string name = hubrt::fuzz::source_path("hubs/station/fuzz-plant.yaml");
  auto plant = hubrt::hubctl::load_plant_file_string(text, name);
  if (!plant) return 0;
  std::set<std::uint32_t> domains;
  for (const auto& station : plant->stations) {
    if (!hubrt::hubctl::is_station_name(station.name) || !domains.insert(station.domain_id).second)
      __builtin_trap();
  }
  return 0;
}
