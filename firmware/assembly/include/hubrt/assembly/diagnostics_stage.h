// Publishes the hub's health on /diagnostics as diagnostic_msgs/DiagnosticArray, the topic ROS
// users already watch (rqt_runtime_monitor, ros2 topic echo): one status for the cycle and one
// per node, at a low rate, built in storage sized once. Both carry the lifecycle (lifecycle.h):
// the hub's overall state (keys lifecycle, lifecycle_reason) and each node's (lifecycle,
// lifecycle_reason, lifecycle_transitions).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hubrt/dds/peer_authentication_watch.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/runtime/hub.h"
#include "hubrt/runtime/text_buffer.h"

// The message types with their DDS registration, generated once (a second registration here
// clashed with it wherever both headers met, as in a unity source).
#include "diagnostic_msgs_typed.h"

namespace hubrt::assembly {

class DiagnosticsStage final : public runtime::CycleStage {
 public:
  static constexpr std::size_t kMaxValues = 28;

  // `hub` must already have all its nodes. `interval` between two publications. A positive
  // `command_timeout` is published too (key command_timeout_ms), so that tools such as
  // `hubctl conformance` learn the watchdog's timeout from the wire; likewise a positive
  // `immediate_state_interval` (key immediate_state_interval_ms, with immediate_state_burst: the
  // token bucket of immediate States), so that a tool measuring echo latency spaces its changes
  // by at least that much; and
  // `log_lines_dropped` when given (key log_lines_dropped: log lines lost to a closed stderr;
  // must outlive the stage).
  // Errors: the DDS topic or writer that could not be created.
  static Expected<std::unique_ptr<DiagnosticsStage>> create(
      const dds::Participant& participant, const runtime::Hub& hub, std::string hardware_id,
      Duration interval, Duration command_timeout = {}, Duration immediate_state_interval = {},
      const std::atomic<std::uint64_t>* log_lines_dropped = nullptr);

  // The stage's DDS side alone (the /diagnostics topic and writer), which needs no node: hubd
  // creates it while the start-up twin check watches discovery (it publishes nothing until the
  // stage runs, and /diagnostics is no State topic), so that it does not add to the start-up.
  struct Endpoint {
    dds::Topic<diagnostic_msgs_msg_dds__DiagnosticArray_> topic;
    dds::Writer<diagnostic_msgs_msg_dds__DiagnosticArray_> writer;
    // In a process that counts DDS Security refusals (dds/security_refusals.h, a secured hubd):
    // the remote participants that do not authenticate (dds/peer_authentication_watch.h).
    std::unique_ptr<dds::PeerAuthenticationWatch> peers;
  };
  // Errors: the DDS topic, writer or discovery readers that could not be created.
  static Expected<Endpoint> open_endpoint(const dds::Participant& participant);
  // As create() above, on an endpoint opened before. Never fails.
  static std::unique_ptr<DiagnosticsStage> create(
      Endpoint endpoint, const runtime::Hub& hub, std::string hardware_id, Duration interval,
      Duration command_timeout = {}, Duration immediate_state_interval = {},
      const std::atomic<std::uint64_t>* log_lines_dropped = nullptr);

  void before_nodes(const Instant& /*now*/) noexcept override {}
  void after_nodes(const Instant& now, bool publish_all, bool took_effect) noexcept override;

  // Builds the array for `now` without publishing (tests read it).
  const diagnostic_msgs_msg_dds__DiagnosticArray_& build(const Instant& now) noexcept;

 private:
  struct Status {
    runtime::TextBuffer<96> name;
    runtime::TextBuffer<191> message;
    std::array<runtime::TextBuffer<40>, kMaxValues> values;
    runtime::LifecycleState::Reason lifecycle_reason;  // longer than a value slot
    std::array<diagnostic_msgs_msg_dds__KeyValue_, kMaxValues> pairs{};
  };

  DiagnosticsStage(dds::Topic<diagnostic_msgs_msg_dds__DiagnosticArray_> topic,
                   dds::Writer<diagnostic_msgs_msg_dds__DiagnosticArray_> writer,
                   std::unique_ptr<dds::PeerAuthenticationWatch> peers, const runtime::Hub& hub,
                   std::string hardware_id, Duration interval, Duration command_timeout,
                   Duration immediate_state_interval, const std::atomic<std::uint64_t>* log_lines_dropped);
  void fill_hub_status(const Instant& now) noexcept;
  void fill_node_status(std::size_t index, const runtime::NodeBase& node) noexcept;
  // The commands a node (or the hub-level command node) did not follow, and its clock offsets.
  template <class Add>
  static void add_command_counts(const runtime::NodeBase& node, Add&& add) noexcept {
    add("commands_rejected", node.rejected());
    add("commands_stale", node.commands_stale());
    if (const runtime::CommandAgeJudge* ages = node.command_ages(); ages != nullptr && ages->offset_seen()) {
      add("clock_offset_ms", to_seconds(ages->last_offset()) * 1e3);
      add("clock_offset_max_ms", to_seconds(ages->largest_offset()) * 1e3);
    }
  }
  void set_value(std::size_t status, std::size_t slot, const char* key, const char* value) noexcept;
  // The nodes' clock tolerance in ms, or "none" (clocks not synced).
  std::string_view clock_tolerance_text() noexcept;

  dds::Topic<diagnostic_msgs_msg_dds__DiagnosticArray_> topic_;
  dds::Writer<diagnostic_msgs_msg_dds__DiagnosticArray_> writer_;
  std::unique_ptr<dds::PeerAuthenticationWatch> peers_;
  const runtime::Hub& hub_;
  std::string hardware_id_;
  Duration interval_;
  Duration command_timeout_;
  Duration immediate_state_interval_;
  const std::atomic<std::uint64_t>* log_lines_dropped_;
  runtime::TextBuffer<24> tolerance_text_;
  Time next_due_{};
  bool started_ = false;
  Time started_at_{};
  std::vector<Status> statuses_;
  std::vector<diagnostic_msgs_msg_dds__DiagnosticStatus_> wire_statuses_;
  diagnostic_msgs_msg_dds__DiagnosticArray_ array_{};
};

}  // namespace hubrt::assembly
