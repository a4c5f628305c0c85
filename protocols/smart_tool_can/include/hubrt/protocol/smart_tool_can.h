// The smart fastening tool controller's CAN protocol, exactly as docs/protocols/smart-tool-can.md
// defines it: frame ids, payload layouts and scaling, as constants and pure encode/decode
// functions. The simulator and the hub logic both use these, so the two cannot drift apart.
//
// Everything here is pure, never allocates and is safe to call from any thread.
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <optional>

#include "hubrt/base/time.h"
#include "hubrt/hal/can_bus.h"

namespace hubrt::protocol::smart_tool {

inline constexpr std::uint32_t kBitrate = 500'000;
inline constexpr std::uint8_t kMinNodeId = 1;
inline constexpr std::uint8_t kMaxNodeId = 127;
inline constexpr std::uint8_t kDefaultNodeId = 1;

inline constexpr Duration kHeartbeatPeriod = std::chrono::milliseconds(100);
// The hub declares the controller lost when no heartbeat came for this many periods plus
// kHeartbeatGrace: 3 × 100 ms + 50 ms = 350 ms.
inline constexpr int kMissedHeartbeatsForLoss = 3;
inline constexpr Duration kHeartbeatGrace = std::chrono::milliseconds(50);
inline constexpr Duration kControllerLostAfter =
    kMissedHeartbeatsForLoss * kHeartbeatPeriod + kHeartbeatGrace;

// A frame id is the function's base plus the node id (CANopen-like, but this is not CANopen).
// Lower ids win arbitration: the run command (Stop) has the highest priority.
enum class Function : std::uint16_t {
  kRunCommand = 0x080,     // hub → tool
  kProgramSelect = 0x100,  // hub → tool
  kStatus = 0x180,         // tool → hub
  kResult = 0x200,         // tool → hub
  kProgramAck = 0x280,     // tool → hub
  kHeartbeat = 0x700,      // tool → hub
};

// Precondition: node_id in [kMinNodeId, kMaxNodeId].
constexpr std::uint32_t frame_id(Function function, std::uint8_t node_id) noexcept {
  return static_cast<std::uint32_t>(function) + node_id;
}

[[nodiscard]] constexpr bool valid_node_id(unsigned node_id) noexcept {
  return node_id >= kMinNodeId && node_id <= kMaxNodeId;
}

// Exact-id filters for what the hub receives from node `node_id` (status, result, ack, heartbeat).
std::array<hal::CanFilter, 4> hub_filters(std::uint8_t node_id) noexcept;
// Exact-id filters for what the controller receives (run command, program select).
std::array<hal::CanFilter, 2> controller_filters(std::uint8_t node_id) noexcept;

// ---- Run command (hub → tool, DLC 2) --------------------------------------------------------
enum class Command : std::uint8_t { kStop = 0, kStart = 1, kResetAlarm = 2 };
enum class Direction : std::uint8_t { kForward = 0, kReverse = 1 };

struct RunCommand {
  Command command = Command::kStop;
  Direction direction = Direction::kForward;  // meaningful for kStart only; sent as 0 otherwise
  friend bool operator==(const RunCommand&, const RunCommand&) = default;
};

// ---- Program select (hub → tool, DLC 8) and its acknowledgement (tool → hub, DLC 8) ---------
struct Program {
  std::uint8_t number = 0;              // 1..255; 0 means "none" and is rejected
  std::uint16_t torque_target_cnm = 0;  // 0.01 Nm; 1..65535
  std::uint16_t angle_min_ddeg = 0;     // 0.1°
  std::uint16_t angle_max_ddeg = 0;     // 0.1°; must be >= angle_min_ddeg
  friend bool operator==(const Program&, const Program&) = default;
};

// True when the controller accepts the program's parameters (number, torque non-zero, min <= max).
[[nodiscard]] constexpr bool valid_program(const Program& p) noexcept {
  return p.number != 0 && p.torque_target_cnm != 0 && p.angle_min_ddeg <= p.angle_max_ddeg;
}

enum class AckCode : std::uint8_t { kAccepted = 0, kInvalid = 1, kBusy = 2 };

struct ProgramAck {
  Program program;  // the request as received, echoed
  AckCode code = AckCode::kAccepted;
  friend bool operator==(const ProgramAck&, const ProgramAck&) = default;
};

// ---- Status (tool → hub, DLC 8) --------------------------------------------------------------
namespace status_flag {
inline constexpr std::uint8_t kRunning = 0x01;
inline constexpr std::uint8_t kReverse = 0x02;
inline constexpr std::uint8_t kTorqueReached = 0x04;
inline constexpr std::uint8_t kProgramSelected = 0x08;
inline constexpr std::uint8_t kAlarm = 0x10;
}  // namespace status_flag

namespace alarm_bit {
inline constexpr std::uint8_t kOvercurrent = 0x01;
inline constexpr std::uint8_t kOvertemperature = 0x02;
inline constexpr std::uint8_t kTransducerFault = 0x04;
inline constexpr std::uint8_t kAll = 0x07;
}  // namespace alarm_bit

struct Status {
  std::uint8_t flags = 0;        // status_flag bits
  std::uint8_t alarms = 0;       // alarm_bit bits
  std::uint16_t torque_cnm = 0;  // live during a run, final after it
  std::uint16_t angle_ddeg = 0;
  std::uint8_t program = 0;      // selected program number, 0 = none
  std::uint8_t run_counter = 0;  // number of the current / last run (wraps 255 → 0)
  friend bool operator==(const Status&, const Status&) = default;
};

// ---- Result (tool → hub, DLC 8), once at the end of every forward run ----------------------
namespace nok_reason {
inline constexpr std::uint8_t kTorqueLow = 0x01;         // target torque not reached
inline constexpr std::uint8_t kAngleLow = 0x02;          // torque reached below the angle window
inline constexpr std::uint8_t kAngleHigh = 0x04;         // angle passed the window's maximum
inline constexpr std::uint8_t kStoppedByCommand = 0x08;  // Stop before the torque was reached
inline constexpr std::uint8_t kAlarm = 0x10;             // an alarm ended the run
inline constexpr std::uint8_t kRunTimeout = 0x20;        // the maximum run time elapsed
inline constexpr std::uint8_t kLinkLost = 0x40;          // the controller went bus-off mid-run
}  // namespace nok_reason

struct RunResult {
  std::uint8_t program = 0;
  std::uint16_t torque_cnm = 0;  // final torque, 0.01 Nm
  std::uint16_t angle_ddeg = 0;  // final angle, 0.1°
  bool ok = false;               // sent as byte 5 = 0x01 (OK) / 0x00 (NOK)
  std::uint8_t nok_reasons = 0;  // nok_reason bits; 0 exactly when ok
  std::uint8_t run_counter = 0;
  friend bool operator==(const RunResult&, const RunResult&) = default;
};

// ---- Heartbeat (tool → hub, DLC 2, every 100 ms) --------------------------------------------
enum class ControllerState : std::uint8_t { kIdle = 1, kRunning = 2, kAlarm = 3 };

struct Heartbeat {
  std::uint8_t counter = 0;  // +1 per heartbeat, wraps 255 → 0, 0 after power-up
  ControllerState state = ControllerState::kIdle;
  friend bool operator==(const Heartbeat&, const Heartbeat&) = default;
};

// ---- Encoding: each returns the complete frame for node `node_id` ----------------------------
hal::CanFrame encode(std::uint8_t node_id, const RunCommand& message) noexcept;
hal::CanFrame encode(std::uint8_t node_id, const Program& message) noexcept;
hal::CanFrame encode(std::uint8_t node_id, const ProgramAck& message) noexcept;
hal::CanFrame encode(std::uint8_t node_id, const Status& message) noexcept;
hal::CanFrame encode(std::uint8_t node_id, const RunResult& message) noexcept;
hal::CanFrame encode(std::uint8_t node_id, const Heartbeat& message) noexcept;

// ---- Decoding: nullopt when the frame is not that message of node `node_id` (other id,
// extended or remote frame, wrong DLC) or carries a value the protocol does not define. -------
std::optional<RunCommand> decode_run_command(const hal::CanFrame& frame, std::uint8_t node_id) noexcept;
std::optional<Program> decode_program_select(const hal::CanFrame& frame, std::uint8_t node_id) noexcept;
std::optional<ProgramAck> decode_program_ack(const hal::CanFrame& frame, std::uint8_t node_id) noexcept;
std::optional<Status> decode_status(const hal::CanFrame& frame, std::uint8_t node_id) noexcept;
std::optional<RunResult> decode_result(const hal::CanFrame& frame, std::uint8_t node_id) noexcept;
std::optional<Heartbeat> decode_heartbeat(const hal::CanFrame& frame, std::uint8_t node_id) noexcept;

// Scaling helpers (wire units ↔ SI-ish units used in logs and states).
constexpr double to_newton_metres(std::uint16_t cnm) noexcept {
  return cnm / 100.0;
}
constexpr double to_degrees(std::uint16_t ddeg) noexcept {
  return ddeg / 10.0;
}

}  // namespace hubrt::protocol::smart_tool
