// The DDS side of a `hubctl play` run: the State topics it reads (latest sample as JSON, and how
// many have arrived), the commands it keeps sending the way the planner does (each again and
// again at the scenario's rate until replaced), where hubs and nodes are, and writers matched with
// their readers before anything is written. The steps (scenario_steps.h) use it; it knows nothing
// of steps.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include <nlohmann/json.hpp>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/type_info.h"

#include "node_locator.h"
#include "sample_decoder.h"
#include "scenario.h"

namespace hubrt::hubctl {

using SteadyClock = std::chrono::steady_clock;

inline constexpr std::string_view kStationStateTopic = "/sim/station/state";
inline constexpr std::string_view kStationCommandTopic = "/sim/station/command";
inline constexpr std::string_view kSimInputTopic = "/sim/input";
inline constexpr std::string_view kSimBadgeTopic = "/sim/badge";
inline constexpr std::string_view kInstructionTopic = "/operator/instruction";
inline constexpr std::string_view kSimFaultTopic = "/sim/fault";
// How often the loop looks for samples and due commands while a step runs.
inline constexpr auto kPoll = std::chrono::milliseconds(5);

// A State topic being read: the latest sample, as JSON, and how many have arrived.
struct StateChannel {
  std::string topic;
  const msgs::TypeInfo* type = nullptr;
  std::optional<dds::UntypedTopic> dds_topic;
  std::optional<dds::UntypedReader> reader;
  std::optional<dds::UntypedSample> sample;
  std::optional<SampleDecoder> decoder;
  nlohmann::ordered_json latest;
  std::uint64_t generation = 0;
  SteadyClock::time_point received_at{};
};

struct WriterEntry {
  std::optional<dds::UntypedTopic> topic;
  std::optional<dds::UntypedWriter> writer;
};

// A command the planner keeps sending: one node's (node-type layout) or one hub's, with the
// fragments of every node commanded so far (hub layout).
struct Plan {
  std::string hub;
  NodeEndpoints endpoints;
  std::map<std::string, nlohmann::ordered_json> fragments;  // node -> its command
  std::optional<dds::UntypedSample> sample;
  WriterEntry* writer = nullptr;
};

// Not thread-safe; one run at a time. Every wait ends early on Ctrl-C (stop_requested()).
class ScenarioTraffic {
 public:
  // `participant` must outlive this. `period`: how often each plan is sent again.
  // `command_lifespan_ms`: the LIFESPAN of command writers (command_writer(); 0: none).
  // `ros_namespace` ("" or "/cell_a"): the station's; its hubs are looked for under it and the
  // station's other topics (station_topic()) are under it too.
  ScenarioTraffic(const dds::Participant& participant, Duration discovery_timeout, Duration period,
                  std::uint32_t command_lifespan_ms, std::string ros_namespace = {});

  // The rate's clock starts now: the first resend of a plan is due at once.
  void start() { next_send_ = SteadyClock::now(); }
  // The loop: samples in, due commands out. Call often (every kPoll) while a step runs.
  void pump();
  // pump() for `span`, or until Ctrl-C.
  void pump_for(Duration span);
  // Sends `plan` now (a new command goes out at once, then at the rate).
  static void send(Plan& plan);
  // The commands sent at the rate, by hub (hub layout) or hub/node (node-type layout).
  std::map<std::string, Plan>& plans() { return plans_; }

  // A topic of this station that is no hub's (kSimInputTopic, kInstructionTopic, ...): under the
  // station's namespace.
  [[nodiscard]] std::string station_topic(std::string_view topic) const {
    return ros_namespace_ + std::string(topic);
  }

  // Where `target` is (looked up once, then remembered). Errors: as find_node.
  Expected<NodeEndpoints> locate(const StepTarget& target);
  // Errors: kNotFound for a type this hubctl was not built with.
  static Expected<const msgs::TypeInfo*> known_type(std::string_view ros_name);
  // Where the State of `target` arrives, and which part of it is the node's (empty: all of it).
  Expected<std::pair<StateChannel*, std::string>> state_of(const StepTarget& target);
  // A writer on `topic`, matched with at least `readers` readers (waits up to the discovery
  // timeout; a writer that is not matched yet would send into the void).
  Expected<WriterEntry*> writer(const std::string& topic, const msgs::TypeInfo& type,
                                std::uint32_t readers = 1);
  // As writer(), for a hub's command topic: the writer is created with the command LIFESPAN.
  Expected<WriterEntry*> command_writer(const std::string& topic, const msgs::TypeInfo& type);
  // The number of remote readers of `ros_topic`, once the hub `hub` is among them.
  Expected<std::uint32_t> readers_including(std::string_view ros_topic, std::string_view hub);
  // The number of remote readers of `ros_topic` discovery knows now (no waiting).
  Expected<std::uint32_t> readers_now(std::string_view ros_topic);

 private:
  Expected<WriterEntry*> writer_with(const std::string& topic, const msgs::TypeInfo& type,
                                     std::uint32_t readers, const dds::Qos& qos);
  Expected<StateChannel*> channel(const std::string& topic, const msgs::TypeInfo& type);
  Expected<void> wait_for_readers(const WriterEntry& entry, std::uint32_t count);

  const dds::Participant& participant_;
  Duration discovery_timeout_;
  Duration period_;
  std::uint32_t command_lifespan_ms_;
  std::string ros_namespace_;
  SteadyClock::time_point next_send_{};
  std::map<std::string, NodeEndpoints> located_;
  std::map<std::string, std::unique_ptr<StateChannel>> states_;
  std::map<std::string, std::unique_ptr<WriterEntry>> writers_;
  std::map<std::string, Plan> plans_;
};

}  // namespace hubrt::hubctl
