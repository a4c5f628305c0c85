// The lift's motor drive register map, exactly as docs/protocols/lift-drive-modbus.md defines it.
// Shared by the simulator and the hub logic. Addresses are 0-based PDU addresses (holding
// register 0 is "40001" in the 1-based notation of drive manuals).
#pragma once

#include <chrono>
#include <cstdint>

#include "hubrt/base/time.h"

namespace hubrt::protocol::lift_drive {

inline constexpr std::uint8_t kDefaultUnitId = 1;
inline constexpr std::uint16_t kDefaultTcpPort = 502;
// The drive answers within this; clients should allow kRecommendedResponseTimeout.
inline constexpr Duration kDriveAnswerTime = std::chrono::milliseconds(10);
inline constexpr Duration kRecommendedResponseTimeout = std::chrono::milliseconds(100);

// Holding registers (read 0x03, write 0x06 / 0x10).
namespace holding {
inline constexpr std::uint16_t kControlWord = 0;     // control bits below
inline constexpr std::uint16_t kTargetPosition = 1;  // 0.1 mm, 0..travel
inline constexpr std::uint16_t kSpeed = 2;           // mm/s, 1..max speed
inline constexpr std::uint16_t kWatchdogMs = 3;      // communication watchdog, ms, 0 = off
inline constexpr std::uint16_t kCount = 4;
}  // namespace holding

// Input registers (read 0x04).
namespace input {
inline constexpr std::uint16_t kActualPosition = 0;  // 0.1 mm
inline constexpr std::uint16_t kStatusWord = 1;      // status bits below
inline constexpr std::uint16_t kFaultCode = 2;       // FaultCode
inline constexpr std::uint16_t kActualSpeed = 3;     // mm/s, signed (two's complement), + = up
inline constexpr std::uint16_t kCount = 4;
}  // namespace input

// Control word bits; coils 0..3 are the same bits (0x01 / 0x05 / 0x0F).
namespace control {
inline constexpr std::uint16_t kEnable = 0x0001;      // level; power stage needs a 0→1 edge
inline constexpr std::uint16_t kMove = 0x0002;        // level: move toward the target
inline constexpr std::uint16_t kStop = 0x0004;        // level: halt and hold (overrides move)
inline constexpr std::uint16_t kResetFault = 0x0008;  // rising edge: clear the fault
inline constexpr std::uint16_t kAll = 0x000F;
inline constexpr std::uint16_t kCoilCount = 4;
}  // namespace control

// Status word bits; discrete inputs 0..5 are the same bits (0x02).
namespace status {
inline constexpr std::uint16_t kEnabled = 0x0001;  // power stage on
inline constexpr std::uint16_t kMoving = 0x0002;
inline constexpr std::uint16_t kInPosition = 0x0004;  // not moving and within 0.5 mm of the target
inline constexpr std::uint16_t kLimitUp = 0x0008;     // upper end of travel
inline constexpr std::uint16_t kLimitDown = 0x0010;   // lower end of travel
inline constexpr std::uint16_t kFault = 0x0020;
inline constexpr std::uint16_t kDiscreteInputCount = 6;
}  // namespace status

enum class FaultCode : std::uint16_t {
  kNone = 0,
  kOvercurrent = 1,
  kFollowingError = 2,
  kOvertemperature = 3,
  kWatchdog = 4,  // communication watchdog expired while enabled
};

inline constexpr std::uint16_t kMaxWatchdogMs = 60'000;
// Conversions between wire units and millimetres.
constexpr double to_mm(std::uint16_t tenth_mm) noexcept {
  return tenth_mm / 10.0;
}

}  // namespace hubrt::protocol::lift_drive
