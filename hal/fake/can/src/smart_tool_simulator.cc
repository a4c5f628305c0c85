#include "hubrt/hal/fake/smart_tool_simulator.h"

#include <algorithm>
#include <utility>

namespace hubrt::hal::fake {
namespace {

namespace st = protocol::smart_tool;

// Enough for every command a hub could send between two advances of a busy bus.
constexpr std::size_t kControllerQueueCapacity = 64;

Status validate(const SmartToolSimulatorConfig& c) noexcept {
  const RunPhysics& p = c.physics;
  const bool ok = st::valid_node_id(c.node_id) && !c.interface.empty() &&
                  c.heartbeat_period > Duration::zero() && p.torque_rate_nm_per_s > 0.0 &&
                  p.angle_rate_deg_per_s > 0.0 && p.max_run_time > Duration::zero() &&
                  p.slip_torque_fraction >= 0.0 && p.slip_torque_fraction < 1.0;
  return ok ? Status::ok() : Status(ErrorCode::kInvalidArgument);
}

}  // namespace

Expected<std::unique_ptr<SmartToolSimulator>> SmartToolSimulator::create(VirtualCanNetwork& network,
                                                                         SmartToolSimulatorConfig config) {
  if (!validate(config).is_ok()) {
    return make_error(ErrorCode::kInvalidArgument,
                      "smart tool simulator on '" + config.interface +
                          "': invalid configuration (node id 1..127, interface named, positive period, "
                          "rates and run time, slip fraction in [0, 1))");
  }
  const auto filters = st::controller_filters(config.node_id);
  CanConfig can;
  can.bus = "smart_tool_controller";
  can.interface = config.interface;
  can.filters.assign(filters.begin(), filters.end());
  auto node = network.open(can, VirtualCanNodeOptions{kControllerQueueCapacity, false});
  if (!node) return std::move(node).error();
  std::unique_ptr<SmartToolSimulator> sim(
      new SmartToolSimulator(network, std::move(config), std::move(*node)));
  network.attach(*sim);
  return sim;
}

SmartToolSimulator::SmartToolSimulator(VirtualCanNetwork& network, SmartToolSimulatorConfig config,
                                       std::unique_ptr<VirtualCanNode> node)
    : network_(network), config_(std::move(config)), node_(std::move(node)) {
  const Time t = now();
  last_advance_ = t;
  boot(t);
}

SmartToolSimulator::~SmartToolSimulator() {
  network_.detach(*this);
}

Time SmartToolSimulator::now() const noexcept {
  return network_.clock().now().mono;
}

void SmartToolSimulator::power_off() {
  const std::lock_guard lock(mutex_);
  advance_locked(now());
  powered_ = false;
  run_.reset();
  program_.reset();
  unsent_result_.reset();
  next_heartbeat_ = Time::max();
}

void SmartToolSimulator::power_on() {
  const std::lock_guard lock(mutex_);
  advance_locked(now());
  if (powered_) return;
  boot(last_advance_);
  advance_locked(last_advance_);
}

void SmartToolSimulator::raise_alarm(std::uint8_t alarm_bits) {
  const std::lock_guard lock(mutex_);
  const Time t = now();
  advance_locked(t);
  if (!powered_) return;
  alarms_ |= static_cast<std::uint8_t>(alarm_bits & st::alarm_bit::kAll);
  if (run_) end_run(last_advance_, RunEnd::kAlarm);
  send_status_if_changed(last_advance_);
}

void SmartToolSimulator::set_joint_slip(bool slipping) {
  const std::lock_guard lock(mutex_);
  advance_locked(now());
  slipping_ = slipping;
}

void SmartToolSimulator::set_bus_off(bool bus_off) {
  const std::lock_guard lock(mutex_);
  advance_locked(now());
  node_->set_node_state(bus_off ? CanBusState::kBusOff : CanBusState::kErrorActive);
  advance_locked(last_advance_);
}

SmartToolSnapshot SmartToolSimulator::snapshot() {
  const std::lock_guard lock(mutex_);
  advance_locked(now());
  const st::Status status = status_at(last_advance_);
  SmartToolSnapshot s;
  s.powered = powered_;
  s.link_up = link_up_;
  s.running = run_.has_value();
  s.direction = run_ && run_->is_reverse() ? st::Direction::kReverse : st::Direction::kForward;
  s.program = program_;
  s.alarms = alarms_;
  s.torque_cnm = status.torque_cnm;
  s.angle_ddeg = status.angle_ddeg;
  s.run_counter = run_counter_;
  s.heartbeat_counter = heartbeat_counter_;
  s.last_result = last_result_;
  s.ignored_frames = ignored_frames_;
  return s;
}

void SmartToolSimulator::advance(Time now) noexcept {
  const std::lock_guard lock(mutex_);
  advance_locked(now);
}

Time SmartToolSimulator::next_wakeup() const noexcept {
  const std::lock_guard lock(mutex_);
  if (!powered_) return Time::max();
  const Time run_end = run_ ? run_->natural_end() : Time::max();
  return std::min(next_heartbeat_, run_end);
}

void SmartToolSimulator::boot(Time now) noexcept {
  powered_ = true;
  heartbeat_counter_ = 0;
  next_heartbeat_ = now;
  program_.reset();
  alarms_ = 0;
  run_.reset();
  run_counter_ = 0;
  torque_reached_ = false;
  last_torque_cnm_ = 0;
  last_angle_ddeg_ = 0;
  last_result_.reset();
  unsent_result_.reset();
  last_sent_status_.reset();
}

void SmartToolSimulator::advance_locked(Time now) noexcept {
  // Two threads may read the clock in one order and get here in the other.
  now = std::max(now, last_advance_);
  if (!powered_) {
    // A controller without power hears nothing: frames sent meanwhile are lost.
    while (node_->receive(Duration::zero()).is_ok()) {
    }
    last_advance_ = now;
    return;
  }
  update_link(now);
  // Scheduled events in time order; a run that ends together with a heartbeat ends first, so
  // that the heartbeat already shows the controller idle.
  for (;;) {
    const Time run_end = run_ ? run_->natural_end() : Time::max();
    const Time next = std::min(next_heartbeat_, run_end);
    if (next > now) break;
    if (run_end <= next_heartbeat_) {
      end_run(run_end, run_->natural_cause());
      send_status_if_changed(run_end);
    } else {
      const Time at = next_heartbeat_;
      next_heartbeat_ += config_.heartbeat_period;
      // A bus-off controller's timer keeps counting: the hub sees the gap in the counter.
      if (link_up_) {
        send_heartbeat();
        send_status(at);
      }
      ++heartbeat_counter_;
    }
  }
  for (;;) {
    Result<CanFrame> frame = node_->receive(Duration::zero());
    if (!frame.is_ok()) break;
    handle_frame(frame.value(), now);
  }
  last_advance_ = now;
}

void SmartToolSimulator::update_link(Time now) noexcept {
  const bool up = node_->status().state < CanBusState::kBusOff;
  if (up == link_up_) return;
  link_up_ = up;
  if (!up) {
    // The motor must not keep turning while the hub cannot reach the controller.
    if (run_) end_run(now, RunEnd::kLinkLost);
    return;
  }
  if (unsent_result_) {
    send(st::encode(config_.node_id, *unsent_result_));
    unsent_result_.reset();
  }
  send_status(now);
}

void SmartToolSimulator::handle_frame(const CanFrame& frame, Time now) noexcept {
  if (const auto command = st::decode_run_command(frame, config_.node_id)) {
    switch (command->command) {
      case st::Command::kStop:
        if (run_) end_run(now, RunEnd::kStopped);
        break;
      case st::Command::kStart:
        // Ignored when it cannot be honoured; the next status shows the controller not running.
        if (!run_ && alarms_ == 0 && (command->direction == st::Direction::kReverse || program_)) {
          start_run(command->direction, now);
        }
        break;
      case st::Command::kResetAlarm:
        if (!run_) alarms_ = 0;
        break;
    }
    send_status_if_changed(now);
    return;
  }
  if (const auto program = st::decode_program_select(frame, config_.node_id)) {
    st::ProgramAck ack{*program, st::AckCode::kAccepted};
    if (run_) {
      ack.code = st::AckCode::kBusy;
    } else if (!st::valid_program(*program)) {
      ack.code = st::AckCode::kInvalid;
    } else {
      program_ = *program;
    }
    send(st::encode(config_.node_id, ack));
    send_status_if_changed(now);
    return;
  }
  ++ignored_frames_;
}

void SmartToolSimulator::start_run(st::Direction direction, Time now) noexcept {
  ++run_counter_;
  torque_reached_ = false;
  run_ = direction == st::Direction::kReverse
             ? TighteningRun::reverse(config_.physics, now)
             : TighteningRun::forward(*program_, config_.physics, slipping_, now);
}

void SmartToolSimulator::end_run(Time at, RunEnd cause) noexcept {
  last_torque_cnm_ = run_->torque_cnm(at);
  last_angle_ddeg_ = run_->angle_ddeg(at);
  if (!run_->is_reverse()) {
    const st::RunResult result = run_->result(at, cause, run_counter_);
    torque_reached_ = cause == RunEnd::kTorqueReached;
    last_result_ = result;
    if (link_up_) {
      send(st::encode(config_.node_id, result));
    } else {
      unsent_result_ = result;
    }
  }
  run_.reset();
}

void SmartToolSimulator::send(const CanFrame& frame) noexcept {
  // A controller that cannot transmit loses the frame; the protocol's periodic frames cover it.
  node_->send(frame, Duration::zero()).ignore();
}

void SmartToolSimulator::send_heartbeat() noexcept {
  st::Heartbeat hb;
  hb.counter = heartbeat_counter_;
  hb.state = alarms_ != 0 ? st::ControllerState::kAlarm
                          : (run_ ? st::ControllerState::kRunning : st::ControllerState::kIdle);
  send(st::encode(config_.node_id, hb));
}

st::Status SmartToolSimulator::status_at(Time now) const noexcept {
  st::Status s;
  if (run_) s.flags |= st::status_flag::kRunning;
  if (run_ && run_->is_reverse()) s.flags |= st::status_flag::kReverse;
  if (torque_reached_) s.flags |= st::status_flag::kTorqueReached;
  if (program_) s.flags |= st::status_flag::kProgramSelected;
  if (alarms_ != 0) s.flags |= st::status_flag::kAlarm;
  s.alarms = alarms_;
  s.torque_cnm = run_ ? run_->torque_cnm(now) : last_torque_cnm_;
  s.angle_ddeg = run_ ? run_->angle_ddeg(now) : last_angle_ddeg_;
  s.program = program_ ? program_->number : 0;
  s.run_counter = run_counter_;
  return s;
}

void SmartToolSimulator::send_status(Time now) noexcept {
  if (!link_up_) return;
  const st::Status s = status_at(now);
  send(st::encode(config_.node_id, s));
  last_sent_status_ = s;
}

void SmartToolSimulator::send_status_if_changed(Time now) noexcept {
  // "Changed" means the flags, alarms, program or run counter; live torque and angle alone
  // go out with the periodic status only, as the protocol says.
  const st::Status s = status_at(now);
  if (last_sent_status_ && last_sent_status_->flags == s.flags && last_sent_status_->alarms == s.alarms &&
      last_sent_status_->program == s.program && last_sent_status_->run_counter == s.run_counter) {
    return;
  }
  send_status(now);
}

}  // namespace hubrt::hal::fake
