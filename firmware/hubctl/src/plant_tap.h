// The tap (tap.h) over several stations' domains: one StationTap per station (plant_session.h),
// all feeding each consumer's one queue, every topic named after its station
// ("/cell_a/dock_ecu/dock/state") and numbered apart. With one unnamed station it is that
// station's tap, topics as they are. `hubctl watch` and `hubctl record` read it, so both work
// across a plant's domains as they do on one.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "hubrt/base/status.h"

#include "plant_session.h"
#include "station_tap.h"

namespace hubrt::hubctl {

class PlantTap {
 public:
  // Topic ids of station k start at k * kTopicIdsPerStation.
  static constexpr std::uint32_t kTopicIdsPerStation = 1U << 16;

  // Starts one tap per member with `options` (its station and first topic id set per member).
  // The members must outlive the tap. Errors: the first tap that could not start, naming its
  // station.
  static Expected<std::unique_ptr<PlantTap>> start(const std::vector<PlantMember>& members,
                                                   const TapOptions& options);

  // A consumer of every station's events, in one queue of at most `sample_capacity` samples; it
  // is finished once every station's tap has ended. Thread-safe.
  std::unique_ptr<TapSubscription> subscribe(std::size_t sample_capacity);
  // Every station's, their names in front as in the topics. Thread-safe.
  [[nodiscard]] std::vector<std::string> written_topics() const;
  [[nodiscard]] std::vector<std::string> unknown_types() const;
  [[nodiscard]] TapCounters counters() const;

 private:
  PlantTap() = default;
  // `list` of every station's tap, each name under its station's (as the topics are).
  std::vector<std::string> each_station(std::vector<std::string> (StationTap::*list)() const) const;
  std::vector<std::string> stations_;
  std::vector<std::unique_ptr<StationTap>> taps_;
};

}  // namespace hubrt::hubctl
