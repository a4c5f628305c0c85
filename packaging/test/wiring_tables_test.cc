#include "hubrt/packaging/wiring_tables.h"

#include <gtest/gtest.h>

#include "hubrt/hal/board/board_loader.h"

namespace hubrt::packaging {
namespace {

hal::BoardConfig loaded_board(const std::string& text) {
  auto loaded = hal::load_board_string(text, "test-board.yaml");
  EXPECT_TRUE(loaded) << loaded.error().message;
  return loaded ? std::move(*loaded) : hal::BoardConfig{};
}

TEST(RpiHeaderPin, MapsBcmLinesOfTheSocChipsToHeaderPins) {
  EXPECT_EQ(rpi_header_pin("pinctrl-bcm2711", 4), 7);
  EXPECT_EQ(rpi_header_pin("pinctrl-bcm2711", 17), 11);
  EXPECT_EQ(rpi_header_pin("pinctrl-bcm2711", 27), 13);
  EXPECT_EQ(rpi_header_pin("pinctrl-bcm2835", 0), 27);
  EXPECT_EQ(rpi_header_pin("pinctrl-rp1", 21), 40);
}

TEST(RpiHeaderPin, NoPinForOtherChipsOrLinesOffTheHeader) {
  EXPECT_EQ(rpi_header_pin("pinctrl-bcm2711", 28), std::nullopt);
  EXPECT_EQ(rpi_header_pin("sim-dock", 5), std::nullopt);
  EXPECT_EQ(rpi_header_pin("gpiochip0", 5), std::nullopt);
}

TEST(WiringTables, GpioRowsSortedByLineWithEverythingAWirerNeeds) {
  const std::string tables = wiring_tables(loaded_board(R"(
board: test-pi
description: A test Pi
arch: arm64
hub: rsp_ecu
gpio:
  chips:
    main: {label: pinctrl-bcm2711}
  inputs:
    b.button: {chip: main, line: 6, polarity: active_low, bias: pull_up, debounce_ms: 20}
    b.pulse:  {chip: main, line: 12, catch_pulses: true}
  outputs:
    b.valve: {chip: main, line: 4, safe: false, initial: true}
)"));
  EXPECT_EQ(tables,
            "### test-pi\n\n"
            "A test Pi. Architecture `arm64`, hub `rsp_ecu`.\n\n"
            "GPIO chip `main`: label `pinctrl-bcm2711`.\n\n"
            "| header pin | GPIO | signal | direction | active | bias | notes |\n"
            "|---|---|---|---|---|---|---|\n"
            "| 7 | BCM 4 | `b.valve` | output | high | — | starts active; safe: inactive |\n"
            "| 31 | BCM 6 | `b.button` | input | low | pull-up | debounce 20 ms |\n"
            "| 32 | BCM 12 | `b.pulse` | input | high | as is | short pulses caught |\n");
}

TEST(WiringTables, OtherChipsByAliasAndLineAndBusTables) {
  const std::string tables = wiring_tables(loaded_board(R"(
board: test-expander
arch: armhf
hub: tool_ecu
gpio:
  chips:
    exp: {name: gpiochip2}
  outputs:
    x.out: {chip: exp, line: 3, safe: true}
can:
  tool_bus: {interface: can1, bitrate: 125000}
modbus:
  drive: {rtu: {device: /dev/ttyAMA0, baud: 19200, parity: E, data_bits: 8, stop_bits: 1}, unit: 7, timeout_ms: 250}
  plc: {tcp: {host: 10.0.0.9, port: 1502}}
)"));
  EXPECT_NE(tables.find("GPIO chip `exp`: kernel name `gpiochip2`."), std::string::npos) << tables;
  EXPECT_NE(tables.find("| — | `exp` line 3 | `x.out` | output | high | — | starts active; safe: active |"),
            std::string::npos)
      << tables;
  EXPECT_NE(tables.find("| `tool_bus` | `can1` | 125 kbit/s |"), std::string::npos) << tables;
  EXPECT_NE(tables.find("| `drive` | RTU `/dev/ttyAMA0`, 19200 baud, 8E1 | 7 | 250 ms |"), std::string::npos)
      << tables;
  EXPECT_NE(tables.find("| `plc` | TCP 10.0.0.9:1502 | 1 | 100 ms |"), std::string::npos) << tables;
}

TEST(WiringSection, LeavesOutSimulationBoardsAndSortsByName) {
  std::vector<hal::BoardConfig> boards;
  for (const char* name : {"zeta", "alpha"}) {
    boards.push_back(loaded_board(std::string("board: ") + name + R"(
arch: arm64
hub: dock_ecu
can:
  bus: {interface: can0}
)"));
  }
  boards.push_back(loaded_board(R"(
board: beta-sim
arch: x86_64
hub: dock_ecu
gpio:
  chips:
    dock: {label: sim-dock}
  inputs:
    dock.slot.spare: {chip: dock, line: 13}
simulation:
  inputs:
    dock.slot.spare: true
)"));
  const std::string section = wiring_section(boards);
  const auto alpha = section.find("### alpha");
  const auto zeta = section.find("### zeta");
  ASSERT_NE(alpha, std::string::npos) << section;
  ASSERT_NE(zeta, std::string::npos) << section;
  EXPECT_LT(alpha, zeta);
  EXPECT_EQ(section.find("beta-sim"), std::string::npos) << section;
}

TEST(ReplaceGeneratedSection, ReplacesOnlyBetweenTheMarkersAndIsStable) {
  const std::string doc = "# Guide\n\ntext before\n" + std::string(kBeginMarker) + "\nold tables\n" +
                          std::string(kEndMarker) + "\ntext after\n";
  auto updated = replace_generated_section(doc, "new tables\n");
  ASSERT_TRUE(updated) << updated.error().message;
  EXPECT_EQ(*updated, "# Guide\n\ntext before\n" + std::string(kBeginMarker) + "\n\nnew tables\n\n" +
                          std::string(kEndMarker) + "\ntext after\n");
  auto again = replace_generated_section(*updated, "new tables\n");
  ASSERT_TRUE(again) << again.error().message;
  EXPECT_EQ(*again, *updated);
}

TEST(ReplaceGeneratedSection, MissingOrMisplacedMarkersAreErrors) {
  const std::string begin(kBeginMarker);
  const std::string end(kEndMarker);
  EXPECT_FALSE(replace_generated_section("no markers\n", "x"));
  EXPECT_FALSE(replace_generated_section(begin + "\nonly the start\n", "x"));
  EXPECT_FALSE(replace_generated_section(end + "\n" + begin + "\n", "x"));
  EXPECT_FALSE(replace_generated_section(begin + "\n" + end + "\n" + begin + "\n" + end + "\n", "x"));
  // A marker quoted inside a line is not a marker.
  EXPECT_FALSE(replace_generated_section("see `" + begin + "`\n" + end + "\n", "x"));
}

}  // namespace
}  // namespace hubrt::packaging
