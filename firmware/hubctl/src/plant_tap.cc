#include "plant_tap.h"

#include <fmt/format.h>

namespace hubrt::hubctl {
namespace {

// "/cell_a" + name, or the name alone for an unnamed station.
std::vector<std::string> named(const std::string& station, std::vector<std::string> names) {
  if (station.empty()) return names;
  for (std::string& name : names) name.insert(0, "/" + station);
  return names;
}

}  // namespace

Expected<std::unique_ptr<PlantTap>> PlantTap::start(const std::vector<PlantMember>& members,
                                                    const TapOptions& options) {
  std::unique_ptr<PlantTap> plant(new PlantTap());
  for (std::size_t k = 0; k < members.size(); ++k) {
    TapOptions station_options = options;
    station_options.station = members[k].station;
    station_options.first_topic_id = static_cast<std::uint32_t>(k) * kTopicIdsPerStation;
    auto tap = StationTap::start(members[k].participant, std::move(station_options));
    if (!tap) {
      if (members[k].station.empty()) return std::move(tap).error();
      return make_error(tap.error().code,
                        fmt::format("station '{}': {}", members[k].station, tap.error().message));
    }
    plant->stations_.push_back(members[k].station);
    plant->taps_.push_back(std::move(*tap));
  }
  return plant;
}

std::unique_ptr<TapSubscription> PlantTap::subscribe(std::size_t sample_capacity) {
  auto queue = std::make_shared<TapQueue>(sample_capacity);
  for (std::size_t k = 1; k < taps_.size(); ++k) queue->add_producer();
  for (const auto& tap : taps_) tap->feed(queue);
  return std::make_unique<TapSubscription>(std::move(queue));
}

std::vector<std::string> PlantTap::each_station(std::vector<std::string> (StationTap::*list)() const) const {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < taps_.size(); ++k) {
    auto names = named(stations_[k], ((*taps_[k]).*list)());
    out.insert(out.end(), names.begin(), names.end());
  }
  return out;
}

std::vector<std::string> PlantTap::written_topics() const {
  return each_station(&StationTap::written_topics);
}

std::vector<std::string> PlantTap::unknown_types() const {
  return each_station(&StationTap::unknown_types);
}

TapCounters PlantTap::counters() const {
  TapCounters total;
  for (const auto& tap : taps_) {
    const TapCounters c = tap->counters();
    total.samples += c.samples;
    total.bytes += c.bytes;
    total.topics += c.topics;
  }
  return total;
}

}  // namespace hubrt::hubctl
