// The interface a hub type implements (a folder under hubs/): what it needs from a board and how
// to build its nodes. The composition root (firmware/assembly) finds hub types by name in
// assembly::hub_types(); adding a hub type is adding a folder and one line to
// hubs/CMakeLists.txt, not touching hubd (docs/new-hub.md).
#pragma once

#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <spdlog/logger.h>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/config/hub_config.h"
#include "hubrt/dds/participant.h"
#include "hubrt/hal/backend.h"
#include "hubrt/hal/board/board_config.h"
#include "hubrt/hal/board/board_requirements.h"
#include "hubrt/runtime/cycle_runner.h"
#include "hubrt/runtime/hub.h"

namespace hubrt::hub_api {

class Subscriptions;
}  // namespace hubrt::hub_api

namespace hubrt::blackbox {
class BlackBox;
}  // namespace hubrt::blackbox

namespace hubrt::hub_api {

// Everything a hub type may use while building. References outlive the built hub.
struct HubContext {
  const config::HubConfig& config;
  const hal::BoardConfig& board;
  hal::Backend& backend;
  const dds::Participant& participant;
  runtime::Waker waker;  // wakes the cycle when a command arrives
  std::shared_ptr<spdlog::logger> log;
  // For opening devices at start and for the command sources' reading at each take (outlives the
  // built hub); the logic gets its time from the cycle.
  const Clock& clock;
  // Other hubs' States, by the names of the hub file's `subscriptions:` (outlive the built hub).
  Subscriptions& subscriptions;
  // The hub's black box, or null: the command readers and State writers show it their samples
  // (black_box_streams.h). Outlives the built hub.
  blackbox::BlackBox* black_box = nullptr;
};

// What HubType::stop_devices() did for one device.
struct DeviceStopReport {
  std::string device;  // the board's device name, e.g. "lift_drive"
  bool stopped = false;
  std::string message;  // what was done, or why it could not be
};

class HubType {
 public:
  virtual ~HubType() = default;
  [[nodiscard]] virtual std::string_view name() const noexcept = 0;
  // The signals, buses and devices the configured nodes use. Reads the node settings, so errors
  // there (file:line, what is wrong) come from here, before anything is opened.
  [[nodiscard]] virtual Expected<hal::BoardRequirements> requirements(
      const config::HubConfig& config) const = 0;
  // The rest of what build() would refuse in the configuration alone — message types of the
  // subscriptions, the hub layout's fields — without opening any device or joining DDS (what
  // `hubd --check` runs after requirements()). Errors: as build(), file and line.
  [[nodiscard]] virtual Expected<void> check(const config::HubConfig& /*config*/) const { return {}; }
  // Opens the devices and DDS endpoints and adds the nodes to `hub`. Errors name the node and the
  // device or topic that failed.
  [[nodiscard]] virtual Expected<void> build(const HubContext& context, runtime::Hub& hub) const = 0;
  // Best effort, once the hub's process has ended (`hubd --safe-outputs`, the unit's
  // ExecStopPost): tells the devices that would go on with their last command by themselves — a
  // motor drive on a bus — to stop, each call bounded by `timeout`. GPIO outputs are not this
  // function's: hubd drives them to their safe levels itself. None by default.
  [[nodiscard]] virtual std::vector<DeviceStopReport> stop_devices(const config::HubConfig& /*config*/,
                                                                   const hal::BoardConfig& /*board*/,
                                                                   hal::Backend& /*backend*/,
                                                                   Duration /*timeout*/) const {
    return {};
  }
};

}  // namespace hubrt::hub_api
