// The plant-wide tools' way onto the domains (`hubctl list/watch/record`): one domain as every
// command joins it, or several — `--domain 10-41`, or the stations of a plant file (`--plant
// plant.yaml`, plant_file.h) — each with a participant of its own, since a DDS participant lives
// in one domain (docs/plant.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <CLI/CLI.hpp>

#include "hubrt/base/status.h"
#include "hubrt/dds/participant.h"

#include "session.h"

namespace hubrt::hubctl {

struct PlantOptions {
  DomainOptions connection;  // --dds-config, --loopback, security, --timeout; for every domain alike
  std::string domains;       // --domain: one id or a set (domain_set.h); "" = $ROS_DOMAIN_ID or 0
  std::string plant_file;    // --plant
};
void add_plant_options(CLI::App& app, PlantOptions& options);

// One station of what the tool joined: its name ("" when the tool joined a single domain without
// a plant file: its topics keep their plain names) and its participant.
struct PlantMember {
  std::string station;
  dds::Participant participant;
};

// The stations to join, without joining: with --plant, the plant's stations (only those whose
// domain --domain names, when it is given too); with a --domain set of several ids, one station
// per id named "d<id>"; else one unnamed station in --domain, $ROS_DOMAIN_ID or 0. Errors
// (kInvalidArgument, kNotFound): the plant file's or the domain set's (plant_file.h,
// domain_set.h), a --domain that selects none of the plant's stations.
struct PlantChoice {
  std::string station;
  std::optional<std::uint32_t> domain_id;  // none: $ROS_DOMAIN_ID or 0
};
Expected<std::vector<PlantChoice>> choose_stations(const PlantOptions& options);

// Joins every chosen station's domain as `name` (join_domain: the same configuration, security
// and identity for each). Errors: choose_stations()'s, or the first domain that could not be
// joined (Cyclone's reason, naming the station and its domain).
Expected<std::vector<PlantMember>> join_plant(const PlantOptions& options, std::string_view name);

}  // namespace hubrt::hubctl
