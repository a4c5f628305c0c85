#include "hubrt/sim/sim_bridge_stage.h"

#include <atomic>
#include <memory>

#include <fmt/format.h>

#include "hubrt/sim/sim_world.h"

namespace hubrt::sim {
namespace {

template <class Element, class Sequence>
void point_sequence(Sequence& sequence, std::vector<Element>& elements) {
  sequence._buffer = elements.data();
  sequence._length = static_cast<std::uint32_t>(elements.size());
  sequence._maximum = sequence._length;
  sequence._release = false;
}

}  // namespace

std::string sim_signals_topic(std::string_view hub) {
  return fmt::format("/sim/{}/signals", hub);
}

std::string sim_topic(std::string_view ros_namespace, std::string_view topic) {
  return fmt::format("{}{}", ros_namespace, topic);
}

Expected<std::unique_ptr<SimBridgeStage>> SimBridgeStage::create(const dds::Participant& participant,
                                                                 std::string hub_name,
                                                                 const hal::BoardConfig& board,
                                                                 hal::fake::FakeBackend& fake,
                                                                 std::shared_ptr<spdlog::logger> log) {
  auto entities = open_entities(participant, hub_name);
  if (!entities) return std::move(entities).error();
  return create(std::move(*entities), std::move(hub_name), board, fake, std::move(log));
}

std::unique_ptr<SimBridgeStage> SimBridgeStage::create(Entities entities, std::string hub_name,
                                                       const hal::BoardConfig& board,
                                                       hal::fake::FakeBackend& fake,
                                                       std::shared_ptr<spdlog::logger> log) {
  return std::unique_ptr<SimBridgeStage>(
      new SimBridgeStage(std::move(entities), std::move(hub_name), board, fake, std::move(log)));
}

Expected<SimBridgeStage::Entities> SimBridgeStage::open_entities(const dds::Participant& participant,
                                                                 const std::string& hub_name,
                                                                 std::string_view ros_namespace) {
  // Set by Cyclone's data-available listener of the three readers (no blocking: an atomic store),
  // so that a cycle with nothing received takes nothing: three empty dds_take calls per cycle were
  // most of what the bridge cost once the signals were written only on change.
  auto pending = std::make_shared<std::atomic<bool>>(true);
  const auto note = [pending] { pending->store(true); };
  auto input_topic =
      dds::Topic<hub_msgs_msg_dds__SimInput_>::create(participant, sim_topic(ros_namespace, kSimInputTopic));
  if (!input_topic) return std::move(input_topic).error();
  auto input_reader = dds::Reader<hub_msgs_msg_dds__SimInput_>::create(participant, *input_topic,
                                                                       dds::Qos::ros2_default(), note);
  if (!input_reader) return std::move(input_reader).error();
  auto fault_topic =
      dds::Topic<hub_msgs_msg_dds__SimFault_>::create(participant, sim_topic(ros_namespace, kSimFaultTopic));
  if (!fault_topic) return std::move(fault_topic).error();
  auto fault_reader = dds::Reader<hub_msgs_msg_dds__SimFault_>::create(participant, *fault_topic,
                                                                       dds::Qos::ros2_default(), note);
  if (!fault_reader) return std::move(fault_reader).error();
  auto badge_topic =
      dds::Topic<hub_msgs_msg_dds__SimBadge_>::create(participant, sim_topic(ros_namespace, kSimBadgeTopic));
  if (!badge_topic) return std::move(badge_topic).error();
  auto badge_reader = dds::Reader<hub_msgs_msg_dds__SimBadge_>::create(participant, *badge_topic,
                                                                       dds::Qos::ros2_default(), note);
  if (!badge_reader) return std::move(badge_reader).error();
  auto signals_topic = dds::Topic<hub_msgs_msg_dds__SimSignals_>::create(
      participant, sim_topic(ros_namespace, sim_signals_topic(hub_name)));
  if (!signals_topic) return std::move(signals_topic).error();
  auto writer = dds::Writer<hub_msgs_msg_dds__SimSignals_>::create(participant, *signals_topic);
  if (!writer) return std::move(writer).error();
  return Entities{std::move(pending),       std::move(*input_topic),   std::move(*input_reader),
                  std::move(*fault_topic),  std::move(*fault_reader),  std::move(*badge_topic),
                  std::move(*badge_reader), std::move(*signals_topic), std::move(*writer)};
}

SimBridgeStage::SimBridgeStage(Entities entities, std::string hub_name, const hal::BoardConfig& board,
                               hal::fake::FakeBackend& fake, std::shared_ptr<spdlog::logger> log)
    : dds_(std::move(entities)),
      hub_name_(std::move(hub_name)),
      board_(board),
      fake_(fake),
      log_(std::move(log)) {
  for (const auto& input : board.inputs) signals_.push_back(Signal{input.config.signal, false, {}});
  for (const auto& output : board.outputs) signals_.push_back(Signal{output.config.signal, true, {}});
  for (auto& signal : signals_) {
    if (const auto wired = fake_.wiring(signal.name); wired.is_ok()) signal.wiring = wired.value();
  }
  if (board.simulation) {
    for (const auto& valve : board.simulation->valves) {
      if (fake_.valve(valve.output) != nullptr) valves_.push_back(valve.output);
    }
    for (const auto& device : board.simulation->modbus) {
      if (fake_.lift_drive(device.device) != nullptr) lifts_.push_back(device.device);
    }
  }
  wire_signals_.resize(signals_.size());
  for (std::size_t i = 0; i < signals_.size(); ++i) {
    wire_signals_[i].name = signals_[i].name.data();
    wire_signals_[i].output = signals_[i].output;
  }
  wire_valves_.resize(valves_.size());
  for (std::size_t i = 0; i < valves_.size(); ++i) wire_valves_[i].name = valves_[i].data();
  wire_lifts_.resize(lifts_.size());
  for (std::size_t i = 0; i < lifts_.size(); ++i) wire_lifts_[i].device = lifts_[i].data();
  wire_.hub = hub_name_.data();
  point_sequence(wire_.signals, wire_signals_);
  point_sequence(wire_.valves, wire_valves_);
  point_sequence(wire_.lifts, wire_lifts_);
}

bool SimBridgeStage::apply(std::string_view signal, bool active) noexcept {
  if (auto applied = apply_input(fake_, signal, active); !applied) {
    log_->warn("sim: hub '{}': {}", hub_name_, applied.error().message);
    return false;
  }
  log_->info("sim: {} -> {}", signal, active ? "active" : "inactive");
  return true;
}

void SimBridgeStage::apply_fault(const hub_msgs_msg_dds__SimFault_& fault, Time now) noexcept {
  const FaultRequest request{fault.device, fault.fault, fault.value};
  if (auto applied = sim::apply_fault(fake_, board_, request, now); !applied) {
    log_->warn("sim: hub '{}': fault refused: {}", hub_name_, applied.error().message);
    return;
  }
  log_->warn("sim: fault injected: {} {} (value {})", request.device, request.fault, request.value);
}

void SimBridgeStage::before_nodes(const Instant& now) noexcept {
  // A sample arriving from here on sets the flag again: at worst one more look next cycle.
  if (!dds_.pending->exchange(false)) return;
  int i = 0;
  for (i = 0; i < 64; ++i) {  // bounded: a flood of sim inputs must not stall the cycle
    const Result<bool> taken = dds_.input_reader.take_next(input_);
    if (!taken.is_ok() || !taken.value()) break;
    const auto& input = input_.get();
    if (input.hub == nullptr || input.signal == nullptr || hub_name_ != input.hub) continue;
    apply(input.signal, input.active);
  }
  bool more = i == 64;  // stopped at a bound: look again next cycle
  for (i = 0; i < 16; ++i) {
    const Result<bool> taken = dds_.badge_reader.take_next(badge_);
    if (!taken.is_ok() || !taken.value()) break;
    const auto& badge = badge_.get();
    if (badge.hub == nullptr || badge.reader == nullptr || badge.text == nullptr || hub_name_ != badge.hub)
      continue;
    // The text is the simulated badge: it is logged by its length only (badges never in clear).
    if (auto shown = apply_badge(fake_, badge.reader, badge.text); !shown) {
      log_->warn("sim: hub '{}': {}", hub_name_, shown.error().message);
    } else {
      log_->info("sim: badge of {} byte(s) shown to {}", std::string_view(badge.text).size(), badge.reader);
    }
  }
  more |= i == 16;
  for (i = 0; i < 16; ++i) {
    const Result<bool> taken = dds_.fault_reader.take_next(fault_);
    if (!taken.is_ok() || !taken.value()) break;
    const auto& fault = fault_.get();
    if (fault.hub == nullptr || fault.device == nullptr || fault.fault == nullptr || hub_name_ != fault.hub)
      continue;
    apply_fault(fault, now.mono);
  }
  if (more || i == 16) dds_.pending->store(true);
}

bool SimBridgeStage::read_signals(const Instant& now) noexcept {
  bool changed = false;
  for (std::size_t i = 0; i < signals_.size(); ++i) {
    const Signal& signal = signals_[i];
    bool active = false;
    if (signal.wiring) {
      const Result<bool> high = signal.wiring->chip->level(signal.wiring->line);
      active = high.is_ok() && high.value() != (signal.wiring->polarity == hal::Polarity::kActiveLow);
    } else {
      const Result<bool> level = fake_.active(signal.name);
      active = level.is_ok() && level.value();
    }
    changed |= wire_signals_[i].active != active;
    wire_signals_[i].active = active;
  }
  for (std::size_t i = 0; i < valves_.size(); ++i) {
    const bool energised = fake_.valve(valves_[i])->in_energised_position();
    changed |= wire_valves_[i].energised != energised;
    wire_valves_[i].energised = energised;
  }
  for (std::size_t i = 0; i < lifts_.size(); ++i) {
    const auto position = static_cast<float>(fake_.lift_drive(lifts_[i])->position_mm(now.mono));
    changed |= wire_lifts_[i].position_mm != position;
    wire_lifts_[i].position_mm = position;
  }
  return changed;
}

void SimBridgeStage::write_signals(const Instant& now) noexcept {
  dds_.signals_writer.write(wire_).ignore();  // observation only; a lost sample is replaced soon
  last_written_ = now.mono;
}

void SimBridgeStage::after_nodes(const Instant& now, bool publish_all, bool /*took_effect*/) noexcept {
  if (!publish_all) return;
  // Nobody listening (a hub under test or in the bench without the station model): the signals are
  // not even read. Reading them is a level read per signal, each advancing every simulator of the
  // fake GPIO to the clock's now, which was most of what a simulated hub's cycle cost beyond its
  // own node (perf, issue 16). A reader that matches is counted by take_new_readers(), so the next
  // periodic cycle reads and writes at once, as before.
  const bool new_reader = dds_.signals_writer.take_new_readers() > 0;
  if (!new_reader && !dds_.signals_writer.has_matched_readers()) return;
  const bool changed = read_signals(now);
  const bool due = !last_written_ || now.mono - *last_written_ >= kSimSignalsKeepAlive;
  if (changed || due || new_reader) write_signals(now);
}

void SimBridgeStage::after_safe_state(const Instant& now) noexcept {
  read_signals(now);
  write_signals(now);  // always: the watchers see the safe outputs
  // The writer is reliable, but Cyclone's writer linger "is currently not applied when Cyclone DDS
  // is requested to terminate" (docs/manual/config.rst, Lingering writers): wait for the readers'
  // acknowledgements (dds_wait_for_acks, dds.h) before hubd deletes its participant. Bounded, and
  // off the cycle: the outputs are already safe, this only tells the watchers.
  constexpr dds_duration_t kAckTimeout = DDS_MSECS(500);
  if (dds_wait_for_acks(dds_.signals_writer.handle(), kAckTimeout) != DDS_RETCODE_OK) {
    log_->warn("sim bridge: the last signals sample was not acknowledged within 500 ms");
  }
}

}  // namespace hubrt::sim
