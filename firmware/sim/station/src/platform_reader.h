// The mobile platform's State as hubsim reads it (station.yaml's mobile_platform): the mir_com
// hub's RobotMoverState (node-type layout), or the field of its MirComState (hub layout).
#pragma once

#include <memory>
#include <optional>

#include "hubrt/base/status.h"
#include "hubrt/dds/participant.h"
#include "hubrt/sim/station/station_config.h"
#include "hubrt/sim/station/station_model.h"

namespace hubrt::sim::station {

// Not thread-safe: take() from one thread.
class PlatformReader {
 public:
  virtual ~PlatformReader() = default;
  // A reader of `config.state_topic` of the type `config.field` says. Errors: the DDS entities
  // (naming the topic).
  static Expected<std::unique_ptr<PlatformReader>> create(const dds::Participant& participant,
                                                          const MobilePlatformConfig& config);

  // The newest of the States that arrived since the last call (a bounded number is taken per
  // call), or nullopt when none did. The report's pose points into this reader until the next call.
  virtual std::optional<PlatformReport> take() = 0;

 protected:
  PlatformReader() = default;
};

}  // namespace hubrt::sim::station
