// A board as the loader returns it: which chip, line, interface or endpoint each logical signal,
// bus and device of the hubs is wired to, and (simulation boards) which simulators stand in for
// the devices. The schema is documented in boards/README.md.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/time.h"
#include "hubrt/hal/badge_reader.h"
#include "hubrt/hal/can_bus.h"
#include "hubrt/hal/common/gpio_chip_selector.h"
#include "hubrt/hal/digital_io.h"
#include "hubrt/hal/http_client.h"
#include "hubrt/hal/modbus_client.h"

namespace hubrt::hal {

// Where something was declared in the board file (1-based; 0 when unknown).
struct SourceLocation {
  int line = 0;
  int column = 0;
};

struct BoardGpioChip {
  std::string alias;  // key under gpio.chips, e.g. "main"
  GpioChipSelectorKind kind = GpioChipSelectorKind::kLabel;
  std::string selector;  // what goes into Digital*Config::chip, e.g. "pinctrl-bcm2711"
  SourceLocation where;
};

struct BoardInput {
  DigitalInputConfig config;  // config.signal is the logical name, config.chip the chip's selector
  std::string chip_alias;
  SourceLocation where;
};

struct BoardOutput {
  DigitalOutputConfig config;
  std::string chip_alias;
  SourceLocation where;
};

struct BoardCanBus {
  CanConfig config;  // config.bus is the logical name
  SourceLocation where;
};

struct BoardModbusDevice {
  ModbusConfig config;  // config.device is the logical name; TCP port 0 = the simulator's port
  SourceLocation where;
};

struct BoardHttpDevice {
  // config.device is the logical name; config.authorization stays empty here (the secret is in
  // authorization_file, read when the device is opened: load_http_authorization()), except on
  // simulation boards, which may give it inline.
  HttpConfig config;
  std::string authorization_file;  // empty: none (or inline on a simulation board)
  SourceLocation where;
};

struct BoardBadgeReader {
  BadgeReaderConfig config;  // config.reader is the logical name (key under rfid:)
  SourceLocation where;
};

// --- simulation: only on boards meant for the fake backend -----------------------------------

struct SimPressureSupplyConfig {
  std::string name;          // e.g. "main_air"
  std::string switch_input;  // input signal of its pressure switch (active while pressure is OK)
  bool ok = true;            // pressure at start
  SourceLocation where;
};

struct SimValveConfig {
  std::string output;                 // output signal driving the solenoid (active = energised)
  std::vector<std::string> confirms;  // input signals active in the energised end position
  std::string supply;                 // pressure supply name; empty = always pressurised
  Duration actuation{0};
  SourceLocation where;
};

struct SimDockSensorConfig {
  std::string input;  // input signal, active while the slot is occupied
  Duration bounce{0};
  bool occupied = false;  // at start
  SourceLocation where;
};

struct SimInputLevel {
  std::string input;  // a plain input (no simulator of its own)
  bool active = false;
  SourceLocation where;
};

struct SimCanDevice {
  std::string bus;        // CAN bus name (key under can:)
  std::string simulator;  // "smart_tool"
  unsigned node_id = 0;   // 0 = the protocol's default
  SourceLocation where;
};

struct SimModbusDevice {
  std::string device;     // Modbus device name (key under modbus:)
  std::string simulator;  // "lift_drive"
  SourceLocation where;
};

struct SimMirPosition {
  std::string name;
  double x = 0, y = 0, yaw_deg = 0;
};

struct SimHttpDevice {
  std::string device;     // HTTP device name (key under http:)
  std::string simulator;  // "mir100"
  std::string robot_name;
  std::vector<SimMirPosition> positions;  // the map's named positions; the platform starts at the first
  double speed_m_s = 1.0;
  SourceLocation where;
};

struct SimulationConfig {
  unsigned chip_lines = 32;  // lines of every fake chip
  std::vector<SimPressureSupplyConfig> pressure_supplies;
  std::vector<SimValveConfig> valves;
  std::vector<SimDockSensorConfig> dock_sensors;
  std::vector<SimInputLevel> inputs;
  std::vector<SimCanDevice> can;
  std::vector<SimModbusDevice> modbus;
  std::vector<SimHttpDevice> http;
};

struct BoardConfig {
  std::string file;  // as given to the loader, for messages
  std::string name;
  std::string description;
  std::string arch;               // arm64 | armhf | x86_64
  std::vector<std::string> hubs;  // hub types this board is wired for
  std::vector<BoardGpioChip> chips;
  std::vector<BoardInput> inputs;
  std::vector<BoardOutput> outputs;
  std::vector<BoardCanBus> can;
  std::vector<BoardModbusDevice> modbus;
  std::vector<BoardHttpDevice> http;
  std::vector<BoardBadgeReader> badge_readers;  // rfid:
  std::optional<SimulationConfig> simulation;

  // Look-ups by logical name; nullptr when absent. Never allocate.
  [[nodiscard]] const BoardInput* find_input(std::string_view signal) const noexcept;
  [[nodiscard]] const BoardOutput* find_output(std::string_view signal) const noexcept;
  [[nodiscard]] const BoardCanBus* find_can(std::string_view bus) const noexcept;
  [[nodiscard]] const BoardModbusDevice* find_modbus(std::string_view device) const noexcept;
  [[nodiscard]] const BoardHttpDevice* find_http(std::string_view device) const noexcept;
  [[nodiscard]] const BoardBadgeReader* find_badge_reader(std::string_view reader) const noexcept;
  [[nodiscard]] const BoardGpioChip* find_chip(std::string_view alias) const noexcept;
  [[nodiscard]] bool wired_for(std::string_view hub) const noexcept;
};

// The Authorization header value of `device`: its inline value (simulation boards), or the first
// line of its authorization_file (e.g. "Basic <base64>", as MiR's REST API takes it), or empty
// when it has neither. Errors (naming the device and file): kNotFound / kPermissionDenied (the
// file), kInvalidArgument (empty, over 512 bytes, a control character).
Expected<std::string> load_http_authorization(const BoardHttpDevice& device);

}  // namespace hubrt::hal
