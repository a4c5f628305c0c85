// A smart fastening tool controller on a virtual CAN bus, speaking exactly
// docs/protocols/smart-tool-can.md: heartbeat and status every period, program select
// acknowledged, forward runs that build torque toward the target while the angle grows and end
// with a result frame (OK / NOK with reasons), reverse runs until Stop, and injectable faults.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/fake/tightening_run.h"
#include "hubrt/hal/fake/virtual_can_network.h"
#include "hubrt/protocol/smart_tool_can.h"

namespace hubrt::hal::fake {

struct SmartToolSimulatorConfig {
  std::string interface = "vcan0";  // the virtual bus the controller sits on
  std::uint8_t node_id = protocol::smart_tool::kDefaultNodeId;
  Duration heartbeat_period = protocol::smart_tool::kHeartbeatPeriod;
  RunPhysics physics;  // torque rate, spindle speed, maximum run time, slip fraction
};

// What the controller is doing, for tests and for the fake hub's diagnostics.
struct SmartToolSnapshot {
  bool powered = false;
  bool link_up = false;  // its CAN controller is neither bus-off nor down
  bool running = false;
  protocol::smart_tool::Direction direction = protocol::smart_tool::Direction::kForward;
  std::optional<protocol::smart_tool::Program> program;
  std::uint8_t alarms = 0;
  std::uint16_t torque_cnm = 0;
  std::uint16_t angle_ddeg = 0;
  std::uint8_t run_counter = 0;
  std::uint8_t heartbeat_counter = 0;  // of the next heartbeat
  std::optional<protocol::smart_tool::RunResult> last_result;
  std::uint64_t ignored_frames = 0;  // frames for this node it could not use (bad values)
};

// Thread-safe: the network advances it from whichever thread uses the bus, and the fault
// injection calls may come from any other thread. Every call takes effect at the network clock's
// now, after the controller has been brought up to that time.
class SmartToolSimulator final : public VirtualCanDevice {
 public:
  // Opens the controller's node on `config.interface`, attaches to `network` and powers on at
  // network.clock().now() (its first heartbeat, counter 0, is due at once). The simulator must be
  // destroyed before `network`.
  // Errors: kInvalidArgument (node id outside 1..127, non-positive rates, period or run time,
  // slip fraction outside [0, 1), empty interface).
  static Expected<std::unique_ptr<SmartToolSimulator>> create(VirtualCanNetwork& network,
                                                              SmartToolSimulatorConfig config);
  // Detaches from the network: never called again afterwards.
  ~SmartToolSimulator() override;

  // Controller lost: it goes silent (no heartbeat, no status, no answers) and forgets its
  // program; a running run is cut without a result.
  void power_off();
  // Boots again: heartbeat counter 0, no program, no alarm; first heartbeat at once.
  void power_on();
  // Latches alarm bits (protocol::smart_tool::alarm_bit); a forward run in progress ends NOK with
  // the alarm reason. Cleared by the Reset alarm command while idle.
  void raise_alarm(std::uint8_t alarm_bits);
  // Joint slip: runs started from now on stall at the slip fraction of the target torque and end
  // NOK (angle high, or run timeout) instead of reaching the torque.
  void set_joint_slip(bool slipping);
  // This controller's CAN controller goes bus-off (true) or recovers (false). While bus-off it
  // stops the motor and sends nothing; on recovery it first reports the aborted run (link lost).
  // For a whole-bus fault use VirtualCanNetwork::set_bus_state instead.
  void set_bus_off(bool bus_off);

  [[nodiscard]] SmartToolSnapshot snapshot();
  [[nodiscard]] const SmartToolSimulatorConfig& config() const noexcept { return config_; }

  void advance(Time now) noexcept override;
  [[nodiscard]] Time next_wakeup() const noexcept override;

 private:
  SmartToolSimulator(VirtualCanNetwork& network, SmartToolSimulatorConfig config,
                     std::unique_ptr<VirtualCanNode> node);

  // All below: called with mutex_ held.
  void advance_locked(Time now) noexcept;
  void update_link(Time now) noexcept;
  void handle_frame(const CanFrame& frame, Time now) noexcept;
  void start_run(protocol::smart_tool::Direction direction, Time now) noexcept;
  void end_run(Time at, RunEnd cause) noexcept;
  void boot(Time now) noexcept;
  void send(const CanFrame& frame) noexcept;
  void send_heartbeat() noexcept;
  void send_status(Time now) noexcept;
  void send_status_if_changed(Time now) noexcept;
  [[nodiscard]] protocol::smart_tool::Status status_at(Time now) const noexcept;
  [[nodiscard]] Time now() const noexcept;

  VirtualCanNetwork& network_;
  const SmartToolSimulatorConfig config_;
  std::unique_ptr<VirtualCanNode> node_;

  mutable std::mutex mutex_;
  Time last_advance_{};
  bool powered_ = false;
  bool link_up_ = true;
  bool slipping_ = false;
  std::uint8_t heartbeat_counter_ = 0;
  Time next_heartbeat_ = Time::max();
  std::optional<protocol::smart_tool::Program> program_;
  std::uint8_t alarms_ = 0;
  std::optional<TighteningRun> run_;  // present while a run is in progress (no allocation)
  std::uint8_t run_counter_ = 0;
  bool torque_reached_ = false;
  std::uint16_t last_torque_cnm_ = 0;
  std::uint16_t last_angle_ddeg_ = 0;
  std::optional<protocol::smart_tool::RunResult> last_result_;
  std::optional<protocol::smart_tool::RunResult> unsent_result_;  // held while bus-off
  std::optional<protocol::smart_tool::Status> last_sent_status_;
  std::uint64_t ignored_frames_ = 0;
};

}  // namespace hubrt::hal::fake
