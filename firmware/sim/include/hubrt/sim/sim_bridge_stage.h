// Connects a hub's fake backend to the outside over DDS, so that a test, the demo or the station
// model (another process) can change the simulated world and watch the hub's outputs. It runs on
// the cycle thread (the fake GPIO belongs to it): inputs received are applied before the nodes
// step; the signals are published after periodic cycles.
#pragma once

#include <memory>
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
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__SimSignals_, hub_msgs_msg_dds__SimSignals__desc);

namespace hubrt::sim {

inline constexpr std::string_view kSimInputTopic = "/sim/input";
std::string sim_signals_topic(std::string_view hub);

class SimBridgeStage final : public runtime::CycleStage {
 public:
  // Publishes every input and output signal of `board`. Errors: the DDS entities.
  static Expected<std::unique_ptr<SimBridgeStage>> create(const dds::Participant& participant, std::string hub_name,
                                                          const hal::BoardConfig& board,
                                                          hal::fake::FakeBackend& fake,
                                                          std::shared_ptr<spdlog::logger> log);

  void before_nodes(const Instant& now) noexcept override;
  void after_nodes(const Instant& now, bool publish_all, bool took_effect) noexcept override;

  // Applies one input change as if it came over DDS. Returns false (and logs) for a signal that
  // is not a simulated input of this board.
  bool apply(std::string_view signal, bool active) noexcept;

 private:
  struct Signal {
    std::string name;
    bool output = false;
  };
  SimBridgeStage(dds::Topic<hub_msgs_msg_dds__SimInput_> input_topic,
                 dds::Reader<hub_msgs_msg_dds__SimInput_> reader,
                 dds::Topic<hub_msgs_msg_dds__SimSignals_> signals_topic,
                 dds::Writer<hub_msgs_msg_dds__SimSignals_> writer, std::string hub_name, std::vector<Signal> signals,
                 hal::fake::FakeBackend& fake, std::shared_ptr<spdlog::logger> log);

  dds::Topic<hub_msgs_msg_dds__SimInput_> input_topic_;
  dds::Reader<hub_msgs_msg_dds__SimInput_> reader_;
  dds::Topic<hub_msgs_msg_dds__SimSignals_> signals_topic_;
  dds::Writer<hub_msgs_msg_dds__SimSignals_> writer_;
  std::string hub_name_;
  std::vector<Signal> signals_;
  hal::fake::FakeBackend& fake_;
  std::shared_ptr<spdlog::logger> log_;
  dds::Sample<hub_msgs_msg_dds__SimInput_> input_;
  std::vector<hub_msgs_msg_dds__SimSignal_> wire_signals_;
  hub_msgs_msg_dds__SimSignals_ wire_{};
};

}  // namespace hubrt::sim
