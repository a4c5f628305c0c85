// A hubctl play scenario (YAML, or JSON, which YAML reads too) through load and parse: steps,
// conditions, repeats and includes. Named as if it sat in hubs/station/scenarios/, so includes
// of the real common/*.yaml resolve.
#include "scenario.h"

#include <cstddef>
#include <cstdint>
#include <string>

#include "hubrt/config/yaml_map.h"

#include "station_files.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string name = hubrt::fuzz::source_path("hubs/station/scenarios/fuzz.yaml");
  const std::string text(reinterpret_cast<const char*>(data), size);
  auto root = hubrt::config::YamlMap::load_string(text, name);
  if (!root) return 0;
  auto scenario = hubrt::hubctl::parse_scenario(*root);
  if (!scenario) return 0;
  for (const auto& step : scenario->steps) (void)step.describe();
  return 0;
}
