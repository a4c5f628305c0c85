#include "hubrt/sim/sim_bridge_stage.h"

#include <fmt/format.h>

namespace hubrt::sim {

std::string sim_signals_topic(std::string_view hub) { return fmt::format("/sim/{}/signals", hub); }

Expected<std::unique_ptr<SimBridgeStage>> SimBridgeStage::create(const dds::Participant& participant,
                                                                 std::string hub_name, const hal::BoardConfig& board,
                                                                 hal::fake::FakeBackend& fake,
                                                                 std::shared_ptr<spdlog::logger> log) {
  auto input_topic = dds::Topic<hub_msgs_msg_dds__SimInput_>::create(participant, kSimInputTopic);
  if (!input_topic) return std::move(input_topic).error();
  auto reader = dds::Reader<hub_msgs_msg_dds__SimInput_>::create(participant, *input_topic);
  if (!reader) return std::move(reader).error();
  auto signals_topic = dds::Topic<hub_msgs_msg_dds__SimSignals_>::create(participant, sim_signals_topic(hub_name));
  if (!signals_topic) return std::move(signals_topic).error();
  auto writer = dds::Writer<hub_msgs_msg_dds__SimSignals_>::create(participant, *signals_topic);
  if (!writer) return std::move(writer).error();
  std::vector<Signal> signals;
  for (const auto& input : board.inputs) signals.push_back(Signal{input.config.signal, false});
  for (const auto& output : board.outputs) signals.push_back(Signal{output.config.signal, true});
  return std::unique_ptr<SimBridgeStage>(new SimBridgeStage(std::move(*input_topic), std::move(*reader),
                                                            std::move(*signals_topic), std::move(*writer),
                                                            std::move(hub_name), std::move(signals), fake,
                                                            std::move(log)));
}

SimBridgeStage::SimBridgeStage(dds::Topic<hub_msgs_msg_dds__SimInput_> input_topic,
                               dds::Reader<hub_msgs_msg_dds__SimInput_> reader,
                               dds::Topic<hub_msgs_msg_dds__SimSignals_> signals_topic,
                               dds::Writer<hub_msgs_msg_dds__SimSignals_> writer, std::string hub_name,
                               std::vector<Signal> signals, hal::fake::FakeBackend& fake,
                               std::shared_ptr<spdlog::logger> log)
    : input_topic_(std::move(input_topic)),
      reader_(std::move(reader)),
      signals_topic_(std::move(signals_topic)),
      writer_(std::move(writer)),
      hub_name_(std::move(hub_name)),
      signals_(std::move(signals)),
      fake_(fake),
      log_(std::move(log)),
      wire_signals_(signals_.size()) {
  for (std::size_t i = 0; i < signals_.size(); ++i) {
    wire_signals_[i].name = signals_[i].name.data();
    wire_signals_[i].output = signals_[i].output;
  }
  wire_.hub = hub_name_.data();
  wire_.signals._buffer = wire_signals_.data();
  wire_.signals._length = static_cast<std::uint32_t>(wire_signals_.size());
  wire_.signals._maximum = wire_.signals._length;
  wire_.signals._release = false;
}

bool SimBridgeStage::apply(std::string_view signal, bool active) noexcept {
  if (auto* sensor = fake_.dock_sensor(signal); sensor != nullptr) {
    sensor->set_occupied(active);
  } else if (auto* input = fake_.input(signal); input != nullptr) {
    input->set(active);
  } else if (auto* supply = fake_.pressure_supply(signal); supply != nullptr) {
    if (active) {
      supply->restore();
    } else {
      supply->drop();
    }
  } else {
    log_->warn("sim: '{}' is not a simulated input or pressure supply of hub '{}'", signal, hub_name_);
    return false;
  }
  log_->info("sim: {} -> {}", signal, active ? "active" : "inactive");
  return true;
}

void SimBridgeStage::before_nodes(const Instant& /*now*/) noexcept {
  for (int i = 0; i < 64; ++i) {  // bounded: a flood of sim inputs must not stall the cycle
    const Result<bool> taken = reader_.take_next(input_);
    if (!taken.is_ok() || !taken.value()) break;
    const auto& input = input_.get();
    if (input.hub == nullptr || input.signal == nullptr || hub_name_ != input.hub) continue;
    apply(input.signal, input.active);
  }
}

void SimBridgeStage::after_nodes(const Instant& /*now*/, bool publish_all, bool /*took_effect*/) noexcept {
  if (!publish_all) return;
  for (std::size_t i = 0; i < signals_.size(); ++i) {
    const Result<bool> level = fake_.active(signals_[i].name);
    wire_signals_[i].active = level.is_ok() && level.value();
  }
  writer_.write(wire_).ignore();  // observation only; a lost sample is replaced next cycle
}

}  // namespace hubrt::sim
