// The boards shipped in boards/: they load, they carry what each hub needs (the signal table in
// boards/README.md), and host-sim.yaml wires every signal exactly as the Raspberry Pi boards do.
#include <set>

#include <gtest/gtest.h>

#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/board/board_requirements.h"

namespace hubrt::hal {
namespace {

const std::string kBoards = HUBRT_BOARDS_DIR;

// The signal table of boards/README.md.
const BoardRequirements kToolEcu{
    "tool_ecu",
    {"tool.button.forward", "tool.button.reverse", "tool.torque_reached", "tool.summary_alarm",
     "tool.arm.home", "tool.arm.pre_home", "tool.arm.out_of_range"},
    {"tool.run_forward", "tool.run_reverse"},
    {"tool_bus"},
    {"lift_drive"},
    {}};
const BoardRequirements kRspEcu{
    "rsp_ecu",
    {"rsp.tool_id.ladder_frame_tool", "rsp.tool_id.smart_tool", "rsp.tool_id.filter_tool",
     "rsp.gripper.confirm_a", "rsp.gripper.confirm_b", "rsp.pressure_ok"},
    {"rsp.lock_valve", "rsp.gripper_valve"},
    {},
    {},
    {}};
const BoardRequirements kDockEcu{
    "dock_ecu",
    {"dock.slot.ladder_frame_tool", "dock.slot.filter_tool", "dock.slot.smart_tool", "dock.slot.spare"},
    {},
    {},
    {},
    {}};

BoardConfig load(const std::string& file) {
  auto board = load_board(kBoards + "/" + file);
  EXPECT_TRUE(board.is_ok()) << board.error().message;
  return board ? std::move(*board) : BoardConfig{};
}

struct ShippedBoard {
  const char* file;
  const BoardRequirements* hub;
};

class ShippedPiBoard : public ::testing::TestWithParam<ShippedBoard> {};

TEST_P(ShippedPiBoard, LoadsAndProvidesWhatItsHubNeeds) {
  const BoardConfig board = load(GetParam().file);
  const auto checked = check_requirements(board, *GetParam().hub);
  EXPECT_TRUE(checked.is_ok()) << checked.error().message;
  EXPECT_EQ(board.arch, "arm64");
  ASSERT_EQ(board.chips.size(), 1U);
  EXPECT_EQ(board.chips[0].selector, "pinctrl-bcm2711");
  EXPECT_FALSE(board.simulation.has_value());
}

TEST_P(ShippedPiBoard, UsesOnlyTheOriginalStationsPins) {
  const BoardConfig board = load(GetParam().file);
  for (const BoardInput& input : board.inputs) {
    EXPECT_TRUE((std::set<unsigned>{5, 6, 12, 13, 16, 19, 22, 23}.contains(input.config.line)))
        << input.config.signal;
  }
  for (const BoardOutput& output : board.outputs) {
    EXPECT_TRUE((std::set<unsigned>{4, 17, 18, 27}.contains(output.config.line))) << output.config.signal;
  }
}

TEST_P(ShippedPiBoard, HostSimWiresEverySignalTheSameWay) {
  const BoardConfig pi = load(GetParam().file);
  const BoardConfig sim = load("host-sim.yaml");
  for (const BoardInput& input : pi.inputs) {
    const BoardInput* twin = sim.find_input(input.config.signal);
    ASSERT_NE(twin, nullptr) << input.config.signal;
    EXPECT_EQ(twin->config.line, input.config.line) << input.config.signal;
    EXPECT_EQ(twin->config.polarity, input.config.polarity) << input.config.signal;
    EXPECT_EQ(twin->config.bias, input.config.bias) << input.config.signal;
    EXPECT_EQ(twin->config.debounce, input.config.debounce) << input.config.signal;
    EXPECT_EQ(twin->config.catch_pulses, input.config.catch_pulses) << input.config.signal;
  }
  for (const BoardOutput& output : pi.outputs) {
    const BoardOutput* twin = sim.find_output(output.config.signal);
    ASSERT_NE(twin, nullptr) << output.config.signal;
    EXPECT_EQ(twin->config.line, output.config.line) << output.config.signal;
    EXPECT_EQ(twin->config.polarity, output.config.polarity) << output.config.signal;
    EXPECT_EQ(twin->config.initial, output.config.initial) << output.config.signal;
    EXPECT_EQ(twin->config.safe, output.config.safe) << output.config.signal;
  }
  for (const BoardCanBus& bus : pi.can) EXPECT_NE(sim.find_can(bus.config.bus), nullptr) << bus.config.bus;
  for (const BoardModbusDevice& device : pi.modbus) {
    EXPECT_NE(sim.find_modbus(device.config.device), nullptr) << device.config.device;
  }
}

INSTANTIATE_TEST_SUITE_P(Boards, ShippedPiBoard,
                         ::testing::Values(ShippedBoard{"rpi4-tool-ecu.yaml", &kToolEcu},
                                           ShippedBoard{"rpi4-rsp-ecu.yaml", &kRspEcu},
                                           ShippedBoard{"rpi4-dock-ecu.yaml", &kDockEcu}),
                         [](const ::testing::TestParamInfo<ShippedBoard>& board) {
                           return board.param.hub->hub;
                         });

TEST(HostSimBoard, CarriesEveryHubAndASimulationSection) {
  const BoardConfig sim = load("host-sim.yaml");
  for (const BoardRequirements* hub : {&kToolEcu, &kRspEcu, &kDockEcu}) {
    const auto checked = check_requirements(sim, *hub);
    EXPECT_TRUE(checked.is_ok()) << checked.error().message;
  }
  ASSERT_TRUE(sim.simulation.has_value());
  EXPECT_EQ(sim.simulation->valves.size(), 2U);
  EXPECT_EQ(sim.simulation->dock_sensors.size(), 4U);
  ASSERT_EQ(sim.simulation->can.size(), 1U);
  EXPECT_EQ(sim.find_can("tool_bus")->config.interface, "vcan-tool");
  ASSERT_EQ(sim.simulation->modbus.size(), 1U);
  const auto& endpoint = std::get<ModbusTcpEndpoint>(sim.find_modbus("lift_drive")->config.endpoint);
  EXPECT_EQ(endpoint.host, "127.0.0.1");
  EXPECT_EQ(endpoint.port, 0);
}

}  // namespace
}  // namespace hubrt::hal
