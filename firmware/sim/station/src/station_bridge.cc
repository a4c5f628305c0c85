#include "hubrt/sim/station/station_bridge.h"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "hubrt/runtime/node.h"
#include "hubrt/runtime/reflected_message_ops.h"

#include "platform_reader.h"
#include "station_reflect.h"

namespace hubrt::sim::station {
namespace {

std::string text(const char* s) {
  return s == nullptr ? std::string() : std::string(s);
}

char* wire(const std::string& s) {
  return const_cast<char*>(s.c_str());
}  // NOLINT: wire type wants char*

}  // namespace

Expected<std::unique_ptr<StationBridge>> StationBridge::create(const dds::Participant& participant,
                                                               StationModel& model,
                                                               std::shared_ptr<spdlog::logger> log,
                                                               std::string_view ros_namespace) {
  std::array<std::unique_ptr<HubView>, kHubRoles> hubs;
  for (std::size_t role = 0; role < kHubRoles; ++role) {
    const std::string& name = model.config().hubs[role];
    auto topic = dds::Topic<hub_msgs_msg_dds__SimSignals_>::create(
        participant, sim_topic(ros_namespace, sim_signals_topic(name)));
    if (!topic) return std::move(topic).error();
    auto reader = dds::Reader<hub_msgs_msg_dds__SimSignals_>::create(participant, *topic);
    if (!reader) return std::move(reader).error();
    hubs[role] = std::unique_ptr<HubView>(new HubView{name, std::move(*topic), std::move(*reader), {}, {}});
  }
  auto command_topic = dds::Topic<hub_msgs_msg_dds__StationCommand_>::create(
      participant, sim_topic(ros_namespace, kStationCommandTopic));
  if (!command_topic) return std::move(command_topic).error();
  auto command_reader = dds::Reader<hub_msgs_msg_dds__StationCommand_>::create(participant, *command_topic);
  if (!command_reader) return std::move(command_reader).error();
  auto state_topic = dds::Topic<hub_msgs_msg_dds__StationState_>::create(
      participant, sim_topic(ros_namespace, kStationStateTopic));
  if (!state_topic) return std::move(state_topic).error();
  auto state_writer = dds::Writer<hub_msgs_msg_dds__StationState_>::create(participant, *state_topic);
  if (!state_writer) return std::move(state_writer).error();
  auto input_topic =
      dds::Topic<hub_msgs_msg_dds__SimInput_>::create(participant, sim_topic(ros_namespace, kSimInputTopic));
  if (!input_topic) return std::move(input_topic).error();
  auto input_writer = dds::Writer<hub_msgs_msg_dds__SimInput_>::create(participant, *input_topic);
  if (!input_writer) return std::move(input_writer).error();
  std::unique_ptr<PlatformReader> platform;
  if (model.config().mobile_platform) {
    auto reader = PlatformReader::create(participant, *model.config().mobile_platform);
    if (!reader) return std::move(reader).error();
    platform = std::move(*reader);
  }
  Entities entities{std::move(hubs),          std::move(*command_topic), std::move(*command_reader),
                    std::move(*state_topic),  std::move(*state_writer),  std::move(*input_topic),
                    std::move(*input_writer), std::move(platform)};
  return std::unique_ptr<StationBridge>(new StationBridge(std::move(entities), model, std::move(log)));
}

StationBridge::StationBridge(Entities entities, StationModel& model, std::shared_ptr<spdlog::logger> log)
    : dds_(std::move(entities)), model_(model), log_(std::move(log)) {}

StationBridge::~StationBridge() = default;

void StationBridge::step(const Instant& now) {
  model_.advance(now.mono);
  take_signals(now.mono);
  take_platform(now.mono);
  take_commands(now.mono);
  reconcile(now.mono);
  publish(now);
}

bool StationBridge::silent(const HubView& hub, Time now) const noexcept {
  return !hub.last_heard || now - *hub.last_heard > kSilentAfter;
}

void StationBridge::take_signals(Time now) {
  // Every hub on the simulation board simulates every device of the station; only the one wired
  // to it is real: the RSP ECU's valves, the Tool ECU's lift.
  for (std::size_t role = 0; role < kHubRoles; ++role) {
    HubView* hub = dds_.hubs[role].get();
    const bool valves_here = static_cast<HubRole>(role) == HubRole::kRsp;
    const bool lifts_here = static_cast<HubRole>(role) == HubRole::kTool;
    for (int i = 0; i < 64; ++i) {
      const Result<bool> taken = hub->reader.take_next(signals_);
      if (!taken.is_ok() || !taken.value()) break;
      const auto& sample = signals_.get();
      if (!hub->last_heard) log_->info("station: hearing hub '{}'", hub->name);
      hub->last_heard = now;
      for (std::uint32_t s = 0; s < sample.signals._length; ++s) {
        const auto& signal = sample.signals._buffer[s];
        if (signal.name != nullptr) hub->levels.insert_or_assign(std::string(signal.name), signal.active);
      }
      for (std::uint32_t v = 0; valves_here && v < sample.valves._length; ++v) {
        const auto& valve = sample.valves._buffer[v];
        if (valve.name != nullptr) model_.observe_valve(valve.name, valve.energised, now);
      }
      for (std::uint32_t l = 0; lifts_here && l < sample.lifts._length; ++l) {
        const auto& lift = sample.lifts._buffer[l];
        if (lift.device != nullptr) model_.observe_lift(lift.device, lift.position_mm);
      }
    }
  }
}

void StationBridge::take_platform(Time now) {
  if (!dds_.platform) return;
  if (const auto report = dds_.platform->take()) model_.observe_platform(*report, now);
  // Also when the platform's State was lost (advance() in step() made the kit unknown).
  if (model_.kit() != logged_kit_) {
    log_->info("station: the kit is {} (mobile platform on {})", to_string(model_.kit()),
               model_.config().mobile_platform->state_topic);
    logged_kit_ = model_.kit();
  }
}

void StationBridge::take_commands(Time now) {
  for (int i = 0; i < 16; ++i) {
    const Result<bool> taken = dds_.command_reader.take_next(command_);
    if (!taken.is_ok() || !taken.value()) break;
    const auto& c = command_.get();
    // The hubs' rules for command text (strict UTF-8, no control characters, 64 bytes), with the
    // same escaped rejection: the State and the log must never carry raw bytes from a peer.
    static const runtime::ReflectedMessageOps ops(msgs::type_info_of<hub_msgs_msg_dds__StationCommand_>());
    if (runtime::Problem problem; !ops.check_fields(&c, runtime::kMaxCommandString, problem)) {
      rejection_ = std::string(problem.view());
      rejected_at_ = now;
      log_->warn("station: rejected command: {}", rejection_);
      continue;
    }
    on_command(Echo{text(c.target_type), text(c.target_name), text(c.action), text(c.location)}, now);
  }
}

// The hubs' command semantics: content that differs from the echo, or that comes after a pause
// longer than the freshness window, takes effect; a quick repeat only keeps the echo fresh.
void StationBridge::on_command(Echo command, Time now) {
  const auto addressed = [](const std::string& s) { return s.empty() || s == "station"; };
  if (!addressed(command.target_type) || !addressed(command.target_name)) {
    rejection_ = fmt::format("wrong target: '{}' of type '{}' (this is 'station' of type 'station')",
                             command.target_name, command.target_type);
    rejected_at_ = now;
    log_->warn("station: rejected command: {}", rejection_);
    return;
  }
  const bool repeat = echo_ && *echo_ == command && now - last_command_ <= kCommandFreshFor;
  if (repeat) {
    last_command_ = now;
    return;
  }
  if (auto done = model_.command(command.action, command.location, now); !done) {
    rejection_ = done.error().message;
    rejected_at_ = now;
    log_->warn("station: rejected command: {}", rejection_);
    return;
  }
  log_->info("station: {} {}", command.action, command.location);
  echo_ = std::move(command);
  echo_since_ = now;
  last_command_ = now;
  rejection_.clear();
}

void StationBridge::reconcile(Time now) {
  bool all_match = true;
  for (const WorldInput& input : model_.inputs()) {
    HubView& hub = *dds_.hubs[static_cast<std::size_t>(input.hub)];
    if (silent(hub, now)) {
      all_match = false;
      continue;
    }
    const auto level = hub.levels.find(input.signal);
    if (level == hub.levels.end()) {
      all_match = false;  // the hub's board lacks the signal: nothing to send it to
      continue;
    }
    if (level->second == input.active) continue;
    all_match = false;
    const auto key = std::make_pair(input.hub, std::string(input.signal));
    const auto sent = sent_.find(key);
    if (sent != sent_.end() && sent->second.active == input.active &&
        now - sent->second.at < model_.config().resend_holdoff) {
      continue;  // on its way: the hub applies it in its next cycle
    }
    hub_msgs_msg_dds__SimInput_ wire_input{};
    wire_input.hub = wire(hub.name);
    const std::string signal(input.signal);
    wire_input.signal = wire(signal);
    wire_input.active = input.active;
    if (auto written = dds_.input_writer.write(wire_input); !written.is_ok()) {
      log_->warn("station: sending {} to hub '{}' failed: {}", signal, hub.name, to_string(written.code()));
      continue;
    }
    log_->debug("station: {}.{} -> {}", hub.name, signal, input.active);
    sent_.insert_or_assign(key, Sent{input.active, now});
  }
  in_sync_ = all_match;
}

void StationBridge::publish(const Instant& now) {
  const Time t = now.mono;
  std::vector<std::string> errors;
  if (!rejection_.empty() && t - rejected_at_ <= kCommandFreshFor) {
    errors.push_back(fmt::format("rejected command: {}", rejection_));
  }
  errors.insert(errors.end(), model_.faults().begin(), model_.faults().end());
  std::vector<char*> error_pointers;
  error_pointers.reserve(errors.size());
  for (const auto& e : errors) error_pointers.push_back(wire(e));

  const auto& config = model_.config();
  std::vector<hub_msgs_msg_dds__StationTool_> tools(config.tools.size());
  for (std::size_t i = 0; i < config.tools.size(); ++i) {
    tools[i].name = wire(config.tools[i].name);
    tools[i].at = const_cast<char*>(to_string(model_.tool_place(i)).data());  // NOLINT: static text
  }
  std::vector<char*> silent_hubs;
  for (const auto& hub : dds_.hubs) {
    if (silent(*hub, t)) silent_hubs.push_back(wire(hub->name));
  }

  const Echo empty;
  const Echo& echo = echo_ ? *echo_ : empty;
  const bool fresh = echo_ && t - last_command_ <= kCommandFreshFor;
  // The lock's actuator, and where its solenoid sends it (the RSP ECU's output line).
  std::string lock = "unknown";
  if (model_.lock_open()) {
    const HubView& rsp = *dds_.hubs[static_cast<std::size_t>(HubRole::kRsp)];
    const auto solenoid = rsp.levels.find(config.lock_valve);
    const bool open = *model_.lock_open();
    const bool moving = solenoid != rsp.levels.end() && solenoid->second != open;
    lock = moving ? (open ? "closing" : "opening") : (open ? "open" : "closed");
  }
  const std::string gripper =
      !model_.gripper_closed() ? "unknown" : (*model_.gripper_closed() ? "closed" : "open");
  const ToolConfig* on_robot = model_.on_robot();
  static const std::string kNone = "none";
  static const std::string kStation = "station";

  hub_msgs_msg_dds__StationState_ state{};
  state.header.seq = ++published_;
  // The station model has no devices nor latched faults: it follows its commands while fresh.
  state.header.lifecycle =
      static_cast<std::uint8_t>(fresh ? runtime::Lifecycle::kOperational : runtime::Lifecycle::kSafe);
  state.header.stamp.sec = static_cast<std::int32_t>(now.wall.ns_since_epoch / 1'000'000'000);
  state.header.stamp.nanosec = static_cast<std::uint32_t>(now.wall.ns_since_epoch % 1'000'000'000);
  state.name = wire(kStation);
  state.echo.target_type = wire(echo.target_type);
  state.echo.target_name = wire(echo.target_name);
  state.echo.action = wire(echo.action);
  state.echo.location = wire(echo.location);
  state.fresh_msg = fresh;
  state.t_plus = echo_ ? static_cast<float>(to_seconds(t - echo_since_)) : 0.0F;
  state.got_reset = fresh && echo.action == "reset";
  state.error_list._buffer = error_pointers.data();
  state.error_list._length = static_cast<std::uint32_t>(error_pointers.size());
  state.error_list._maximum = state.error_list._length;
  state.robot_at = wire(model_.robot_at());
  state.robot_moving_to = wire(model_.robot_moving_to());
  state.changer_lock = wire(lock);
  state.on_robot = wire(on_robot != nullptr ? on_robot->name : kNone);
  state.tools._buffer = tools.data();
  state.tools._length = static_cast<std::uint32_t>(tools.size());
  state.tools._maximum = state.tools._length;
  state.ladder_frame = wire(model_.ladder_frame());
  state.kit = const_cast<char*>(to_string(model_.kit()).data());  // NOLINT: static text
  state.gripper = wire(gripper);
  state.smart_tool_arm = const_cast<char*>(to_string(model_.arm()).data());  // NOLINT: static text
  state.lift_mm =
      model_.lift_mm() ? static_cast<float>(*model_.lift_mm()) : std::numeric_limits<float>::quiet_NaN();
  state.in_sync = in_sync_;
  state.hubs_silent._buffer = silent_hubs.data();
  state.hubs_silent._length = static_cast<std::uint32_t>(silent_hubs.size());
  state.hubs_silent._maximum = state.hubs_silent._length;
  if (auto written = dds_.state_writer.write(state); !written.is_ok()) {
    log_->warn("station: publishing the State failed: {}", to_string(written.code()));
  }
}

}  // namespace hubrt::sim::station
