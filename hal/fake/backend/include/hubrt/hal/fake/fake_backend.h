// The Backend for a whole station on one host: fake GPIO chips with simulated valves, pressure
// supplies, dock sensors and settable inputs; a virtual CAN network with the simulated smart tool
// controller; the lift-drive simulator as a real libmodbus TCP server on loopback, reached through
// the real libmodbus client; a simulated RFID reader for every rfid: reader of the board. Built
// from a board's simulation section (boards/host-sim.yaml).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/backend.h"
#include "hubrt/hal/board/board_config.h"
#include "hubrt/hal/fake/dock_presence_sensor.h"
#include "hubrt/hal/fake/fake_gpio.h"
#include "hubrt/hal/fake/lift_drive.h"
#include "hubrt/hal/fake/lift_drive_server.h"
#include "hubrt/hal/fake/mir_platform.h"
#include "hubrt/hal/fake/mir_sim_server.h"
#include "hubrt/hal/fake/pneumatic_valve.h"
#include "hubrt/hal/fake/pressure_supply.h"
#include "hubrt/hal/fake/settable_input.h"
#include "hubrt/hal/fake/simulated_badge_reader.h"
#include "hubrt/hal/fake/smart_tool_simulator.h"
#include "hubrt/hal/fake/virtual_can_network.h"

namespace hubrt::hal::fake {

// Devices behave as the Linux backend's do (same errors, polarity, debouncing through
// DebouncedInput); the test hooks below reach the chips and simulators behind them, by the
// board's logical names.
//
// Thread-safety: open_* as Backend. The GPIO side (FakeGpio, its simulators and the devices
// opened from it) belongs to one thread, the one running the cycle: hooks that touch it must run
// there too. The CAN network, smart tool and lift drive simulators are thread-safe.
class FakeBackend final : public Backend {
 public:
  // One fake chip per board chip, named by its selector (e.g. "sim-dock") with
  // simulation.chip_lines lines; the simulators of the simulation section; every other input gets
  // a SettableInput (initial level from simulation.inputs, else inactive); the CAN and Modbus
  // simulators are created and the Modbus servers started on their loopback address.
  // `clock` drives every simulator and must outlive the backend.
  // Errors: kInvalidArgument (no simulation section, or a simulated Modbus device not on a
  // loopback address), and those of SmartToolSimulator::create and LiftDriveServer::start.
  static Expected<std::unique_ptr<FakeBackend>> create(const BoardConfig& board, const Clock& clock);
  ~FakeBackend() override;

  // Errors: as FakeGpio::open_input; debounced when config.debounce > 0.
  Expected<std::unique_ptr<DigitalInput>> open_input(const DigitalInputConfig& config) override;
  Expected<std::unique_ptr<DigitalOutput>> open_output(const DigitalOutputConfig& config) override;
  // A node on the virtual bus config.interface. Errors: as VirtualCanNetwork::open.
  Expected<std::unique_ptr<CanBus>> open_can(const CanConfig& config) override;
  // A real libmodbus client connected to the simulator of config.device (its port put in for the
  // board's port 0). Errors: kNotFound (no simulator for that device), those of open_libmodbus.
  Expected<std::unique_ptr<ModbusClient>> open_modbus(const ModbusConfig& config) override;
  // A real cpp-httplib client connected to the MiR simulator of config.device (its port put in).
  // Errors: kNotFound (no simulator for that device), those of open_httplib.
  Expected<std::unique_ptr<HttpClient>> open_http(const HttpConfig& config) override;
  // The simulated reader of the board's rfid: entry config.reader (every reader of the board has
  // one). Errors: kNotFound (no such reader, or it is unplugged).
  Expected<std::unique_ptr<BadgeReader>> open_badge_reader(const BadgeReaderConfig& config) override;

  // --- Test hooks, by logical name (nullptr when the board has no such thing) --------------------
  [[nodiscard]] FakeGpio& gpio() noexcept { return gpio_; }
  [[nodiscard]] VirtualCanNetwork& can_network() noexcept { return can_network_; }
  [[nodiscard]] PneumaticValve* valve(std::string_view output_signal) noexcept;
  [[nodiscard]] PressureSupply* pressure_supply(std::string_view name) noexcept;
  [[nodiscard]] DockPresenceSensor* dock_sensor(std::string_view input_signal) noexcept;
  // The plain inputs: every input no valve, supply or dock sensor drives.
  [[nodiscard]] SettableInput* input(std::string_view input_signal) noexcept;
  [[nodiscard]] SmartToolSimulator* smart_tool(std::string_view can_bus) noexcept;
  [[nodiscard]] LiftDrive* lift_drive(std::string_view modbus_device) noexcept;
  [[nodiscard]] LiftDriveServer* lift_drive_server(std::string_view modbus_device) noexcept;
  [[nodiscard]] MirPlatform* mir_platform(std::string_view http_device) noexcept;
  [[nodiscard]] MirSimServer* mir_server(std::string_view http_device) noexcept;
  [[nodiscard]] SimulatedBadgeReader* badge_reader(std::string_view reader) noexcept;

  // The chip and line a signal is wired to, for the chip's own hooks (history, faults).
  struct Wiring {
    FakeGpioChip* chip = nullptr;
    unsigned line = 0;
    Polarity polarity = Polarity::kActiveHigh;
  };
  // Errors: kNotFound (no such input or output on the board).
  [[nodiscard]] Result<Wiring> wiring(std::string_view signal) noexcept;
  // Whether a signal's line shows its active level now (polarity applied). Errors: kNotFound.
  [[nodiscard]] Result<bool> active(std::string_view signal) noexcept;
  struct SignalChange {
    Time at;
    bool active = false;
    friend bool operator==(const SignalChange&, const SignalChange&) = default;
  };
  // A signal's line changes in logical terms, oldest first (empty for an unknown signal).
  [[nodiscard]] std::vector<SignalChange> history(std::string_view signal);

 private:
  template <class T>
  struct Named {
    std::string name;
    T* item = nullptr;
  };
  struct SimulatedLift {
    std::string device;
    std::string host;
    std::unique_ptr<LiftDrive> drive;
    std::unique_ptr<LiftDriveServer> server;
  };

  struct SimulatedMir {
    std::string device;
    std::string host;
    std::unique_ptr<MirPlatform> platform;
    std::unique_ptr<MirSimServer> server;
  };

  FakeBackend(const BoardConfig& board, const Clock& clock);
  Expected<void> build_http();
  Expected<void> build_gpio();
  Expected<void> build_can();
  Expected<void> build_modbus();
  [[nodiscard]] SimLine sim_line(std::string_view signal);

  BoardConfig board_;
  const Clock& clock_;
  FakeGpio gpio_;
  std::vector<Named<PneumaticValve>> valves_;
  std::vector<Named<PressureSupply>> supplies_;
  std::vector<Named<DockPresenceSensor>> dock_sensors_;
  std::vector<Named<SettableInput>> inputs_;
  VirtualCanNetwork can_network_;
  std::vector<std::pair<std::string, std::unique_ptr<SmartToolSimulator>>> smart_tools_;  // after the network
  std::vector<SimulatedLift> lifts_;
  std::vector<SimulatedMir> mirs_;
  std::vector<std::unique_ptr<SimulatedBadgeReader>> badge_readers_;
};

}  // namespace hubrt::hal::fake
