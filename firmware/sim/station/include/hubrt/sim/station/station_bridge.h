// The station model on DDS (what hubsim runs): it watches the three hubs' /sim/<hub>/signals,
// takes StationCommands from /sim/station/command, tells each hub the inputs the world gives it
// through /sim/input — only those that its signals show differently, again after a hold-off
// until they match, so a hub that starts late or restarts is brought in line — and publishes
// StationState on /sim/station/state. With a mobile platform configured it also reads the
// platform's State (the mir_com hub's) and tells the model where the kit is.
#pragma once

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <spdlog/logger.h>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/sim/sim_bridge_stage.h"
#include "hubrt/sim/station/station_model.h"

#include "station.h"

HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__StationCommand_, hub_msgs_msg_dds__StationCommand__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__StationState_, hub_msgs_msg_dds__StationState__desc);

namespace hubrt::sim::station {

class PlatformReader;

inline constexpr std::string_view kStationCommandTopic = "/sim/station/command";
inline constexpr std::string_view kStationStateTopic = "/sim/station/state";
// A hub whose signals have not arrived for this long counts as silent.
inline constexpr Duration kSilentAfter = std::chrono::seconds(1);
// A command is fresh, and a rejection shown, for this long.
inline constexpr Duration kCommandFreshFor = std::chrono::seconds(1);

// Not thread-safe: step() from one thread.
class StationBridge {
 public:
  // `model` must outlive the bridge. `ros_namespace` ("/cell_a", or "" for none) goes in front of
  // the station's simulation topics (sim_topic: the commands and State above, /sim/input and each
  // hub's signals), for a station that shares its DDS domain with others (docs/plant.md); the
  // mobile platform's State topic is the model's, as configured. Errors: the DDS entities (naming
  // the topic).
  static Expected<std::unique_ptr<StationBridge>> create(const dds::Participant& participant,
                                                         StationModel& model,
                                                         std::shared_ptr<spdlog::logger> log,
                                                         std::string_view ros_namespace = {});

  ~StationBridge();
  StationBridge(const StationBridge&) = delete;
  StationBridge& operator=(const StationBridge&) = delete;

  // One step at `now`: takes the hubs' signals, the mobile platform's State, the commands that arrived,
  // advances the model, sends the inputs the hubs lack, publishes the State.
  void step(const Instant& now);

  // Every wanted input shows in its hub's signals, and every hub is heard.
  [[nodiscard]] bool in_sync() const noexcept { return in_sync_; }

 private:
  struct HubView {
    std::string name;
    dds::Topic<hub_msgs_msg_dds__SimSignals_> topic;
    dds::Reader<hub_msgs_msg_dds__SimSignals_> reader;
    std::map<std::string, bool, std::less<>> levels;
    std::optional<Time> last_heard;
  };
  struct Sent {
    bool active = false;
    Time at{};
  };
  struct Echo {
    std::string target_type, target_name, action, location;
    friend bool operator==(const Echo&, const Echo&) = default;
  };
  struct Entities {
    std::array<std::unique_ptr<HubView>, kHubRoles> hubs;
    dds::Topic<hub_msgs_msg_dds__StationCommand_> command_topic;
    dds::Reader<hub_msgs_msg_dds__StationCommand_> command_reader;
    dds::Topic<hub_msgs_msg_dds__StationState_> state_topic;
    dds::Writer<hub_msgs_msg_dds__StationState_> state_writer;
    dds::Topic<hub_msgs_msg_dds__SimInput_> input_topic;
    dds::Writer<hub_msgs_msg_dds__SimInput_> input_writer;
    std::unique_ptr<PlatformReader> platform;  // null without a mobile platform configured
  };

  StationBridge(Entities entities, StationModel& model, std::shared_ptr<spdlog::logger> log);

  void take_signals(Time now);
  void take_platform(Time now);
  void take_commands(Time now);
  void on_command(Echo command, Time now);
  void reconcile(Time now);
  void publish(const Instant& now);
  [[nodiscard]] bool silent(const HubView& hub, Time now) const noexcept;

  Entities dds_;
  StationModel& model_;
  std::shared_ptr<spdlog::logger> log_;
  dds::Sample<hub_msgs_msg_dds__SimSignals_> signals_;
  dds::Sample<hub_msgs_msg_dds__StationCommand_> command_;
  std::map<std::pair<HubRole, std::string>, Sent> sent_;
  bool in_sync_ = false;

  std::optional<Echo> echo_;
  Time echo_since_{};
  Time last_command_{};
  std::string rejection_;
  Time rejected_at_{};
  std::uint64_t published_ = 0;
  std::optional<KitPlace> logged_kit_;
};

}  // namespace hubrt::sim::station
