// Connects a hub's fake backend to the outside over DDS, so that a test, the demo or the station
// model (another process) can change the simulated world and watch the hub's outputs. It runs on
// the cycle thread (the fake GPIO belongs to it): inputs and faults received are applied before
// the nodes step; the signals are published after periodic cycles.
#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/hal/board/board_config.h"
#include "hubrt/hal/fake/fake_backend.h"
#include "hubrt/runtime/hub.h"

#include "sim.h"

HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__SimInput_, hub_msgs_msg_dds__SimInput__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__SimBadge_, hub_msgs_msg_dds__SimBadge__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__SimFault_, hub_msgs_msg_dds__SimFault__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__SimSignals_, hub_msgs_msg_dds__SimSignals__desc);

namespace hubrt::sim {

inline constexpr std::string_view kSimInputTopic = "/sim/input";
inline constexpr std::string_view kSimBadgeTopic = "/sim/badge";
inline constexpr std::string_view kSimFaultTopic = "/sim/fault";
std::string sim_signals_topic(std::string_view hub);
// A simulation topic of a station under a ROS namespace ("/cell_a": "/cell_a/sim/input"; "": the
// topic as it is). A plant whose stations share one DDS domain gives each station a namespace
// (docs/plant.md): its hubs' (`namespace:` in the hub file), its hubsim's (`--namespace`) and its
// planner's (`hubctl play --namespace`), so that no station's simulation reaches another's hubs.
std::string sim_topic(std::string_view ros_namespace, std::string_view topic);
// The signals are published after a periodic cycle when one changed, when a new reader matched,
// and otherwise at least this often (the station model takes a hub silent for a second as gone:
// station_bridge.h, kSilentAfter) — but only while a reader is matched: with nobody listening they
// are not even read, and a reader that matches gets them at the next periodic cycle. Unchanged
// signals are not written every cycle: at 1 kHz that was a second DDS write per cycle beside the
// State.
inline constexpr Duration kSimSignalsKeepAlive = std::chrono::milliseconds(100);

class SimBridgeStage final : public runtime::CycleStage {
 public:
  // Publishes every input and output signal of `board`, its valves and its lift drives (when they
  // change; see kSimSignalsKeepAlive).
  // Errors: the DDS entities.
  static Expected<std::unique_ptr<SimBridgeStage>> create(const dds::Participant& participant,
                                                          std::string hub_name, const hal::BoardConfig& board,
                                                          hal::fake::FakeBackend& fake,
                                                          std::shared_ptr<spdlog::logger> log);

  // The stage's DDS side alone (needs no backend): hubd opens it while its start-up twin check
  // runs (Simulation::prepare_bridge). Nothing is published until the stage runs.
  struct Entities {
    // Something arrived on one of the three readers since the last look (their listener sets it).
    std::shared_ptr<std::atomic<bool>> pending;
    dds::Topic<hub_msgs_msg_dds__SimInput_> input_topic;
    dds::Reader<hub_msgs_msg_dds__SimInput_> input_reader;
    dds::Topic<hub_msgs_msg_dds__SimFault_> fault_topic;
    dds::Reader<hub_msgs_msg_dds__SimFault_> fault_reader;
    dds::Topic<hub_msgs_msg_dds__SimBadge_> badge_topic;
    dds::Reader<hub_msgs_msg_dds__SimBadge_> badge_reader;
    dds::Topic<hub_msgs_msg_dds__SimSignals_> signals_topic;
    dds::Writer<hub_msgs_msg_dds__SimSignals_> signals_writer;
  };
  // Errors: the DDS entities.
  // `ros_namespace`: the hub's (its hub file's `namespace:`), in front of every topic (sim_topic).
  static Expected<Entities> open_entities(const dds::Participant& participant, const std::string& hub_name,
                                          std::string_view ros_namespace = {});
  // As create() above, on entities opened before. Never fails.
  static std::unique_ptr<SimBridgeStage> create(Entities entities, std::string hub_name,
                                                const hal::BoardConfig& board, hal::fake::FakeBackend& fake,
                                                std::shared_ptr<spdlog::logger> log);

  void before_nodes(const Instant& now) noexcept override;
  void after_nodes(const Instant& now, bool publish_all, bool took_effect) noexcept override;
  // Publishes the signals once more, after the hub drove its outputs safe on the way out.
  void after_safe_state(const Instant& now) noexcept override;

  // Applies one input change as if it came over DDS. Returns false (and logs) for a signal that
  // is not a simulated input of this board.
  bool apply(std::string_view signal, bool active) noexcept;

 private:
  struct Signal {
    std::string name;
    bool output = false;
    // Resolved once (board lookup by name, chip by name): reading it by name every cycle was most
    // of a simulated hub's cycle (callgrind). Chips are never removed from the fake GPIO, so the
    // pointer stays valid; unresolved (chip missing at start) reads by name.
    std::optional<hal::fake::FakeBackend::Wiring> wiring;
  };
  SimBridgeStage(Entities entities, std::string hub_name, const hal::BoardConfig& board,
                 hal::fake::FakeBackend& fake, std::shared_ptr<spdlog::logger> log);
  void apply_fault(const hub_msgs_msg_dds__SimFault_& fault, Time now) noexcept;
  // Reads the signals into the wire sample; true when one differs from what was last written.
  bool read_signals(const Instant& now) noexcept;
  void write_signals(const Instant& now) noexcept;

  Entities dds_;
  std::string hub_name_;
  const hal::BoardConfig& board_;
  std::vector<Signal> signals_;
  std::vector<std::string> valves_;  // output signals of the simulated valves
  std::vector<std::string> lifts_;   // Modbus devices with a lift drive simulator
  hal::fake::FakeBackend& fake_;
  std::shared_ptr<spdlog::logger> log_;
  std::optional<Time> last_written_;  // monotonic time of the last signals sample
  dds::Sample<hub_msgs_msg_dds__SimInput_> input_;
  dds::Sample<hub_msgs_msg_dds__SimFault_> fault_;
  dds::Sample<hub_msgs_msg_dds__SimBadge_> badge_;
  std::vector<hub_msgs_msg_dds__SimSignal_> wire_signals_;
  std::vector<hub_msgs_msg_dds__SimValve_> wire_valves_;
  std::vector<hub_msgs_msg_dds__SimLift_> wire_lifts_;
  hub_msgs_msg_dds__SimSignals_ wire_{};
};

}  // namespace hubrt::sim
