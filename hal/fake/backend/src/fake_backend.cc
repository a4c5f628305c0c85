#include "hubrt/hal/fake/fake_backend.h"

#include <algorithm>
#include <cassert>

#include <fmt/format.h>

#include "hubrt/hal/common/debounced_input.h"
#include "hubrt/hal/httplib/open_http_module.h"
#include "hubrt/hal/libmodbus/open_libmodbus.h"

namespace hubrt::hal::fake {
namespace {

template <class T>
T* find_named(const auto& items, std::string_view name) noexcept {
  const auto it =
      std::find_if(items.begin(), items.end(), [&](const auto& item) { return item.name == name; });
  return it == items.end() ? nullptr : it->item;
}

bool loopback(const std::string& host) {
  return host.starts_with("127.");
}

}  // namespace

FakeBackend::FakeBackend(const BoardConfig& board, const Clock& clock)
    : board_(board), clock_(clock), gpio_(clock), can_network_(clock) {}

FakeBackend::~FakeBackend() = default;

Expected<std::unique_ptr<FakeBackend>> FakeBackend::create(const BoardConfig& board, const Clock& clock) {
  if (!board.simulation) {
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("{}: board {} has no simulation section: the fake backend does not know which "
                    "simulators to attach (use boards/host-sim.yaml or add one)",
                    board.file, board.name));
  }
  std::unique_ptr<FakeBackend> backend(new FakeBackend(board, clock));
  if (auto ok = backend->build_gpio(); !ok) return std::move(ok).error();
  if (auto ok = backend->build_can(); !ok) return std::move(ok).error();
  if (auto ok = backend->build_modbus(); !ok) return std::move(ok).error();
  if (auto ok = backend->build_http(); !ok) return std::move(ok).error();
  for (const BoardBadgeReader& reader : board.badge_readers) {
    backend->badge_readers_.push_back(std::make_unique<SimulatedBadgeReader>(reader.config));
  }
  return backend;
}

SimLine FakeBackend::sim_line(std::string_view signal) {
  const Result<Wiring> wired = wiring(signal);
  assert(wired.is_ok());  // the loader checked every simulator's signals
  return SimLine(*wired.value().chip, wired.value().line, wired.value().polarity);
}

Expected<void> FakeBackend::build_gpio() {
  const SimulationConfig& sim = *board_.simulation;
  for (const BoardGpioChip& chip : board_.chips) gpio_.add_chip(chip.selector, sim.chip_lines);

  for (const SimPressureSupplyConfig& config : sim.pressure_supplies) {
    auto& supply = gpio_.add_simulator(
        std::make_unique<PressureSupply>(gpio_, sim_line(config.switch_input), config.ok));
    supplies_.push_back({config.name, &supply});
  }
  for (const SimValveConfig& config : sim.valves) {
    std::vector<SimLine> confirms;
    for (const std::string& confirm : config.confirms) confirms.push_back(sim_line(confirm));
    PressureSupply* supply =
        config.supply.empty() ? nullptr : find_named<PressureSupply>(supplies_, config.supply);
    auto& valve = gpio_.add_simulator(std::make_unique<PneumaticValve>(
        gpio_, config.output, sim_line(config.output), std::move(confirms), supply, config.actuation));
    valves_.push_back({config.output, &valve});
  }
  for (const SimDockSensorConfig& config : sim.dock_sensors) {
    auto& sensor = gpio_.add_simulator(
        std::make_unique<DockPresenceSensor>(gpio_, sim_line(config.input), config.bounce, config.occupied));
    dock_sensors_.push_back({config.input, &sensor});
  }
  // Whatever no simulator drives is a plain input the test (or a bridge) sets.
  const auto driven = [&](const std::string& signal) {
    if (find_named<DockPresenceSensor>(dock_sensors_, signal) != nullptr) return true;
    for (const SimPressureSupplyConfig& s : sim.pressure_supplies) {
      if (s.switch_input == signal) return true;
    }
    for (const SimValveConfig& v : sim.valves) {
      if (std::find(v.confirms.begin(), v.confirms.end(), signal) != v.confirms.end()) return true;
    }
    return false;
  };
  for (const BoardInput& input : board_.inputs) {
    if (driven(input.config.signal)) continue;
    const auto level = std::find_if(sim.inputs.begin(), sim.inputs.end(),
                                    [&](const SimInputLevel& l) { return l.input == input.config.signal; });
    const bool active = level != sim.inputs.end() && level->active;
    auto& settable =
        gpio_.add_simulator(std::make_unique<SettableInput>(gpio_, sim_line(input.config.signal), active));
    inputs_.push_back({input.config.signal, &settable});
  }
  return {};
}

Expected<void> FakeBackend::build_can() {
  for (const SimCanDevice& device : board_.simulation->can) {
    const BoardCanBus* bus = board_.find_can(device.bus);
    assert(bus != nullptr);  // checked by the loader
    SmartToolSimulatorConfig config;
    config.interface = bus->config.interface;
    if (device.node_id != 0) config.node_id = static_cast<std::uint8_t>(device.node_id);
    auto tool = SmartToolSimulator::create(can_network_, config);
    if (!tool) {
      Error error = std::move(tool).error();
      error.message =
          fmt::format("{}: simulated smart tool on '{}': {}", board_.file, device.bus, error.message);
      return error;
    }
    smart_tools_.emplace_back(device.bus, std::move(*tool));
  }
  return {};
}

Expected<void> FakeBackend::build_modbus() {
  for (const SimModbusDevice& device : board_.simulation->modbus) {
    const BoardModbusDevice* modbus = board_.find_modbus(device.device);
    assert(modbus != nullptr);  // checked by the loader, TCP included
    const auto& tcp = std::get<ModbusTcpEndpoint>(modbus->config.endpoint);
    if (!loopback(tcp.host)) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: simulated Modbus device '{}' must listen on a loopback address "
                                    "(127.x.x.x), not '{}'",
                                    board_.file, device.device, tcp.host));
    }
    SimulatedLift lift;
    lift.device = device.device;
    lift.host = tcp.host;
    LiftDriveConfig drive_config;
    drive_config.unit_id = modbus->config.unit_id;
    lift.drive = std::make_unique<LiftDrive>(drive_config, clock_.now().mono);
    auto server = LiftDriveServer::start(*lift.drive, clock_, LiftDriveServerOptions{tcp.host, tcp.port});
    if (!server) {
      Error error = std::move(server).error();
      error.message =
          fmt::format("{}: lift drive simulator for '{}': {}", board_.file, device.device, error.message);
      return error;
    }
    lift.server = std::move(*server);
    lifts_.push_back(std::move(lift));
  }
  return {};
}

Expected<void> FakeBackend::build_http() {
  for (const SimHttpDevice& device : board_.simulation->http) {
    const BoardHttpDevice* http = board_.find_http(device.device);
    assert(http != nullptr);  // checked by the loader
    if (!loopback(http->config.host)) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: simulated HTTP device '{}' must listen on a loopback address "
                                    "(127.x.x.x), not '{}'",
                                    board_.file, device.device, http->config.host));
    }
    MirPlatformConfig config;
    config.robot_name = device.robot_name;
    config.authorization = http->config.authorization;
    config.speed_m_s = device.speed_m_s;
    const SimMirPosition& start = device.positions.front();
    config.start_x = start.x;
    config.start_y = start.y;
    config.start_yaw_deg = start.yaw_deg;
    SimulatedMir mir;
    mir.device = device.device;
    mir.host = http->config.host;
    mir.platform = std::make_unique<MirPlatform>(config, clock_.now().mono);
    for (const SimMirPosition& p : device.positions) mir.platform->add_position(p.name, p.x, p.y, p.yaw_deg);
    MirSimServerOptions options;
    options.address = http->config.host;
    options.port = http->config.port;
    options.base_path = http->config.base_path;
    auto server = load_mir_sim_server(default_mir_sim_module_paths(), *mir.platform, clock_, options);
    if (!server) {
      Error error = std::move(server).error();
      error.message =
          fmt::format("{}: MiR simulator for '{}': {}", board_.file, device.device, error.message);
      return error;
    }
    mir.server = std::move(*server);
    mirs_.push_back(std::move(mir));
  }
  return {};
}

Expected<std::unique_ptr<DigitalInput>> FakeBackend::open_input(const DigitalInputConfig& config) {
  auto input = gpio_.open_input(config);
  if (!input) return input;
  return debounce(std::move(*input), config.debounce);
}

Expected<std::unique_ptr<DigitalOutput>> FakeBackend::open_output(const DigitalOutputConfig& config) {
  return gpio_.open_output(config);
}

Expected<std::unique_ptr<CanBus>> FakeBackend::open_can(const CanConfig& config) {
  auto node = can_network_.open(config);
  if (!node) return std::move(node).error();
  return std::unique_ptr<CanBus>(std::move(*node));
}

Expected<std::unique_ptr<ModbusClient>> FakeBackend::open_modbus(const ModbusConfig& config) {
  const auto lift = std::find_if(lifts_.begin(), lifts_.end(),
                                 [&](const SimulatedLift& l) { return l.device == config.device; });
  if (lift == lifts_.end()) {
    return make_error(ErrorCode::kNotFound, fmt::format("{}: no simulator for this Modbus device on board {}",
                                                        config.device, board_.name));
  }
  ModbusConfig connected = config;
  connected.endpoint = ModbusTcpEndpoint{lift->host, lift->server->port()};
  return libmodbus::open_libmodbus(connected, clock_);
}

Expected<std::unique_ptr<HttpClient>> FakeBackend::open_http(const HttpConfig& config) {
  const auto mir = std::find_if(mirs_.begin(), mirs_.end(),
                                [&](const SimulatedMir& m) { return m.device == config.device; });
  if (mir == mirs_.end()) {
    return make_error(ErrorCode::kNotFound, fmt::format("{}: no simulator for this HTTP device on board {}",
                                                        config.device, board_.name));
  }
  HttpConfig connected = config;
  connected.host = mir->host;
  connected.port = mir->server->port();
  return httplib_client::open_http_module_client(httplib_client::default_http_module_paths(), connected);
}

MirPlatform* FakeBackend::mir_platform(std::string_view http_device) noexcept {
  for (SimulatedMir& mir : mirs_) {
    if (mir.device == http_device) return mir.platform.get();
  }
  return nullptr;
}

MirSimServer* FakeBackend::mir_server(std::string_view http_device) noexcept {
  for (SimulatedMir& mir : mirs_) {
    if (mir.device == http_device) return mir.server.get();
  }
  return nullptr;
}

Expected<std::unique_ptr<BadgeReader>> FakeBackend::open_badge_reader(const BadgeReaderConfig& config) {
  SimulatedBadgeReader* reader = badge_reader(config.reader);
  if (reader == nullptr) {
    return make_error(
        ErrorCode::kNotFound,
        fmt::format("{}: no simulated RFID reader of this name on board {}", config.reader, board_.name));
  }
  return reader->open();
}

SimulatedBadgeReader* FakeBackend::badge_reader(std::string_view reader) noexcept {
  for (auto& simulated : badge_readers_) {
    if (simulated->config().reader == reader) return simulated.get();
  }
  return nullptr;
}

PneumaticValve* FakeBackend::valve(std::string_view output_signal) noexcept {
  return find_named<PneumaticValve>(valves_, output_signal);
}

PressureSupply* FakeBackend::pressure_supply(std::string_view name) noexcept {
  return find_named<PressureSupply>(supplies_, name);
}

DockPresenceSensor* FakeBackend::dock_sensor(std::string_view input_signal) noexcept {
  return find_named<DockPresenceSensor>(dock_sensors_, input_signal);
}

SettableInput* FakeBackend::input(std::string_view input_signal) noexcept {
  return find_named<SettableInput>(inputs_, input_signal);
}

SmartToolSimulator* FakeBackend::smart_tool(std::string_view can_bus) noexcept {
  for (auto& [bus, tool] : smart_tools_) {
    if (bus == can_bus) return tool.get();
  }
  return nullptr;
}

LiftDrive* FakeBackend::lift_drive(std::string_view modbus_device) noexcept {
  for (SimulatedLift& lift : lifts_) {
    if (lift.device == modbus_device) return lift.drive.get();
  }
  return nullptr;
}

LiftDriveServer* FakeBackend::lift_drive_server(std::string_view modbus_device) noexcept {
  for (SimulatedLift& lift : lifts_) {
    if (lift.device == modbus_device) return lift.server.get();
  }
  return nullptr;
}

Result<FakeBackend::Wiring> FakeBackend::wiring(std::string_view signal) noexcept {
  const DigitalInputConfig* in = nullptr;
  const DigitalOutputConfig* out = nullptr;
  if (const BoardInput* input = board_.find_input(signal)) in = &input->config;
  if (const BoardOutput* output = board_.find_output(signal)) out = &output->config;
  if (in == nullptr && out == nullptr) return Status(ErrorCode::kNotFound);
  const std::string& chip_name = in != nullptr ? in->chip : out->chip;
  FakeGpioChip* chip = gpio_.chip(chip_name);
  if (chip == nullptr) return Status(ErrorCode::kNotFound);
  return Wiring{chip, in != nullptr ? in->line : out->line, in != nullptr ? in->polarity : out->polarity};
}

Result<bool> FakeBackend::active(std::string_view signal) noexcept {
  const Result<Wiring> wired = wiring(signal);
  if (!wired.is_ok()) return wired.status();
  const Result<bool> high = wired.value().chip->level(wired.value().line);
  if (!high.is_ok()) return high;
  return high.value() != (wired.value().polarity == Polarity::kActiveLow);
}

std::vector<FakeBackend::SignalChange> FakeBackend::history(std::string_view signal) {
  const Result<Wiring> wired = wiring(signal);
  if (!wired.is_ok()) return {};
  const bool active_low = wired.value().polarity == Polarity::kActiveLow;
  std::vector<SignalChange> changes;
  for (const LevelChange& change : wired.value().chip->history(wired.value().line)) {
    changes.push_back(SignalChange{change.at, change.high != active_low});
  }
  return changes;
}

}  // namespace hubrt::hal::fake
