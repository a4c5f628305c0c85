#include "hubrt/hal/board/board_loader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hubrt::hal {
namespace {

using std::chrono::milliseconds;
using ::testing::ElementsAre;

constexpr const char* kBoard = R"(board: test-board
description: a board for the loader test
arch: armhf
hub: dock_ecu
gpio:
  chips:
    main: {label: pinctrl-bcm2711}
    expander: {path: /dev/gpiochip2}
  inputs:
    dock.slot.a: {chip: main, line: 5, polarity: active_low, bias: pull_up, debounce_ms: 20}
    dock.slot.b: {chip: expander, line: 5, catch_pulses: true}
  outputs:
    dock.lamp: {chip: main, line: 4, polarity: active_low, safe: true}
    dock.horn: {chip: main, line: 17, initial: true, safe: false}
can:
  tool_bus:
    interface: can1
    bitrate: 250000
    filters:
      - {id: 0x181, mask: 0x7F0}
      - {id: 0x18FF0001, extended: true}
modbus:
  lift_drive: {tcp: {host: 192.168.10.20}, unit: 3, timeout_ms: 250, reconnect_ms: 1000}
  pump: {rtu: {device: /dev/ttyUSB1, baud: 9600, parity: N, stop_bits: 2}}
)";

TEST(BoardLoader, ReadsEverySection) {
  auto loaded = load_board_string(kBoard, "boards/test-board.yaml");
  ASSERT_TRUE(loaded.is_ok()) << loaded.error().message;
  const BoardConfig& board = *loaded;
  EXPECT_EQ(board.file, "boards/test-board.yaml");
  EXPECT_EQ(board.name, "test-board");
  EXPECT_EQ(board.arch, "armhf");
  EXPECT_THAT(board.hubs, ElementsAre("dock_ecu"));
  EXPECT_FALSE(board.simulation.has_value());

  ASSERT_EQ(board.chips.size(), 2U);
  EXPECT_EQ(board.chips[0].kind, GpioChipSelectorKind::kLabel);
  EXPECT_EQ(board.chips[1].selector, "/dev/gpiochip2");

  const BoardInput* a = board.find_input("dock.slot.a");
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(a->config.chip, "pinctrl-bcm2711");
  EXPECT_EQ(a->chip_alias, "main");
  EXPECT_EQ(a->config.line, 5U);
  EXPECT_EQ(a->config.polarity, Polarity::kActiveLow);
  EXPECT_EQ(a->config.bias, Bias::kPullUp);
  EXPECT_EQ(a->config.debounce, milliseconds(20));
  EXPECT_FALSE(a->config.catch_pulses);
  EXPECT_EQ(a->where.line, 10);
  const BoardInput* b = board.find_input("dock.slot.b");
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->config.chip, "/dev/gpiochip2");
  EXPECT_EQ(b->config.polarity, Polarity::kActiveHigh);
  EXPECT_EQ(b->config.bias, Bias::kAsIs);
  EXPECT_TRUE(b->config.catch_pulses);

  const BoardOutput* lamp = board.find_output("dock.lamp");
  ASSERT_NE(lamp, nullptr);
  EXPECT_TRUE(lamp->config.safe);
  EXPECT_TRUE(lamp->config.initial);  // defaults to the safe level
  EXPECT_EQ(lamp->config.polarity, Polarity::kActiveLow);
  const BoardOutput* horn = board.find_output("dock.horn");
  ASSERT_NE(horn, nullptr);
  EXPECT_TRUE(horn->config.initial);
  EXPECT_FALSE(horn->config.safe);

  const BoardCanBus* bus = board.find_can("tool_bus");
  ASSERT_NE(bus, nullptr);
  EXPECT_EQ(bus->config.interface, "can1");
  EXPECT_EQ(bus->config.bitrate, 250'000U);
  ASSERT_EQ(bus->config.filters.size(), 2U);
  EXPECT_EQ(bus->config.filters[0].id, 0x181U);
  EXPECT_EQ(bus->config.filters[0].mask, 0x7F0U);
  EXPECT_FALSE(bus->config.filters[0].extended);
  EXPECT_EQ(bus->config.filters[1].mask, 0x1FFFFFFFU);
  EXPECT_TRUE(bus->config.filters[1].extended);

  const BoardModbusDevice* lift = board.find_modbus("lift_drive");
  ASSERT_NE(lift, nullptr);
  const auto& tcp = std::get<ModbusTcpEndpoint>(lift->config.endpoint);
  EXPECT_EQ(tcp.host, "192.168.10.20");
  EXPECT_EQ(tcp.port, 502);
  EXPECT_EQ(lift->config.unit_id, 3);
  EXPECT_EQ(lift->config.response_timeout, milliseconds(250));
  EXPECT_EQ(lift->config.reconnect_interval, milliseconds(1000));
  const BoardModbusDevice* pump = board.find_modbus("pump");
  ASSERT_NE(pump, nullptr);
  const auto& rtu = std::get<ModbusRtuEndpoint>(pump->config.endpoint);
  EXPECT_EQ(rtu.device, "/dev/ttyUSB1");
  EXPECT_EQ(rtu.baud, 9600U);
  EXPECT_EQ(rtu.parity, 'N');
  EXPECT_EQ(rtu.data_bits, 8);
  EXPECT_EQ(rtu.stop_bits, 2);
  EXPECT_EQ(pump->config.unit_id, 1);
  EXPECT_EQ(pump->config.response_timeout, milliseconds(100));
}

constexpr const char* kSimBoard = R"(board: sim
arch: x86_64
hub: [rsp_ecu, dock_ecu]
gpio:
  chips:
    rsp: {label: sim-rsp}
  inputs:
    rsp.confirm: {chip: rsp, line: 1}
    rsp.pressure_ok: {chip: rsp, line: 2}
    dock.slot.a: {chip: rsp, line: 3, debounce_ms: 20}
    rsp.tool_id.a: {chip: rsp, line: 4}
  outputs:
    rsp.valve: {chip: rsp, line: 0, safe: false}
can:
  tool_bus: {interface: vcan-tool}
modbus:
  lift_drive: {tcp: {host: 127.0.0.1, port: 0}}
simulation:
  chip_lines: 8
  pressure_supplies:
    air: {switch: rsp.pressure_ok, ok: false}
  valves:
    rsp.valve: {confirms: [rsp.confirm], supply: air, actuation_ms: 150}
  dock_sensors:
    dock.slot.a: {bounce_ms: 15, occupied: true}
  inputs:
    rsp.tool_id.a: true
  can:
    tool_bus: {simulator: smart_tool, node_id: 5}
  modbus:
    lift_drive: {simulator: lift_drive}
)";

TEST(BoardLoader, ReadsTheSimulationSection) {
  auto loaded = load_board_string(kSimBoard, "sim.yaml");
  ASSERT_TRUE(loaded.is_ok()) << loaded.error().message;
  const BoardConfig& board = *loaded;
  EXPECT_THAT(board.hubs, ElementsAre("rsp_ecu", "dock_ecu"));
  EXPECT_TRUE(board.wired_for("dock_ecu"));
  EXPECT_FALSE(board.wired_for("tool_ecu"));
  EXPECT_EQ(std::get<ModbusTcpEndpoint>(board.modbus.at(0).config.endpoint).port, 0);
  ASSERT_TRUE(board.simulation.has_value());
  const SimulationConfig& sim = *board.simulation;
  EXPECT_EQ(sim.chip_lines, 8U);
  ASSERT_EQ(sim.pressure_supplies.size(), 1U);
  EXPECT_EQ(sim.pressure_supplies[0].name, "air");
  EXPECT_EQ(sim.pressure_supplies[0].switch_input, "rsp.pressure_ok");
  EXPECT_FALSE(sim.pressure_supplies[0].ok);
  ASSERT_EQ(sim.valves.size(), 1U);
  EXPECT_EQ(sim.valves[0].output, "rsp.valve");
  EXPECT_THAT(sim.valves[0].confirms, ElementsAre("rsp.confirm"));
  EXPECT_EQ(sim.valves[0].supply, "air");
  EXPECT_EQ(sim.valves[0].actuation, milliseconds(150));
  ASSERT_EQ(sim.dock_sensors.size(), 1U);
  EXPECT_EQ(sim.dock_sensors[0].bounce, milliseconds(15));
  EXPECT_TRUE(sim.dock_sensors[0].occupied);
  ASSERT_EQ(sim.inputs.size(), 1U);
  EXPECT_EQ(sim.inputs[0].input, "rsp.tool_id.a");
  EXPECT_TRUE(sim.inputs[0].active);
  ASSERT_EQ(sim.can.size(), 1U);
  EXPECT_EQ(sim.can[0].simulator, "smart_tool");
  EXPECT_EQ(sim.can[0].node_id, 5U);
  ASSERT_EQ(sim.modbus.size(), 1U);
  EXPECT_EQ(sim.modbus[0].simulator, "lift_drive");
}

TEST(BoardLoader, MissingFileIsNotFound) {
  auto loaded = load_board("no/such/board.yaml");
  ASSERT_FALSE(loaded.is_ok());
  EXPECT_EQ(loaded.error().code, ErrorCode::kNotFound);
  EXPECT_THAT(loaded.error().message, ::testing::StartsWith("no/such/board.yaml: does not exist"));
}

}  // namespace
}  // namespace hubrt::hal
