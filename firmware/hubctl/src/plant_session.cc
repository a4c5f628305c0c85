#include "plant_session.h"

#include <algorithm>

#include <fmt/format.h>

#include "domain_set.h"
#include "plant_file.h"

namespace hubrt::hubctl {

void add_plant_options(CLI::App& app, PlantOptions& options) {
  app.add_option("--domain", options.domains,
                 "DDS domain id, or several stations' domains at once: 10-41, 3,5,7-9 (one participant "
                 "each; their topics shown as /d<id>/...; default: $ROS_DOMAIN_ID or 0)");
  app.add_option("--plant", options.plant_file,
                 "Plant file: the stations and their domains (docs/plant.md); each station's topics "
                 "shown as /<station>/...; with --domain, only the stations in those domains");
  add_connection_options(app, options.connection);
}

Expected<std::vector<PlantChoice>> choose_stations(const PlantOptions& options) {
  std::vector<std::uint32_t> ids;
  if (!options.domains.empty()) {
    auto parsed = parse_domain_set(options.domains);
    if (!parsed) return std::move(parsed).error();
    ids = std::move(*parsed);
  }
  std::vector<PlantChoice> chosen;
  if (!options.plant_file.empty()) {
    auto plant = load_plant_file(options.plant_file);
    if (!plant) return std::move(plant).error();
    for (const PlantStation& station : plant->stations) {
      if (ids.empty() || std::binary_search(ids.begin(), ids.end(), station.domain_id))
        chosen.push_back({station.name, station.domain_id});
    }
    if (chosen.empty()) {
      return make_error(ErrorCode::kNotFound,
                        fmt::format("{}: no station in domain(s) {}", plant->file, format_domain_set(ids)));
    }
    return chosen;
  }
  if (ids.size() <= 1) {
    chosen.push_back({"", ids.empty() ? std::nullopt : std::optional<std::uint32_t>(ids.front())});
    return chosen;
  }
  for (const std::uint32_t id : ids) chosen.push_back({fmt::format("d{}", id), id});
  return chosen;
}

Expected<std::vector<PlantMember>> join_plant(const PlantOptions& options, std::string_view name) {
  auto chosen = choose_stations(options);
  if (!chosen) return std::move(chosen).error();
  std::vector<PlantMember> members;
  members.reserve(chosen->size());
  for (const PlantChoice& choice : *chosen) {
    DomainOptions domain = options.connection;
    domain.domain = choice.domain_id;
    auto participant = join_domain(domain, name);
    if (!participant) {
      if (choice.station.empty()) return std::move(participant).error();
      return make_error(participant.error().code,
                        fmt::format("station '{}': {}", choice.station, participant.error().message));
    }
    members.push_back({choice.station, std::move(*participant)});
  }
  return members;
}

}  // namespace hubrt::hubctl
