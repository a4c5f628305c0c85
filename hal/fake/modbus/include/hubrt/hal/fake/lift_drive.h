// The lift's motor drive as a device model behind the register map of
// docs/protocols/lift-drive-modbus.md: it moves toward its target at the set speed (position
// computed from the time passed in with each access), reports in-position and the end-of-travel
// limits, and faults like a drive does (overcurrent, following error when the load is jammed,
// overtemperature, communication watchdog), with reset through the control word.
//
// Register-level and transport-free: LiftDriveServer puts it behind a real libmodbus TCP server.
#pragma once

#include <array>
#include <cstdint>
#include <mutex>
#include <span>

#include "hubrt/base/time.h"
#include "hubrt/protocol/lift_drive_modbus.h"

namespace hubrt::hal::fake {

// Modbus exception codes a device answers with (the protocol's numbering).
enum class ModbusException : std::uint8_t {
  kNone = 0,
  kIllegalFunction = 1,
  kIllegalDataAddress = 2,
  kIllegalDataValue = 3,
};

struct LiftDriveConfig {
  std::uint8_t unit_id = protocol::lift_drive::kDefaultUnitId;
  std::uint16_t travel_tenth_mm = 4000;  // 400.0 mm: targets beyond are refused
  std::uint16_t initial_position_tenth_mm = 0;
  std::uint16_t max_speed_mm_s = 200;
  std::uint16_t default_speed_mm_s = 50;
  double in_position_window_mm = 0.5;     // also how close to an end a limit switch trips
  double following_error_limit_mm = 5.0;  // lag behind the commanded motion that trips a fault
};

// Everything a master can read, at one instant.
struct LiftDriveRegisters {
  std::array<std::uint16_t, protocol::lift_drive::holding::kCount> holding{};
  std::array<std::uint16_t, protocol::lift_drive::input::kCount> input{};
  [[nodiscard]] std::uint16_t control_word() const noexcept {
    return holding[protocol::lift_drive::holding::kControlWord];
  }
  [[nodiscard]] std::uint16_t status_word() const noexcept {
    return input[protocol::lift_drive::input::kStatusWord];
  }
};

// Thread-safe: the server thread serves requests while a test thread injects faults. Times passed
// in must not go backwards (an earlier time is treated as the latest one seen).
class LiftDrive {
 public:
  // Precondition: config values within their documented ranges (initial position <= travel,
  // 1 <= default speed <= max speed).
  LiftDrive(LiftDriveConfig config, Time now);

  // ---- Modbus access; every call counts as communication for the watchdog -------------------
  LiftDriveRegisters read(Time now);
  // Writes holding registers [address, address + values.size()), all or nothing.
  // Returns kIllegalDataAddress outside the map, kIllegalDataValue for a value out of range
  // (reserved control bits, target beyond travel, speed 0 or above max, watchdog > 60000 ms).
  ModbusException write_holding(std::uint16_t address, std::span<const std::uint16_t> values, Time now);
  // Writes coils (= control word bits) [address, address + values.size()), all or nothing.
  ModbusException write_coils(std::uint16_t address, std::span<const bool> values, Time now);

  // ---- Physical faults, as a test or the fake station injects them ----------------------------
  // Overcurrent trips at once; a reset clears it.
  void inject_overcurrent(Time now);
  // The motor is hot: the fault trips and cannot be reset until it has cooled (hot = false).
  void set_overtemperature(bool hot, Time now);
  // The load is jammed: commanded motion makes no progress, the lag grows at the set speed and
  // trips a following error beyond the limit. Unjamming lets motion resume.
  void set_blocked(bool blocked, Time now);

  [[nodiscard]] const LiftDriveConfig& config() const noexcept { return config_; }
  // Exact position, for tests (the register rounds to 0.1 mm).
  [[nodiscard]] double position_mm(Time now);

 private:
  void update_locked(Time now) noexcept;
  void integrate_locked(Time to) noexcept;
  void trip_locked(protocol::lift_drive::FaultCode code) noexcept;
  void apply_control_locked(std::uint16_t control) noexcept;
  ModbusException write_holding_locked(std::uint16_t address, std::span<const std::uint16_t> values) noexcept;
  [[nodiscard]] bool motion_commanded_locked() const noexcept;
  [[nodiscard]] double target_mm_locked() const noexcept;
  [[nodiscard]] LiftDriveRegisters registers_locked() const noexcept;

  const LiftDriveConfig config_;
  std::mutex mutex_;
  Time last_update_;
  Time last_request_;
  std::uint16_t control_ = 0;
  std::uint16_t target_ = 0;
  std::uint16_t speed_ = 0;
  std::uint16_t watchdog_ms_ = 0;
  double position_mm_ = 0.0;
  double lag_mm_ = 0.0;  // how far the commanded motion is ahead of the (jammed) load
  bool enabled_ = false;
  bool hot_ = false;
  bool blocked_ = false;
  protocol::lift_drive::FaultCode fault_ = protocol::lift_drive::FaultCode::kNone;
};

}  // namespace hubrt::hal::fake
