#include "hubrt/packaging/board_facts.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hubrt/hal/board/board_loader.h"

namespace hubrt::packaging {
namespace {

const std::string kSource = HUBRT_SOURCE_DIR;

hal::BoardConfig board(const std::string& text) {
  auto loaded = hal::load_board_string(text, "test-board.yaml");
  EXPECT_TRUE(loaded) << loaded.error().message;
  return loaded ? std::move(*loaded) : hal::BoardConfig{};
}

config::HubConfig hub(const std::string& type, double rate_hz) {
  config::HubConfig config;
  config.type = type;
  config.name = type;
  config.rate_hz = rate_hz;
  return config;
}

hal::BoardConfig shipped_board(const std::string& name) {
  auto loaded = hal::load_board(kSource + "/boards/" + name + ".yaml");
  EXPECT_TRUE(loaded) << loaded.error().message;
  return loaded ? std::move(*loaded) : hal::BoardConfig{};
}

config::HubConfig shipped_hub(const std::string& type) {
  auto loaded = config::load_hub_config(kSource + "/hubs/" + type + "/" + type + ".yaml");
  EXPECT_TRUE(loaded) << loaded.error().message;
  return loaded ? std::move(*loaded) : config::HubConfig{};
}

TEST(WatchdogForRate, FivePeriodsButAtLeastTwoSecondsRoundedUp) {
  EXPECT_EQ(watchdog_for_rate(10.0), std::chrono::seconds(2));
  EXPECT_EQ(watchdog_for_rate(1000.0), std::chrono::seconds(2));
  EXPECT_EQ(watchdog_for_rate(2.0), std::chrono::seconds(3));  // 2.5 s
  EXPECT_EQ(watchdog_for_rate(1.0), std::chrono::seconds(5));
  EXPECT_EQ(watchdog_for_rate(0.3), std::chrono::seconds(17));  // 16.7 s
}

TEST(PackageFacts, ToolEcuHasGpioAndItsCanInterfaceWithTheBoardsBitrate) {
  auto facts = package_facts(shipped_board("rpi4-tool-ecu"), shipped_hub("tool_ecu"));
  ASSERT_TRUE(facts) << facts.error().message;
  EXPECT_EQ(facts->board, "rpi4-tool-ecu");
  EXPECT_EQ(facts->arch, "arm64");
  EXPECT_EQ(facts->hub, "tool_ecu");
  EXPECT_TRUE(facts->gpio);
  ASSERT_EQ(facts->can.size(), 1U);
  EXPECT_EQ(facts->can[0].interface, "can0");
  EXPECT_EQ(facts->can[0].bitrate, 500000U);
  EXPECT_TRUE(facts->serial_devices.empty());  // the lift drive is on Modbus/TCP
  EXPECT_EQ(facts->watchdog, std::chrono::seconds(2));
}

TEST(PackageFacts, DockEcuHasNoCan) {
  auto facts = package_facts(shipped_board("rpi4-dock-ecu"), shipped_hub("dock_ecu"));
  ASSERT_TRUE(facts) << facts.error().message;
  EXPECT_TRUE(facts->gpio);
  EXPECT_TRUE(facts->can.empty());
}

TEST(PackageFacts, RefusesASimulationBoard) {
  auto facts = package_facts(shipped_board("host-sim"), shipped_hub("dock_ecu"));
  ASSERT_FALSE(facts);
  EXPECT_NE(facts.error().message.find("simulation board"), std::string::npos) << facts.error().message;
}

TEST(PackageFacts, RefusesAHubOfAnotherType) {
  auto facts = package_facts(shipped_board("rpi4-dock-ecu"), hub("tool_ecu", 10.0));
  ASSERT_FALSE(facts);
  EXPECT_NE(facts.error().message.find("'tool_ecu'"), std::string::npos) << facts.error().message;
}

TEST(PackageFacts, RefusesAHostArchitecture) {
  auto facts = package_facts(board(R"(
board: bench
arch: x86_64
hub: dock_ecu
can:
  bus_a: {interface: can1}
)"),
                             hub("dock_ecu", 10.0));
  ASSERT_FALSE(facts);
  EXPECT_NE(facts.error().message.find("x86_64"), std::string::npos) << facts.error().message;
  EXPECT_NE(facts.error().message.find("test-board.yaml"), std::string::npos) << facts.error().message;
}

TEST(PackageFacts, SerialModbusDevicesOnceEachAndNoGpioWithoutLines) {
  auto facts = package_facts(board(R"(
board: serial-only
arch: armhf
hub: tool_ecu
can:
  tool_bus: {interface: can1, bitrate: 250000}
modbus:
  a: {rtu: {device: /dev/ttyUSB0, baud: 9600, parity: N, data_bits: 8, stop_bits: 1}, unit: 2}
  b: {rtu: {device: /dev/ttyUSB0, baud: 9600, parity: N, data_bits: 8, stop_bits: 1}, unit: 3}
  c: {tcp: {host: 10.0.0.2}}
)"),
                             hub("tool_ecu", 1.0));
  ASSERT_TRUE(facts) << facts.error().message;
  EXPECT_FALSE(facts->gpio);
  EXPECT_EQ(facts->serial_devices, std::vector<std::string>{"/dev/ttyUSB0"});
  ASSERT_EQ(facts->can.size(), 1U);
  EXPECT_EQ(facts->can[0].bitrate, 250000U);
  EXPECT_EQ(facts->watchdog, std::chrono::seconds(5));
}

TEST(PackageFacts, JsonCarriesEveryFact) {
  auto facts = package_facts(shipped_board("rpi4-tool-ecu"), shipped_hub("tool_ecu"));
  ASSERT_TRUE(facts) << facts.error().message;
  const auto json = nlohmann::json::parse(to_json(*facts));
  EXPECT_EQ(json.at("board"), "rpi4-tool-ecu");
  EXPECT_EQ(json.at("description"), facts->description);
  EXPECT_EQ(json.at("arch"), "arm64");
  EXPECT_EQ(json.at("hub"), "tool_ecu");
  EXPECT_EQ(json.at("watchdog_sec"), 2);
  EXPECT_EQ(json.at("gpio"), true);
  EXPECT_EQ(json.at("http"), false);
  EXPECT_EQ(json.at("can").at(0).at("interface"), "can0");
  EXPECT_EQ(json.at("can").at(0).at("bitrate"), 500000);
  EXPECT_TRUE(json.at("serial_devices").empty());
  EXPECT_TRUE(json.at("input_devices").empty());
}

TEST(PackageFacts, AnRfidReaderNeedsItsDeviceGroup) {
  auto facts = package_facts(shipped_board("rpi4-operator-hub"), shipped_hub("operator_hub"));
  ASSERT_TRUE(facts) << facts.error().message;
  EXPECT_EQ(facts->input_devices, std::vector<std::string>{"/dev/input/by-id/usb-rfid-reader-event-kbd"});
  EXPECT_TRUE(facts->serial_devices.empty());
  EXPECT_TRUE(facts->gpio);
  EXPECT_FALSE(facts->http);
}

// Only a board with REST devices gets the HTTP client module (and libcpp-httplib's Depends).
TEST(PackageFacts, TheMirBoardNeedsTheHttpModule) {
  auto facts = package_facts(shipped_board("arm64-mir-com"), shipped_hub("mir_com"));
  ASSERT_TRUE(facts) << facts.error().message;
  EXPECT_TRUE(facts->http);
  EXPECT_FALSE(facts->gpio);
}

}  // namespace
}  // namespace hubrt::packaging
