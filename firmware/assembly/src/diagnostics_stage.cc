#include "hubrt/assembly/diagnostics_stage.h"

#include <algorithm>
#include <chrono>

#include <fmt/format.h>

#include "hubrt/dds/oversize_samples.h"
#include "hubrt/dds/security_refusals.h"
#include "hubrt/hub_api/topic_names.h"
#include "hubrt/runtime/immediate_state_budget.h"

namespace hubrt::assembly {
namespace {

char* text(const runtime::TextBuffer<96>& b) noexcept {
  return const_cast<char*>(b.c_str());
}  // NOLINT
char* text(const runtime::TextBuffer<191>& b) noexcept {
  return const_cast<char*>(b.c_str());
}  // NOLINT

std::uint8_t level_of(runtime::Health health) noexcept {
  return static_cast<std::uint8_t>(health);
}

}  // namespace

Expected<std::unique_ptr<DiagnosticsStage>> DiagnosticsStage::create(
    const dds::Participant& participant, const runtime::Hub& hub, std::string hardware_id, Duration interval,
    Duration command_timeout, Duration immediate_state_interval,
    const std::atomic<std::uint64_t>* log_lines_dropped) {
  auto endpoint = open_endpoint(participant);
  if (!endpoint) return std::move(endpoint).error();
  return create(std::move(*endpoint), hub, std::move(hardware_id), interval, command_timeout,
                immediate_state_interval, log_lines_dropped);
}

Expected<DiagnosticsStage::Endpoint> DiagnosticsStage::open_endpoint(const dds::Participant& participant) {
  auto topic =
      dds::Topic<diagnostic_msgs_msg_dds__DiagnosticArray_>::create(participant, hub_api::kDiagnosticsTopic);
  if (!topic) return std::move(topic).error();
  auto writer = dds::Writer<diagnostic_msgs_msg_dds__DiagnosticArray_>::create(participant, *topic);
  if (!writer) return std::move(writer).error();
  std::unique_ptr<dds::PeerAuthenticationWatch> peers;
  if (dds::security_refusals_counted()) {
    auto watch = dds::PeerAuthenticationWatch::start(participant);
    if (!watch) return std::move(watch).error();
    peers = std::move(*watch);
  }
  return Endpoint{std::move(*topic), std::move(*writer), std::move(peers)};
}

std::unique_ptr<DiagnosticsStage> DiagnosticsStage::create(
    Endpoint endpoint, const runtime::Hub& hub, std::string hardware_id, Duration interval,
    Duration command_timeout, Duration immediate_state_interval,
    const std::atomic<std::uint64_t>* log_lines_dropped) {
  return std::unique_ptr<DiagnosticsStage>(new DiagnosticsStage(
      std::move(endpoint.topic), std::move(endpoint.writer), std::move(endpoint.peers), hub,
      std::move(hardware_id), interval, command_timeout, immediate_state_interval, log_lines_dropped));
}

DiagnosticsStage::DiagnosticsStage(dds::Topic<diagnostic_msgs_msg_dds__DiagnosticArray_> topic,
                                   dds::Writer<diagnostic_msgs_msg_dds__DiagnosticArray_> writer,
                                   std::unique_ptr<dds::PeerAuthenticationWatch> peers,
                                   const runtime::Hub& hub, std::string hardware_id, Duration interval,
                                   Duration command_timeout, Duration immediate_state_interval,
                                   const std::atomic<std::uint64_t>* log_lines_dropped)
    : topic_(std::move(topic)),
      writer_(std::move(writer)),
      peers_(std::move(peers)),
      hub_(hub),
      hardware_id_(std::move(hardware_id)),
      interval_(interval),
      command_timeout_(command_timeout),
      immediate_state_interval_(immediate_state_interval),
      log_lines_dropped_(log_lines_dropped),
      statuses_(hub.nodes().size() + 1),
      wire_statuses_(hub.nodes().size() + 1) {
  for (std::size_t i = 0; i < statuses_.size(); ++i) {
    auto& wire = wire_statuses_[i];
    wire.name = text(statuses_[i].name);
    wire.message = text(statuses_[i].message);
    wire.hardware_id = hardware_id_.data();
    wire.values._buffer = statuses_[i].pairs.data();
    wire.values._maximum = kMaxValues;
    wire.values._release = false;
  }
  array_.header.frame_id = const_cast<char*>("");  // NOLINT: wire type wants char*
  array_.status._buffer = wire_statuses_.data();
  array_.status._maximum = static_cast<std::uint32_t>(wire_statuses_.size());
  array_.status._length = static_cast<std::uint32_t>(wire_statuses_.size());
  array_.status._release = false;
}

void DiagnosticsStage::set_value(std::size_t status, std::size_t slot, const char* key,
                                 const char* value) noexcept {
  auto& pair = statuses_[status].pairs[slot];
  pair.key = const_cast<char*>(key);      // NOLINT: static string, never written through
  pair.value = const_cast<char*>(value);  // NOLINT: our buffer, never written through
}

void DiagnosticsStage::fill_hub_status(const Instant& now) noexcept {
  Status& s = statuses_[0];
  const runtime::CycleStats& stats = hub_.stats();
  s.name.format("{}: cycle", hub_.options().name);
  const double period_ms = to_seconds(hub_.options().period) * 1e3;
  s.message.format("{} cycles at {:.1f} ms, {} overruns", stats.cycles, period_ms, stats.overruns);
  // At most 27 values (kMaxValues is 28): 14 always, 5 more when every option is given, 4 more when
  // the process counts security refusals, 4 more in the hub layout; the guard keeps a key added
  // later from writing past the storage.
  std::size_t n = 0;
  const auto add = [&](const char* key, auto value) {
    if (n == kMaxValues) return;
    s.values[n].format("{}", value);
    set_value(0, n, key, s.values[n].c_str());
    ++n;
  };
  add("hub_type", hub_.options().type);
  add("lifecycle", hub_.lifecycle().name());
  s.lifecycle_reason.assign(hub_.lifecycle().reason());
  set_value(0, n++, "lifecycle_reason", s.lifecycle_reason.c_str());
  add("period_ms", period_ms);
  add("rate_hz", 1e3 / period_ms);
  if (command_timeout_ > Duration::zero()) add("command_timeout_ms", to_seconds(command_timeout_) * 1e3);
  // How far the clocks are trusted to agree (runtime/command_age.h): every node has the hub's.
  add("clock_tolerance_ms", clock_tolerance_text());
  // The token bucket of immediate States (runtime/immediate_state_budget.h): refill period, size.
  if (immediate_state_interval_ > Duration::zero()) {
    add("immediate_state_interval_ms", to_seconds(immediate_state_interval_) * 1e3);
    add("immediate_state_burst", runtime::kDefaultImmediateStateBurst);
  }
  add("cycles", stats.cycles);
  add("command_steps", stats.command_steps);
  add("overruns", stats.overruns);
  // Changes whose immediate State the budget held back (a planner flipping its command too fast).
  add("states_deferred", hub_.states_deferred());
  add("last_cycle_us", std::chrono::duration_cast<std::chrono::microseconds>(stats.last_cycle).count());
  add("max_cycle_us", std::chrono::duration_cast<std::chrono::microseconds>(stats.max_cycle).count());
  // The longest the cycle was held past a deadline (stopped, paused, a step that blocked).
  add("max_late_ms", std::chrono::duration_cast<std::chrono::milliseconds>(stats.longest_late).count());
  add("uptime_s", static_cast<std::int64_t>(to_seconds(now.mono - started_at_)));
  if (log_lines_dropped_ != nullptr)
    add("log_lines_dropped", log_lines_dropped_->load(std::memory_order_relaxed));
  // Samples larger than dds::kMaxSampleSizeBytes that Cyclone discarded in this process (a hubd
  // is one hub), when the process counts them (hubd does: dds/oversize_samples.h).
  if (dds::oversize_samples_counted()) add("oversize_samples_dropped", dds::oversize_samples_dropped());
  // What DDS Security refused in this process (a secured hubd is one hub): someone tried to join or
  // to write without the station's credentials. Participants from discovery (they never show an
  // endpoint: dds/peer_authentication_watch.h), the rest from Cyclone's log (dds/security_refusals.h).
  const dds::SecurityRefusalCounts logged = dds::security_refusals();
  const dds::PeerAuthenticationWatch::Counts peers =
      peers_ ? peers_->counts(std::chrono::steady_clock::now()) : dds::PeerAuthenticationWatch::Counts{};
  const std::uint64_t refused_participants = std::max(peers.refused, logged.participants);
  if (dds::security_refusals_counted()) {
    add("refused_participants", refused_participants);
    add("unauthenticated_participants", peers.unauthenticated_now);
    add("refused_writers", logged.writers);
    add("authentication_failures", logged.authentication);
  }
  // The hub layout: the hub-level command's own intake (its stale commands never reach a node).
  if (const runtime::NodeBase* hub_level = hub_.hub_level_node(); hub_level != nullptr)
    add_command_counts(*hub_level, add);
  wire_statuses_[0].values._length = static_cast<std::uint32_t>(n);
  wire_statuses_[0].level =
      stats.publish_errors > 0 ? level_of(runtime::Health::kWarn) : level_of(runtime::Health::kOk);
  // Refusals are an attempt on the station (or a participant of another CA): say so on the line.
  if (refused_participants + logged.writers + logged.readers + logged.authentication > 0) {
    s.message.format(
        "{} cycles at {:.1f} ms, {} overruns; DDS Security refused {} participant(s) ({} now), {} "
        "writer(s), {} handshake step(s)",
        stats.cycles, period_ms, stats.overruns, refused_participants, peers.unauthenticated_now,
        logged.writers, logged.authentication);
    wire_statuses_[0].level = level_of(runtime::Health::kWarn);
  }
  // A hub-wide alert (e.g. a twin) concerns the hub as a whole: say it on the hub's line too.
  if (!hub_.alerts().empty()) {
    s.message.assign(hub_.alerts().at(0));
    wire_statuses_[0].level = level_of(runtime::Health::kError);
  }
}

std::string_view DiagnosticsStage::clock_tolerance_text() noexcept {
  for (const auto& node : hub_.nodes()) {
    const runtime::CommandAgeJudge* ages = node->command_ages();
    if (ages == nullptr) continue;
    if (!ages->tolerance()) return "none";
    tolerance_text_.format("{}",
                           std::chrono::duration_cast<std::chrono::milliseconds>(*ages->tolerance()).count());
    return tolerance_text_.view();
  }
  return "none";
}

void DiagnosticsStage::fill_node_status(std::size_t index, const runtime::NodeBase& node) noexcept {
  Status& s = statuses_[index];
  s.name.format("{}: {}", hub_.options().name, node.name());
  const runtime::Health health = node.health();
  if (!node.first_error().empty()) {
    s.message.assign(node.first_error());
  } else {
    s.message.assign(health == runtime::Health::kOk ? "ok" : "waiting for commands");
  }
  std::size_t n = 0;
  const auto add = [&](const char* key, auto value) {
    s.values[n].format("{}", value);
    set_value(index, n, key, s.values[n].c_str());
    ++n;
  };
  add("node_type", node.type());
  add("lifecycle", node.lifecycle().name());
  s.lifecycle_reason.assign(node.lifecycle().reason());
  set_value(index, n++, "lifecycle_reason", s.lifecycle_reason.c_str());
  add("lifecycle_transitions", node.lifecycle().transitions());
  add("states_published", node.published());
  // Rejected commands, commands too old to act or queued during a stall, and the clock offsets
  // seen in the commands' source timestamps (hub wall clock minus stamp, latency included: the
  // skew, when it is large).
  add_command_counts(node, add);
  add("states_deferred", node.states_deferred());
  wire_statuses_[index].values._length = static_cast<std::uint32_t>(n);
  wire_statuses_[index].level = level_of(health);
}

const diagnostic_msgs_msg_dds__DiagnosticArray_& DiagnosticsStage::build(const Instant& now) noexcept {
  if (!started_) {
    started_ = true;
    started_at_ = now.mono;
  }
  fill_hub_status(now);
  for (std::size_t i = 0; i < hub_.nodes().size(); ++i) fill_node_status(i + 1, *hub_.nodes()[i]);
  array_.header.stamp.sec = static_cast<std::int32_t>(now.wall.ns_since_epoch / 1'000'000'000);
  array_.header.stamp.nanosec = static_cast<std::uint32_t>(now.wall.ns_since_epoch % 1'000'000'000);
  return array_;
}

void DiagnosticsStage::after_nodes(const Instant& now, bool publish_all, bool /*took_effect*/) noexcept {
  if (!publish_all || interval_ <= Duration::zero()) return;
  if (started_ && now.mono < next_due_) return;
  const bool first = !started_;
  build(now);
  if (first) next_due_ = now.mono;
  next_due_ += interval_;
  if (next_due_ <= now.mono) next_due_ = now.mono + interval_;  // behind: skip, never burst
  writer_.write(array_).ignore();  // diagnostics are best effort; the hub's own State carries errors
}

}  // namespace hubrt::assembly
